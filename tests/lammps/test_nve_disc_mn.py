"""fix nve/disc/mn: the 2D disk integrator with gravity in one pass, against LAMMPS's fix
nve/sphere disc + fix gravity (and fix nve/ab2 + fix gravity), against the analytic motion of
a falling and a rolling disk, and its bad inputs."""
import math
import re

import numpy as np
import pytest

from granmn_run import HEADER, PLUGIN, law, run_lammps
from pile_decks import KN, E, BETA, PILE

TILT = (0.3, -1.0)    # the pile's gravity direction (magnitude 1)


def pile_deck(integration, steps, wall_first):
    """The 48-disk pile of pile_decks (fixed bumps, a floor and a ceiling, mu = 0.5) falling
    and starting to flow under tilted gravity, `steps` steps of tau_c/50, the state dumped at
    full precision. `integration`: the integrator fix (and `gravity` for fix gravity)."""
    dt = law(KN, E, BETA)["tau_c"] / 50
    fixes = {"gravity": f"fix gravity mobile gravity 1.0 vector {TILT[0]} {TILT[1]} 0",
             "floor": "fix floor mobile wall/gran/mn yplane 0.0 11.5"}
    lines = [f"fix integrate mobile {integration[0]}"]
    order = ["floor", "gravity"] if wall_first else ["gravity", "floor"]
    lines += [fixes[name] for name in order if name in integration[1:] or name == "floor"]
    return PILE + f"""
pair_style gran/mn kn {KN} e {E} beta {BETA} mu 0.5 wall_types 2
pair_coeff * *
timestep {dt!r}
{chr(10).join(lines)}
run {steps}
write_dump all custom final.txt id x y vx vy omegaz modify sort id format float %.17g
"""


GRAVITY = f"gravity 1.0 {TILT[0]} {TILT[1]}"


def final_state(tmp_path, name, integration, steps=3000, wall_first=True, edit=lambda d: d):
    """The pile's final state (x, y, vx, vy, omegaz) under `integration`, its deck changed by
    edit(deck)."""
    run = run_lammps(edit(pile_deck(integration, steps, wall_first)), tmp_path / name)
    a = run.atoms()
    return np.column_stack([a[k] for k in ("x", "y", "vx", "vy", "omegaz")])


def test_fused_verlet_is_nve_sphere_disc_plus_gravity_to_the_bit(tmp_path):
    """The same floating-point operations in the same order: velocity Verlet's half kicks with
    dt/2m and dt/(2 I) (computed once, as fix nve/sphere disc computes them at every step), the
    body force m g added to the step's force sum. With the wall's force summed before gravity
    (fix floor defined first), 3000 steps of a flowing pile (~1700 contacts made) end in the
    same state to the last bit; any other operation (a kick missing or doubled, z or a factor
    rounded otherwise) would show in the last digits at once and grow in the pile."""
    separate = final_state(tmp_path, "separate", ("nve/sphere disc", "gravity"))
    fused = final_state(tmp_path, "fused", (f"nve/disc/mn {GRAVITY}",))
    assert np.array_equal(separate, fused), np.abs(separate - fused).max()


def test_fused_verlet_differs_only_by_the_order_of_the_force_sum(tmp_path):
    """With fix gravity defined before the wall (as the decks did), LAMMPS sums
    (pair + m g) + wall, the fused fix (pair + wall) + m g: one rounding apart for the disks on
    the wall, which the flow then amplifies. Over 500 steps (a few contacts with the floor
    made) the states agree to 1e-12 of their scale, far below any error of the scheme
    (dt^2 a ~ 1e-9 per step here)."""
    separate = final_state(tmp_path, "separate", ("nve/sphere disc", "gravity"), 500, False)
    fused = final_state(tmp_path, "fused", (f"nve/disc/mn {GRAVITY}",), 500, False)
    scale = np.abs(separate).max(axis=0)
    assert np.all(np.abs(separate - fused) <= 1e-12 * scale), np.abs(separate - fused).max(axis=0)


