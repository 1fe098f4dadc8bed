"""Independent cross-check of the normal law with Debian's LIGGGHTS 3.8 (hooke/stiffness).

For equal unit masses 2M = 1, and against a wall m_i = 1, so gran/mn's forces are
k_n delta - eta_n v_n with the same numbers LIGGGHTS takes as absolute stiffness and damping.
Both integrate with velocity Verlet, so a head-on collision and a bouncing ball must agree to
rounding at the same dt. (LIGGGHTS is installed by scripts/setup.sh.)"""
import shutil
import subprocess

import pytest

from bench.equivalent_laws import LIGGGHTS_FLOOR, liggghts_contacts
from granmn_run import HEADER, PLUGIN, law, run_lammps

KN, E, BETA, MU = 2e5, 0.7, 0.7, 0.5


def scene(engine, kind, dt, steps, mu=MU):
    """The same scene for LIGGGHTS ('liggghts') or lmp with the plugin ('lammps')."""
    c = law(KN, E, BETA)
    if kind in ("collision", "oblique"):
        atoms = ("create_atoms 1 single -0.61234 0 0\ncreate_atoms 1 single 0.61234 0 0\n"
                 "set atom 1 vx 0.5\nset atom 2 vx -0.5\n")
        if kind == "oblique":    # tangential slip, sticking (mu large)
            atoms += "set atom 1 vy 0.3\nset atom 2 vy -0.3\n"
    else:
        atoms = "create_atoms 1 single 0 0.63 0\n"
    if engine == "liggghts":
        setup = f"""
atom_style granular
atom_modify map array
dimension 2
boundary p p p
newton off
communicate single vel yes
units lj
region reg block -5 5 -5 5 -0.5 0.5 units box
create_box 1 reg
neighbor 0.1 bin
neigh_modify delay 0
""" + liggghts_contacts(c, KN, mu)
        wall = LIGGGHTS_FLOOR
        integrate = "fix integrate all nve/sphere\n"
    else:
        setup = HEADER.format(plugin=PLUGIN) + f"""
boundary p f p
region reg block -5 5 -5 5 -0.5 0.5 units box
create_box 1 reg
neigh_modify delay 0
pair_style gran/mn kn {KN!r} e {E!r} beta {BETA!r} mu {mu!r}
pair_coeff * *
"""
        wall = "fix floor all wall/gran/mn yplane 0.0 NULL\n"
        integrate = "fix integrate all nve/sphere disc\n"
    deck = setup + f"timestep {dt!r}\n" + atoms + "set atom * diameter 1.0\nset atom * mass 1.0\n"
    if kind == "bounce":
        deck += wall + "fix gravity all gravity 1.0 vector 0 -1 0\n"
    deck += integrate + "fix flat all enforce2d\n" + f"run {steps}\n"
    deck += "variable x1 equal x[1]\nvariable y1 equal y[1]\nvariable vx1 equal vx[1]\n"
    deck += "variable vy1 equal vy[1]\nvariable w1 equal omegaz[1]\n"
    deck += "print \"RESULT state ${x1} ${y1} ${vx1} ${vy1}\"\n"
    return deck


def run_liggghts(deck, workdir):
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / "in.liggghts").write_text(deck)
    proc = subprocess.run([shutil.which("liggghts") or "liggghts", "-in", "in.liggghts", "-echo",
                           "none", "-log", "log.liggghts"], cwd=workdir, capture_output=True,
                          text=True, errors="replace")
    assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr[-2000:]
    line = next(l for l in proc.stdout.splitlines() if l.startswith("RESULT state"))
    return [float(v) for v in line.split()[2:]]


@pytest.mark.parametrize("kind", ["collision", "bounce"])
def test_same_trajectory_as_liggghts(tmp_path, kind):
    assert shutil.which("liggghts"), "liggghts is missing: scripts/setup.sh installs it"
    ref = law(KN, E, BETA)
    dt = ref["tau_c"] / 100
    steps = 6000 if kind == "collision" else int(2.0 / dt)    # 2 time units: several bounces
    theirs = run_liggghts(scene("liggghts", kind, dt, steps), tmp_path / "liggghts")
    ours = run_lammps(scene("lammps", kind, dt, steps), tmp_path / "lammps",
                      header=False).result("state")
    print(f"{kind}: liggghts {theirs}\n{' ' * len(kind)}  gran/mn  {ours}")
    if kind == "collision":
        assert ours[2] < 0 < ours[0] + 0.7                    # it did rebound
    else:
        assert abs(ours[3]) > 0 or ours[1] < 0.5              # it did reach the floor
    for a, b in zip(theirs, ours):
        assert a == pytest.approx(b, rel=1e-11, abs=1e-12)


def test_no_slip_oblique_impact_within_the_lever_arm_difference(tmp_path):
    """Tangential slip 0.6 against normal speed 1, mu = 10 (sticking). LIGGGHTS takes r - delta/2
    as lever arm where gran/mn takes r, so the tangential impulse differs by the order of the
    peak overlap over the radius: delta_max ~ v_n / sqrt(2 kn) = 1.6e-3, i.e. ~0.3 %; allowed
    1 %. Through the contact's rotation the normal motion feels it too, much less: 1e-3.
    LIGGGHTS's nve/sphere evidently gives 2D particles the disc's moment of inertia: against
    gran/mn with `nve/sphere disc` the rebound agrees to 0.25 %, against plain `nve/sphere`
    (I = 2/5 m r^2) it is 18 % off (measured; not looked up in its source)."""
    dt = law(KN, E, BETA)["tau_c"] / 100
    theirs = run_liggghts(scene("liggghts", "oblique", dt, 6000, mu=10.0), tmp_path / "liggghts")
    ours = run_lammps(scene("lammps", "oblique", dt, 6000, mu=10.0), tmp_path / "lammps",
                      header=False).result("state")
    print(f"oblique: liggghts {theirs}\n         gran/mn  {ours}")
    assert abs(ours[3] - 0.3) > 0.05                           # a real tangential impulse
    assert ours[3] == pytest.approx(theirs[3], rel=0.01)
    assert ours[2] == pytest.approx(theirs[2], rel=1e-3)