def test_fused_ab2_is_nve_ab2_plus_gravity_to_the_bit(tmp_path):
    """The ab2 scheme's acceleration is nve/ab2's with a fix gravity defined after the wall:
    f/m, with m g added to f after the other forces, the same operations. 3000 steps of the
    flowing pile end in the same state to the last bit."""
    separate = final_state(tmp_path, "separate", ("nve/ab2", "gravity"))
    fused = final_state(tmp_path, "fused", (f"nve/disc/mn scheme ab2 {GRAVITY}",))
    assert np.array_equal(separate, fused), np.abs(separate - fused).max()


def builds_and_state(tmp_path, name, fix, neighbor, nprocs=1, steps=3000, extra=""):
    """The pile under `fix` (and the fixes `extra`) with the neighbour settings `neighbor`:
    LAMMPS's count of list builds and what it says of dangerous builds, and the final state."""
    deck = pile_deck((fix,), steps, True).replace("timestep", f"{neighbor}\n{extra}\ntimestep")
    run = run_lammps(deck, tmp_path / name, nprocs=nprocs)
    builds = int(re.search(r"Neighbor list builds = (\d+)", run.output).group(1))
    # (with check no LAMMPS counts none: "Dangerous builds not checked")
    dangerous = re.search(r"Dangerous builds (= \d+|not checked)", run.output).group(1)
    # pair_style gran/mn's warning about once yes is for a run where no fix asks for builds
    assert ("only at the start of a run" in run.output) == ("once yes" in neighbor and
                                                            "neigh_check yes" not in fix)
    a = run.atoms()
    return (builds, dangerous), np.column_stack([a[k] for k in ("x", "y", "vx", "vy", "omegaz")])


LAMMPS_CHECK = "neigh_modify delay 0 every 1 check yes"
OWN_CHECK = "neigh_modify delay 0 every 1 check yes once yes"


@pytest.mark.parametrize("scheme,nprocs", [("verlet", 1), ("ab2", 1), ("verlet", 2)])
def test_neigh_check_builds_the_lists_at_the_steps_lammps_would(tmp_path, scheme, nprocs):
    """neigh_check yes with neigh_modify once yes: the fix's own test (a disk moved more than
    half the skin since the last build) asks for the builds, LAMMPS tests nothing. 3000 steps
    of the flowing pile (skin 0.1): the same number of builds as LAMMPS's own test at every
    step and the same final state to the last bit (a build one step early or late re-sorts
    the neighbours, hence the order of the force sums, and shows in the last digits); on two
    processes too (the decision is reduced over them). Without the fix's test `once yes`
    builds no list after the first: the pile would fall through itself."""
    fix = f"nve/disc/mn scheme {scheme} {GRAVITY}"
    builds, state = builds_and_state(tmp_path, "lammps", fix, LAMMPS_CHECK, nprocs)
    own_builds, own_state = builds_and_state(tmp_path, "own", f"{fix} neigh_check yes",
                                             OWN_CHECK, nprocs)
    print(f"{builds} (builds, dangerous) with LAMMPS's test, {own_builds} with the fix's")
    assert builds[0] > 5
    assert own_builds == builds
    assert np.array_equal(state, own_state), np.abs(state - own_state).max()


@pytest.mark.parametrize("settings", ["delay 0 every 10 check yes", "delay 10 every 5 check yes",
                                      "delay 5 every 1 check yes", "delay 0 every 20 check no"])
def test_neigh_check_decides_as_lammps_with_every_and_delay(tmp_path, settings):
    """neigh_check yes takes LAMMPS's decisions (Neighbor::decide): it looks only at steps at
    least `delay` after the last build and a multiple of `every` since, and there builds (check
    no) or tests the distance (check yes). It tested at every step: 187 builds against
    LAMMPS's 150 with every 10, a trajectory of its own. The same builds, dangerous builds and
    final state to the bit as LAMMPS's own decisions."""
    fix = f"nve/disc/mn {GRAVITY}"
    builds, state = builds_and_state(tmp_path, "lammps", fix, f"neigh_modify {settings}")
    own_builds, own_state = builds_and_state(tmp_path, "own", f"{fix} neigh_check yes",
                                             f"neigh_modify {settings} once yes")
    print(f"{settings}: {builds} (builds, dangerous) with LAMMPS's decisions, {own_builds} "
          "with the fix's")
    assert own_builds == builds
    assert np.array_equal(state, own_state), np.abs(state - own_state).max()


def test_neigh_check_with_fix_balance_on_two_processes(tmp_path):
    """fix balance moves the sub-domains (no box change: the trigger distance stays) at builds
    it forces itself; neigh_check yes refused it as a fix that changes the box. On two
    processes, rebalanced every 250 steps: the same builds and final state to the bit as
    LAMMPS's own test."""
    fix = f"nve/disc/mn {GRAVITY}"
    balance = "fix balance all balance 250 1.0 shift xy 10 1.0"
    builds, state = builds_and_state(tmp_path, "lammps", fix, LAMMPS_CHECK, 2, extra=balance)
    own_builds, own_state = builds_and_state(tmp_path, "own", f"{fix} neigh_check yes",
                                             OWN_CHECK, 2, extra=balance)
    print(f"{builds} (builds, dangerous) with LAMMPS's test, {own_builds} with the fix's")
    assert own_builds == builds
    assert np.array_equal(state, own_state), np.abs(state - own_state).max()


def test_a_mass_set_between_runs_is_followed_without_a_setup(tmp_path):
    """`set ... density/disc` between two runs, the second run ... pre no (no setup: no
    fix's setup is called): the fused fix integrated the second run with the old 1/m, fix
    nve/sphere divides by the mass at every step. Now (its factors are recomputed at the
    first step after a run) the same final state to the bit as nve/sphere disc + fix gravity,
    both with m g of the old mass in the forces of the first step (fix gravity added it at the
    last step of the first run)."""
    def edit(deck):
        return deck.replace(
            "run 500\n", "run 500\nset group mobile density/disc 2.5\nrun 500 pre no\n")
    separate = final_state(tmp_path, "separate", ("nve/sphere disc", "gravity"), 500, edit=edit)
    fused = final_state(tmp_path, "fused", (f"nve/disc/mn {GRAVITY}",), 500, edit=edit)
    assert np.array_equal(separate, fused), np.abs(separate - fused).max()


def test_atoms_added_to_the_group_between_runs_are_integrated_without_a_setup(tmp_path):
    """The pile's first 24 disks integrated for 500 steps (the others held where they are),
    then `group` adds the other 24 and the second run ... pre no (no setup) integrates all:
    the fused fix's list of its group's atoms is made again at the first step after a run,
    so the state is nve/sphere disc + fix gravity's (which test each atom's group at every
    step) to the bit. A list kept from the first run would leave the added disks where they
    were, which changes the state at once."""
    def edit(deck):
        return deck.replace(
            "fix integrate mobile", "group first id <= 24\nfix integrate first").replace(
            "fix gravity mobile", "fix gravity first").replace(
            "run 500\n", "run 500\ngroup first type 1\nrun 500 pre no\n")
    separate = final_state(tmp_path, "separate", ("nve/sphere disc", "gravity"), 500, edit=edit)
    fused = final_state(tmp_path, "fused", (f"nve/disc/mn {GRAVITY}",), 500, edit=edit)
    assert np.array_equal(separate, fused), np.abs(separate - fused).max()


def forces(tmp_path, name, integration, integrator_last=False):
    """The pile's dumped forces every 100 steps (500 steps; fix `integrate` defined first, or
    after the wall): {step: array of (id, type, mass, fx, fy)}."""
    deck = pile_deck(integration, 500, True).replace(
        "run 500\n", "dump f all custom 100 forces.txt id type mass fx fy\n"
                     "dump_modify f sort id format float %.17g\nrun 500\n")
    if integrator_last:
        lines = deck.splitlines()
        integrate = next(l for l in lines if l.startswith("fix integrate"))
        lines.remove(integrate)
        lines.insert(lines.index(next(l for l in lines if l.startswith("fix floor"))) + 1,
                     integrate)
        deck = "\n".join(lines) + "\n"
    run_lammps(deck, tmp_path / name)
    snapshots = (tmp_path / name / "forces.txt").read_text().split("ITEM: TIMESTEP\n")[1:]
    return {int(s.splitlines()[0]): np.loadtxt(s.splitlines()[9:], ndmin=2) for s in snapshots}


@pytest.mark.parametrize("scheme", ["verlet", "ab2"])
def test_dumped_forces_hold_gravity_as_fix_gravity_puts_it(tmp_path, scheme):
    """fix nve/disc/mn's gravity was never in f: dumped forces (and fix dt/reset, anything
    reading f) saw the contact forces alone. Now m g goes into f after every other force, as
    by a fix gravity defined after them: the dumped forces are those of nve/sphere disc (or
    nve/ab2) + fix gravity (defined after the wall) to the bit, at every step of the run. At a
    run's setup each fix adds its forces in its own setup: m g goes in last there when no fix
    after nve/disc/mn adds forces (the integrator defined after the wall: step 0 equal too);
    else at the first step (f at step 0 then lacks m g, the trajectory is the same)."""
    separate_fix = "nve/sphere disc" if scheme == "verlet" else "nve/ab2"
    separate = forces(tmp_path, "separate", (separate_fix, "gravity"))
    fused = forces(tmp_path, "fused", (f"nve/disc/mn scheme {scheme} {GRAVITY}",))
    last = forces(tmp_path, "last", (f"nve/disc/mn scheme {scheme} {GRAVITY}",), True)
    assert sorted(separate) == sorted(fused) == list(range(0, 501, 100))
    for step in separate:
        assert np.array_equal(separate[step], last[step]), step
        if step > 0:
            assert np.array_equal(separate[step], fused[step]), step
    # step 0 of the integrator-first deck: the other forces alone, to which fix gravity added
    # m g (its vector style's acceleration: the magnitude times the normalised direction)
    length = math.sqrt(TILT[0] ** 2 + TILT[1] ** 2)
    g = np.array([1.0 * (TILT[0] / length), 1.0 * (TILT[1] / length)])
    mobile = fused[0][:, 1] == 1
    with_gravity = fused[0][:, 3:5] + np.where(mobile[:, None], fused[0][:, 2:3] * g, 0.0)
    assert np.array_equal(with_gravity, separate[0][:, 3:5])
    assert not np.array_equal(fused[0][mobile, 3:5], separate[0][mobile, 3:5])


def one_disk(fix, steps, dt, y0, wall="", mu=0.5):
    """A unit disk (mass 1) at (1, y0) at rest under fix `fix`, `steps` steps of dt (y not
    periodic, for a wall)."""
    return f"""
boundary p f p
region box block -50 50 -50 50 -0.5 0.5
create_box 1 box
create_atoms 1 single 1.0 {y0!r} 0
set type 1 diameter 1.0
set type 1 density/disc {4 / math.pi!r}
group mobile type 1
pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu {mu}
pair_coeff * *
timestep {dt!r}
fix integrate mobile {fix}
{wall}
run {steps}
write_dump all custom final.txt id x y vx vy omegaz modify sort id format float %.17g
"""


@pytest.mark.parametrize("scheme", ["verlet", "ab2"])
def test_a_falling_disk_follows_the_parabola(tmp_path, scheme):
    """Under constant acceleration both schemes are exact: x = x0 + g t^2/2 along the
    normalised direction (0.6, -0.8) at g = 2.5, v = g t. To 1e-12 relative (rounding over
    1000 steps); a wrong normalisation, magnitude or a half kick lost would be off by O(1)."""
    dt, steps, g = 1e-3, 1000, 2.5
    run = run_lammps(one_disk(f"nve/disc/mn scheme {scheme} gravity {g} 3 -4", steps, dt, 10.0),
                     tmp_path)
    a = run.atoms()
    t = steps * dt
    expected = {"x": 1.0 + 0.6 * g * t * t / 2, "y": 10.0 - 0.8 * g * t * t / 2,
                "vx": 0.6 * g * t, "vy": -0.8 * g * t, "omegaz": 0.0}
    for name, value in expected.items():
        assert a[name][0] == pytest.approx(value, rel=1e-12, abs=1e-12), name


@pytest.mark.parametrize("scheme", ["verlet", "ab2"])
def test_a_disk_rolls_down_the_slope_at_two_thirds_of_g_sin_theta(tmp_path, scheme):
    """A disk on a flat wall (fix wall/gran/mn, mu = 0.5) under gravity tilted by sin(theta) =
    0.2 rolls without slipping (it needs a friction of g sin/3 < mu g cos): its centre
    accelerates at g sin(theta) / (1 + I/(m r^2)) = 2/3 g sin(theta) for a disk, so at t = 2
    it has moved g sin(theta) t^2 / 3 = 0.26667 and spins at omega = -v/r. The overlap
    (m g cos/kn = 5e-6 of the radius) and the tangential spring's stretch (~1e-6) bound the
    deviation to 1e-4 relative; a sphere's inertia (5/7 g sin) would be 7 % off, sliding
    (g sin) 50 %."""
    sin_theta = 0.2
    cos_theta = math.sqrt(1 - sin_theta ** 2)
    dt = law(2e5, 0.7, 0.7)["tau_c"] / 50
    steps = round(2.0 / dt)
    t = steps * dt
    run = run_lammps(one_disk(f"nve/disc/mn scheme {scheme} gravity 1.0 {sin_theta} "
                              f"{-cos_theta}", steps, dt, 0.5,
                              wall="fix floor mobile wall/gran/mn yplane 0.0 NULL"), tmp_path)
    a = run.atoms()
    acceleration = 2 / 3 * sin_theta
    assert a["x"][0] - 1.0 == pytest.approx(acceleration * t * t / 2, rel=1e-4)
    assert a["vx"][0] == pytest.approx(acceleration * t, rel=1e-4)
    assert a["omegaz"][0] == pytest.approx(-a["vx"][0] / 0.5, rel=1e-4)


def bad_deck(fix, dimension="dimension 2", atom_style="atom_style sphere", extra="",
             pair_extra="", diameter="1.0"):
    """Two disks of diameter `diameter` and a bump (type 2, diameter 1) under `fix`."""
    header = (HEADER.format(plugin=PLUGIN).replace("dimension 2", dimension)
              .replace("atom_style sphere", atom_style))
    density = "density/disc 1.2732395447351628" if dimension == "dimension 2" else "density 1.9"
    mass = ("mass * 1.0" if atom_style == "atom_style atomic"
            else f"set type 1 diameter {diameter}\nset type 2 diameter 1.0\nset type * {density}")
    z = "-0.5 0.5" if dimension == "dimension 2" else "-3 3"
    return header + f"""
region box block -3 3 -3 3 {z}
create_box 2 box
create_atoms 1 single 0 0.5 0
create_atoms 1 single 1.2 0.5 0
create_atoms 2 single -1.5 -1.5 0
{mass}
group mobile type 1
pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5 wall_types 2 {pair_extra}
pair_coeff * *
timestep 5e-5
fix integrate mobile {fix}
{extra}
run 10
"""


BAD = {
    "nve/disc/mn in three dimensions": (
        bad_deck("nve/disc/mn", dimension="dimension 3"),
        "Fix nve/disc/mn integrates disks: it requires dimension 2"),
    "nve/ab2 in three dimensions": (
        bad_deck("nve/ab2", dimension="dimension 3"),
        "Fix nve/ab2 integrates disks: it requires dimension 2"),
    "nve/disc/mn without disk attributes": (
        bad_deck("nve/disc/mn", atom_style="atom_style atomic"),
        "Fix nve/disc/mn requires atom attributes radius, rmass, omega, torque"),
    "nve/disc/mn on point particles": (
        bad_deck("nve/disc/mn", diameter="0.0"),
        "Fix nve/disc/mn integrates disks: 2 atoms of its group have diameter 0"),
    "nve/disc/mn on a group with fixed bumps": (
        bad_deck("nve/disc/mn", extra="fix all_of_them all nve/disc/mn") .replace(
            "fix integrate mobile nve/disc/mn\n", ""),
        "fix all_of_them (nve/disc/mn) integrates 1 atoms of wall_types"),
    "a second integrator on the same atoms": (
        bad_deck("nve/disc/mn", extra="fix again mobile nve/sphere disc"),
        "Fix integrate (nve/disc/mn): fix again (nve/sphere) integrates 2 atoms of its group "
        "too; an atom takes one integrator"),
    "gravity in nve/disc/mn and fix gravity": (
        bad_deck("nve/disc/mn gravity 1.0 0 -1", extra="fix gravity all gravity 1.0 vector 0 -1 0"),
        "Fix integrate (nve/disc/mn) applies gravity, and fix gravity (gravity) pulls 2 atoms of "
        "its group too: gravity would act twice"),
    "nve/disc/mn unknown scheme": (bad_deck("nve/disc/mn scheme rk4"),
                                   "scheme must be verlet or ab2, not rk4"),
    "nve/disc/mn scheme without value": (bad_deck("nve/disc/mn scheme"),
                                         "scheme needs verlet or ab2"),
    "nve/disc/mn gravity short of values": (bad_deck("nve/disc/mn gravity 1.0 0"),
                                            "gravity needs G X Y"),
    "nve/disc/mn gravity without direction": (bad_deck("nve/disc/mn gravity 1.0 0 0"),
                                              "gravity direction 0 0 has no length"),
    "nve/disc/mn unknown keyword": (bad_deck("nve/disc/mn disc"), "unknown keyword disc"),
    "nve/ab2 with arguments": (bad_deck("nve/ab2 scheme verlet"), "it takes no arguments"),
    "nve/disc/mn neigh_check without yes or no": (bad_deck("nve/disc/mn neigh_check 1"),
                                                  "neigh_check needs yes or no"),
    "neigh_check with another integrator": (
        bad_deck("nve/disc/mn neigh_check yes",
                 extra="create_atoms 1 single 2.0 2.0 0\nset atom 4 diameter 1.0\n"
                       "set atom 4 density/disc 1.2732395447351628\ngroup lone id 4\n"
                       "fix still lone move linear 0 0 0"),
        "Fix integrate (nve/disc/mn) with neigh_check yes tests only the atoms it moves, and "
        "fix still (move) moves atoms too"),
    "neigh_check with a box a fix changes": (
        bad_deck("nve/disc/mn neigh_check yes", extra="fix squeeze all deform 1 x scale 0.99"),
        "Fix integrate (nve/disc/mn) with neigh_check yes needs a box that no fix changes "
        "during a run, and fix squeeze (deform) does"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_input_stops_with_a_named_error(tmp_path, case):
    text, message = BAD[case]
    run = run_lammps(text, tmp_path, header=False, check=False)
    assert run.returncode != 0, run.output[-2000:]
    assert "ERROR" in run.output
    assert message in run.output, run.output[-2000:]

