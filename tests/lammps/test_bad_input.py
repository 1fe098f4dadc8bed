"""Every bad argument of pair_style gran/mn, fix wall/gran/mn and fix wall/gran/region/mn stops lmp with an error that
names the problem (or, for a merely coarse time step, warns)."""
import re

import pytest

from granmn_run import HEADER, PLUGIN, installed_packages, run_lammps

GOOD_PAIR = "pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5"
# a box region around the two disks of deck(), its floor 0.5 below their centres
REGION = "region inside block -2.5 2.5 0 2.5 -0.5 0.5 units box"
# the same box moved down by v_drop, its floor 0.01 into the disks at the start
MOVING_REGION = "region inside block -2.5 2.5 0.01 2.5 -0.5 0.5 move NULL v_drop NULL units box"


def deck(pair=GOOD_PAIR, coeff="pair_coeff * *", fix="", timestep="timestep 5e-5",
         dimension="dimension 2", atom_style="atom_style sphere", comm="comm_modify vel yes",
         z="-0.5 0.5", second="1.2 0.5 0", boundary="p f p"):
    """Two disks (y not periodic: the wall fixes' cases need it) and `fix`."""
    header = (HEADER.format(plugin=PLUGIN)
              .replace("boundary p p p", f"boundary {boundary}")
              .replace("dimension 2", dimension)
              .replace("atom_style sphere", atom_style)
              .replace("comm_modify vel yes", comm))
    mass = "mass * 1.0" if atom_style == "atom_style atomic" else (
        "set type * density/disc 1.2732395447351628" if dimension == "dimension 2"
        else "set type * density 1.9")
    return header + f"""
region box block -3 3 -3 3 {z}
create_box 2 box
create_atoms 1 single 0 0.5 0
create_atoms 1 single {second}
{mass}
{pair}
{coeff}
{timestep}
fix integrate all nve
{fix}
run 10
"""


ERRORS = {
    "kn zero": (deck(pair="pair_style gran/mn kn 0 e 0.7 beta 0.7 mu 0.5"),
                "kn must be a finite number > 0"),
    "kn negative": (deck(pair="pair_style gran/mn kn -2e5 e 0.7 beta 0.7 mu 0.5"),
                    "kn must be a finite number > 0"),
    "kn not a number": (deck(pair="pair_style gran/mn kn stiff e 0.7 beta 0.7 mu 0.5"),
                        "Expected floating point parameter instead of 'stiff'"),
    "e zero": (deck(pair="pair_style gran/mn kn 2e5 e 0 beta 0.7 mu 0.5"), "e must lie in (0,1]"),
    "e above one": (deck(pair="pair_style gran/mn kn 2e5 e 1.2 beta 0.7 mu 0.5"),
                    "e must lie in (0,1]"),
    "beta zero": (deck(pair="pair_style gran/mn kn 2e5 e 0.7 beta 0 mu 0.5"),
                  "beta must lie in (0,1]"),
    "beta above one": (deck(pair="pair_style gran/mn kn 2e5 e 0.7 beta 1.5 mu 0.5"),
                       "beta must lie in (0,1]"),
    "mu negative": (deck(pair="pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu -0.1"),
                    "mu must be a finite number >= 0"),
    "unknown keyword": (deck(pair=GOOD_PAIR + " stiffness 3"), "unknown keyword stiffness"),
    "keyword without value": (deck(pair="pair_style gran/mn e 0.7 beta 0.7 mu 0.5 kn"),
                              "kn needs a value"),
    "missing parameter": (deck(pair="pair_style gran/mn kn 2e5 e 0.7 mu 0.5"),
                          "beta must be given"),
    "parameter given twice": (deck(pair=GOOD_PAIR + " kn 1e6"), "kn given twice"),
    "wall fix parameter given twice": (
        deck(fix="fix floor all wall/gran/mn yplane 0.0 NULL mu 0.3 mu 0.4"), "mu given twice"),
    "wall_types without types": (deck(pair=GOOD_PAIR + " wall_types"),
                                 "wall_types needs atom types"),
    "wall type out of range": (deck(pair=GOOD_PAIR + " wall_types 3"),
                               "wall type 3 is out of range 1..2"),
    "wall type zero": (deck(pair=GOOD_PAIR + " wall_types 0"), "wall type 0 is out of range"),
    "pair_coeff with coefficients": (deck(coeff="pair_coeff * * 1.0"),
                                     "pair_coeff * * with no further arguments"),
    "atom style without radius": (deck(atom_style="atom_style atomic"),
                                  "requires atom attributes radius, rmass, omega, torque"),
    "discs integrated in three dimensions": (
        deck(dimension="dimension 3", z="-3 3", fix="unfix integrate\nfix spin all nve/sphere disc"),
        "Fix nve/sphere disc requires 2d simulation"),
    "wall fix zplane in two dimensions": (deck(fix="fix floor all wall/gran/mn zplane 0.0 NULL"),
                                          "zplane needs dimension 3"),
    "wall fix unknown wall style in three dimensions": (
        deck(dimension="dimension 3", z="-3 3",
             fix="fix floor all wall/gran/mn xcylinder 0.0 NULL"),
        "unknown wall style xcylinder (expected xplane, yplane, zplane or zcylinder; other "
        "shapes: fix wall/gran/region/mn)"),
    # without comm_modify vel yes the pair style in 2D sends the ghosts' v and omega itself, but
    # not fix deform's shift of them across the periodic boundary (LAMMPS's own communication's)
    "ghost velocities off under fix deform remap v": (
        deck(comm="comm_modify vel no",
             fix="fix shear all deform 1 x erate 0.01 remap v"),
        "with fix deform remap v requires comm_modify vel yes"),
    "time step above stability limit": (deck(timestep="timestep 0.003"),
                                        "exceeds the stability limit"),
    "wall fix without pair style": (
        deck(pair="pair_style zero 1.0", coeff="pair_coeff * *",
             fix="fix floor all wall/gran/mn yplane 0.0 NULL"),
        "takes its kn, e, beta, mu from pair_style gran/mn"),
    "wall fix unknown wall style": (deck(fix="fix floor all wall/gran/mn xcylinder 0.0 NULL"),
                                    "unknown wall style xcylinder (expected xplane, yplane or "
                                    "zcylinder"),
    "zcylinder of radius zero": (
        deck(boundary="f f p", fix="fix drum all wall/gran/mn zcylinder NULL 0"),
        "zcylinder radii must be positive (inner NULL, outer 0)"),
    # the walls are about x = y = 0: a box beside it has them nowhere near its atoms
    "zcylinder whose axis is outside the box": (
        deck(boundary="f f p", fix="displace_atoms all move 2.5 0 0 units box\n"
                                   "change_box all x final 1 5 units box\n"
                                   "fix drum all wall/gran/mn zcylinder NULL 4"),
        "the zcylinder's axis (x = y = 0) lies outside the box (x from 1 to 5)"),
    "zcylinder in a periodic dimension": (
        deck(fix="fix drum all wall/gran/mn zcylinder NULL 2.5"),
        "Fix wall/gran/mn: cannot use wall in periodic dimension x"),
    "wall fix unknown keyword": (deck(fix="fix floor all wall/gran/mn yplane 0.0 NULL shear 1"),
                                 "unknown keyword shear"),
    "wall fix walls in wrong order": (deck(fix="fix floor all wall/gran/mn yplane 2.0 1.0"),
                                      "lower wall 2 not below upper wall 1"),
    "wall fix without walls": (deck(fix="fix floor all wall/gran/mn yplane NULL NULL"),
                               "both walls are NULL"),
    "wall fix too few arguments": (deck(fix="fix floor all wall/gran/mn yplane 0.0"),
                                   "expected xplane|yplane|zcylinder lo hi"),
    "wall fix bad restitution": (deck(fix="fix floor all wall/gran/mn yplane 0.0 NULL e 2"),
                                 "e must lie in (0,1]"),
    "wall fix stiffer than time step allows": (
        deck(fix="fix floor all wall/gran/mn yplane 0.0 NULL kn 1e9"),
        "fix wall/gran/mn: timestep 5e-05 exceeds the stability limit"),
    # at the start of a run no step has moved an atom: it was placed so (the message blamed
    # the time step)
    "atom behind the wall": (deck(fix="fix floor all wall/gran/mn yplane 0.6 NULL"),
                             "atom 1 is behind the wall at 0.6 at the start of the run, its "
                             "centre on the wall or beyond it (placed so?)"),
    # faster than the contact can stop it (v >> r sqrt(kn)), as "atom through the region wall"
    "atom through the wall": (
        deck(fix="fix floor all wall/gran/mn yplane 0.0 NULL\nset atom 1 vy -3000"),
        "atom 1 has passed through the wall at 0 (time step too large for the contact "
        "stiffness?)"),
    "atom through the zcylinder": (
        deck(boundary="f f p", fix="fix drum all wall/gran/mn zcylinder NULL 2.5\n"
                                   "set atom 2 vx 3000"),
        "atom 2 has passed through the zcylinder of radius 2.5 (time step too large"),
    "atom outside the zcylinder": (
        deck(boundary="f f p", fix="fix drum all wall/gran/mn zcylinder NULL 0.3"),
        "atom 1 is outside the outer zcylinder of radius 0.3 at the start of the run"),
    "atom inside the inner zcylinder": (
        deck(boundary="f f p", fix="fix drum all wall/gran/mn zcylinder 0.6 NULL"),
        "atom 1 is inside the inner zcylinder of radius 0.6 at the start of the run"),
    # an atom re-entering through the periodic boundary came back inside the wall (and was shot
    # out at v = 233)
    "wall in a periodic dimension": (
        deck(boundary="p p p", fix="fix floor all wall/gran/mn yplane -2.0 NULL"),
        "Fix wall/gran/mn: cannot use wall in periodic dimension y"),
    # a bump of diameter 0 was accepted, and its first touch said "use a time step below 0"
    "bump of diameter 0": (
        deck(pair=GOOD_PAIR + " wall_types 2",
             fix="set atom 2 type 2\nset atom 2 diameter 0.0\nunfix integrate\n"
                 "group mobile type 1\nfix integrate mobile nve"),
        "pair_style gran/mn: 1 atoms of wall_types have diameter 0"),
    # a mobile point particle: its first touch said "use a time step below 0"
    "point particle touching a disk": (
        deck(second="0.6 0.5 0", fix="set atom 2 diameter 0.0\nset atom 2 vx -1000"),
        "atom 2 has diameter 0 (a point particle), so its centre is inside the other at its "
        "first touch"),
    # off the plane, the neighbor list (3D distances) missed its contacts: disks got inside it
    "disk off the plane in two dimensions": (
        deck(fix="set atom 2 z 0.3"),
        "pair_style gran/mn: atom 2 is at z = 0.3 in a 2D simulation"),
    "kn so large the law overflows": (
        deck(pair="pair_style gran/mn kn 1e308 e 0.7 beta 0.7 mu 0.5"),
        "kn is too large: the derived coefficients (tau_c, eta_n, kt) overflow"),
    "two atoms at the same position": (deck(second="0 0.5 0"),
                                       "atoms 1 and 2 are at the same position"),
    "point particle under nve/ab2": (
        deck(fix="unfix integrate\nset atom 1 diameter 0.0\nfix integrate all nve/ab2"),
        "Fix nve/ab2 integrates disks: 1 atoms of its group have diameter 0"),
    "integrator changed between runs (mu > 0)": (
        deck(fix="run 10\nunfix integrate\nfix integrate all nve/ab2"),
        "its contact history was set up for a different mu, fix contacts/mn or integrator"),
    "spheres integrated by nve/sphere": (
        deck(fix="unfix integrate\nfix spin all nve/sphere"),
        "fix spin (nve/sphere) integrates spheres; the law is for disks"),
    "atoms placed inside each other": (deck(second="0.3 0.5 0"),
                                       "atoms 1 and 2 overlap by 0.7, more than the smaller "
                                       "radius 0.5"),
    "integrated bump": (deck(pair=GOOD_PAIR + " wall_types 2", fix="set atom 2 type 2"),
                        "fix integrate (nve) integrates 1 atoms of wall_types"),
    "two gran/mn sub-styles": (
        deck(pair="pair_style hybrid gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5 "
                  "gran/mn kn 1e6 e 0.7 beta 0.7 mu 0.5",
             coeff="pair_coeff * * gran/mn 1"),
        "pair_style hybrid holds gran/mn twice"),
    "beta near zero at tau_c/100": (
        deck(pair="pair_style gran/mn kn 2e5 e 0.7 beta 1e-40 mu 0.5",
             timestep="timestep $(v_mn_tau_c/100)"),
        "the tangential (sticking) mode of two disks: use a timestep below 4.49"),
    "beta near zero at tau_c/100 in three dimensions": (
        deck(pair="pair_style gran/mn kn 2e5 e 0.7 beta 1e-40 mu 0.5", dimension="dimension 3",
             z="-3 3", timestep="timestep $(v_mn_tau_c/100)"),
        "the tangential (sticking) mode of two spheres: use a timestep below 4.49"),
    "region wall without its region": (
        deck(fix="fix cup all wall/gran/region/mn nowhere"),
        "Fix wall/gran/region/mn: region nowhere does not exist"),
    "region wall unknown keyword": (
        deck(fix=f"{REGION}\nfix cup all wall/gran/region/mn inside shear 1"),
        "Illegal fix wall/gran/region/mn command: unknown keyword shear"),
    "region wall of a region whose shape changes": (
        deck(fix="variable r equal 2+0.1*time\nregion round sphere 0 0 0 v_r\n"
                 "fix cup all wall/gran/region/mn round"),
        "region round changes its shape (variable parameters)"),
    # an atom faster than the contact can stop (v >> r sqrt(kn)): LAMMPS's fix wall/gran/region
    # lets it go on outside the region without a word
    "atom through the region wall": (
        deck(fix=f"{REGION}\nfix cup all wall/gran/region/mn inside\nset atom 1 vy -3000"),
        "atom 1 has passed through the surface of region inside"),
    "region wall face through an atom's centre": (
        deck(fix=REGION.replace("0 2.5 -0.5", "0.5 2.5 -0.5") +
             "\nfix cup all wall/gran/region/mn inside"),
        "atom 1 has its centre on the surface of region inside at the start of the run "
        "(placed so?)"),
    # a region that jumps by more than a radius in a step: it leaves an atom that touched its
    # floor outside it, or (counted) far from it
    "region wall that jumps past an atom": (
        deck(fix="variable drop equal -3*(step>5)\n" + MOVING_REGION +
             "\nfix cup all wall/gran/region/mn inside"),
        "has passed through the surface of region inside (time step too large for the contact "
        "stiffness, or a move or rotate variable of the region that jumps?)"),
    "region wall that jumps away from an atom, counted": (
        deck(fix="variable drop equal -1*(step>5)\n" + MOVING_REGION +
             "\nfix cup all wall/gran/region/mn inside\nfix c all contacts/mn"),
        "by more than its radius within one step: the atom or the face moved that far in a "
        "step (a time step far too large, or a move or rotate variable of the region that "
        "jumps)"),
    "e near zero at tau_c/100": (
        deck(pair="pair_style gran/mn kn 2e5 e 1e-40 beta 0.7 mu 0.5",
             timestep="timestep $(v_mn_tau_c/100)"),
        "the normal mode of two disks: use a timestep below 0.00131"),
}


@pytest.mark.parametrize("case", sorted(ERRORS))
def test_bad_input_stops_with_a_named_error(tmp_path, case):
    text, message = ERRORS[case]
    run = run_lammps(text, tmp_path, header=False, check=False)
    assert run.returncode != 0, run.output[-2000:]
    assert "ERROR" in run.output
    assert message in run.output, run.output[-2000:]


def test_coarse_time_step_warns_but_runs(tmp_path):
    # tau_c = 5.0e-3 at kn = 2e5: dt = 1e-3 resolves a collision with 5 steps, but is stable
    run = run_lammps(deck(timestep="timestep 1e-3"), tmp_path, header=False)
    assert "WARNING" in run.output and "fewer than 10 steps" in run.output


@pytest.mark.parametrize("nprocs", [1, 2])
def test_deep_overlap_at_the_start_is_said(tmp_path, nprocs):
    """Two disks of radius 0.5 whose centres start 0.8 apart (overlap 0.2, 0.4 of the radius:
    placed so): the run starts with a warning that names them, the overlap and the speed the
    spring gives them, 0.2 sqrt(2 k_n) = 126; once, also on two ranks with newton off, where
    the pair straddles the ranks' boundary (x = 0) and both ranks list it. 0.96 apart (0.08 of
    the radius, below the stated 0.1) says nothing."""
    said = ("pair_style gran/mn: 1 pair(s) of particles overlap by more than 0.1 of the smaller "
            "radius at the start of the run; the deepest, atoms 1 and 2, by 0.2 (0.4 of radius "
            "0.5): released, it drives them apart at up to 126 (placed closer than their "
            "radii's sum?)")
    for apart, deep in ((0.8, True), (0.96, False)):
        run = run_lammps(deck(second=f"-{apart} 0.5 0", comm="comm_modify vel yes\nnewton off"),
                         tmp_path / str(apart), nprocs=nprocs, header=False)
        warnings = [line for line in run.output.splitlines() if "overlap by more than" in line]
        if deep:
            assert len(warnings) == 1 and warnings[0].startswith(f"WARNING: {said}"), warnings
        else:
            assert not warnings, warnings


def test_elastic_collisions_under_the_papers_integrator_run_at_its_step(tmp_path):
    """e = 1 leaves the normal mode undamped; Adams-Bashforth 2 amplifies such a mode a little
    at every step and so has no strict stability limit. The paper's tau_c/100 (5e-5 here) is
    accepted, with a warning that says what happens to contacts that last."""
    run = run_lammps(deck(pair="pair_style gran/mn kn 2e5 e 1 beta 0.7 mu 0.5",
                          fix="unfix integrate\nfix integrate all nve/ab2"), tmp_path,
                     header=False)
    assert "slowly amplifies an undamped contact mode" in run.output


def test_write_data_warns_that_the_state_of_the_fixes_is_not_in_the_file(tmp_path):
    """A data file holds positions and velocities, not fix nve/ab2's previous accelerations nor
    the walls' u_t: a run from read_data starts them afresh. write_data says so."""
    run = run_lammps(deck(fix="unfix integrate\nfix integrate all nve/ab2") +
                     "write_data state.data\n", tmp_path, header=False)
    assert "write_data does not carry the per-atom state of fix integrate (nve/ab2)" in run.output


@pytest.mark.parametrize("written, continued", [("nve", "nve/ab2"), ("nve/ab2", "nve")])
def test_restart_under_the_other_integrator_is_refused(tmp_path, written, continued):
    """Under fix nve/ab2 a frictional contact keeps its previous v_t too (2 history values, 1
    under velocity Verlet): a restart continued under the other integrator would misread every
    contact's history, and is refused."""
    first = run_lammps(deck(second="0.95 0.5 0",
                            fix=f"unfix integrate\nfix integrate all {written}") +
                       "write_restart state.restart\n", tmp_path / "written", header=False)
    run = run_lammps(f"read_restart {first.workdir / 'state.restart'}\ncomm_modify vel yes\n"
                     f"fix integrate all {continued}\nrun 10\n", tmp_path / "continued",
                     check=False)
    held, needed = (1, 2) if continued == "nve/ab2" else (2, 1)
    assert run.returncode != 0
    assert (f"the restart file holds {held} history values per contact, this run needs {needed}"
            in run.output), run.output[-1500:]


@pytest.mark.parametrize("compress", ["yes", "no"])
def test_renumbered_atoms_are_said_to_lose_their_contact_history(tmp_path, compress):
    """LAMMPS keys per-contact history by atom IDs: delete_atoms with compress yes (its
    default) renumbers the atoms left, and their contacts start afresh. The pair style says
    so at the next run; with compress no the IDs and the history stay."""
    text = deck(second="0.95 0.5 0") + f"""
create_atoms 1 single -2.5 -2.5 0
set atom 3 density/disc 1.2732395447351628
run 10
group first id 1
delete_atoms group first compress {compress}
run 10
"""
    run = run_lammps(text, tmp_path, header=False)
    said = "atoms have other IDs than in the last run" in run.output
    assert said == (compress == "yes"), run.output[-2000:]


@pytest.mark.parametrize("weak", ["beta", "e"])
def test_a_mode_damped_too_hard_for_tau_c_over_100_is_named_with_a_step_that_works(tmp_path,
                                                                                   weak):
    """e or beta close to 0 damps a contact mode so hard that the integrator needs a step
    below the paper's tau_c/100 (beta = 1e-40: the sticking tangential mode, eta_t =
    -ln(beta)/(3 tau_c); e = 1e-40: the normal one, and tau_c itself grows with |ln e|). The
    error names the mode and the largest stable step; at 0.9 of it a collision with spin
    (tangential motion; sticking at mu = 5) runs and loses energy, as a damped contact must:
    an unstable mode would grow by orders of magnitude over the contact's 100+ steps."""
    e, beta = (0.7, 1e-40) if weak == "beta" else (1e-40, 0.7)
    material = f"kn 2e5 e {e} beta {beta} mu 5"
    refused = run_lammps(deck(pair=f"pair_style gran/mn {material}",
                              timestep="timestep $(v_mn_tau_c/100)"), tmp_path / "paper",
                         header=False, check=False)
    found = re.search(r"for the stiffest contact mode, the (\S+) .* use a timestep below (\S+) "
                      r"\(the paper's tau_c/100 = \S+ is too coarse here", refused.output)
    assert refused.returncode != 0 and found, refused.output[-2000:]
    assert found[1] == ("tangential" if weak == "beta" else "normal")
    dt = 0.9 * float(found[2])
    energy = ("unfix integrate\nfix integrate all nve/sphere disc\nfix flat all enforce2d\n"
              "set atom 1 vx 1 omega 0 0 10\n"
              "compute disk all property/atom radius omegaz\n"    # disks: I = m r^2/2
              "variable spin atom 0.25*mass*c_disk[1]^2*c_disk[2]^2\n"
              "compute spin all reduce sum v_spin\ncompute ke all ke\n"
              "variable energy equal c_ke+c_spin\nthermo_style custom step v_energy\n"
              "run 0\nprint \"RESULT start ${energy}\"")
    text = deck(pair=f"pair_style gran/mn {material}", timestep=f"timestep {dt!r}", fix=energy)
    text = text.replace("run 10\n", "run $(ceil(0.5/dt))\nprint \"RESULT end ${energy}\"\n")
    finer = run_lammps(text, tmp_path / "finer", header=False)
    (start,), (end,) = finer.result("start"), finer.result("end")
    assert 0 < end < start


def test_neighbor_list_built_once_is_warned_about(tmp_path):
    """neigh_modify once yes builds the list only at the start of a run: two disks 0.2 apart
    that meet later never interact. The pair style warns."""
    run = run_lammps(deck(fix="neigh_modify once yes"), tmp_path, header=False)
    assert "neigh_modify once yes builds the neighbor list only at the start of a run" in run.output


def skip_without_bonds():
    """Bonds need LAMMPS's MOLECULE package: the project's builds have it (CMakeLists.txt), an
    lmp of one's own may not."""
    if "MOLECULE" not in installed_packages():
        pytest.skip("this lmp has no MOLECULE package (bonds)")


def bonded_pair(special_bonds, pair=GOOD_PAIR):
    """Two disks that overlap by a tenth of a diameter, bonded (bond_style zero: no bond force),
    at rest, no gravity: they move only if the pair style finds them in contact."""
    return deck(pair=pair, atom_style="atom_style hybrid sphere bond",
                second="0.9 0.5 0", timestep="timestep 1e-4").replace(
        "create_box 2 box",
        "create_box 2 box bond/types 1 extra/bond/per/atom 1 extra/special/per/atom 1").replace(
        "set type * density/disc", f"""bond_style zero
bond_coeff 1
{special_bonds}
create_bonds single/bond 1 1 2
set type * density/disc""").replace("run 10", """run 10
print "RESULT vx $(vx[1]) $(vx[2])"
""")


# special_bonds settings that keep bonded pairs in the neighbor list with a weight the law
# would not apply
BONDED = {
    # BPM's setting: bonded pairs kept in the list (for the bond to break) at lj weight 0
    "bonded pairs listed at lj weight 0": (
        "special_bonds lj 0 1 1 coul 1 1 1",
        "special_bonds lj 0 coul 1 keeps 1-2 pairs in the neighbor list"),
    "bonded pairs at a fractional lj weight": (
        "special_bonds lj 0.5 1 1",
        "special_bonds lj 0.5 coul 0 keeps 1-2 pairs in the neighbor list"),
    "bonded 1-3 pairs at a fractional lj weight": (
        "special_bonds lj 1 0.5 1",
        "special_bonds lj 0.5 coul 0 keeps 1-3 pairs in the neighbor list")}


@pytest.mark.parametrize("case", sorted(BONDED))
def test_bonded_pairs_the_law_would_weigh_are_refused(tmp_path, case):
    skip_without_bonds()
    special_bonds, message = BONDED[case]
    run = run_lammps(bonded_pair(special_bonds), tmp_path, header=False, check=False)
    assert run.returncode != 0, run.output[-2000:]
    assert message in run.output, run.output[-2000:]


@pytest.mark.parametrize("special_bonds", ["", "special_bonds lj 0 1 1 coul 0 1 1",
                                           "special_bonds lj 1 1 1"])
def test_bonded_pairs_touch_where_lammpss_own_granular_style_does(tmp_path, special_bonds):
    """The weights the style accepts, against gran/hooke/history under the same LAMMPS: a bonded
    pair kept in the neighbor list at weight 1 touches in both (the disks are pushed apart); at
    LAMMPS's default weights (lj and coul 0) LAMMPS 2025 on leaves it out of the list, and
    neither touches, while 2021's granular lists keep it, and both do."""
    skip_without_bonds()
    hooke = "pair_style gran/hooke/history 2e5 NULL 50 NULL 0.5 0"
    runs = {name: run_lammps(bonded_pair(special_bonds, pair), tmp_path / name, header=False)
            for name, pair in (("gran/mn", GOOD_PAIR), ("hooke", hooke))}
    touching = {}
    for name, run in runs.items():
        vx1, vx2 = run.result("vx")
        touching[name] = vx1 < 0 < vx2
        assert touching[name] or vx1 == vx2 == 0.0, (name, vx1, vx2)
    assert touching["gran/mn"] == touching["hooke"]
    if special_bonds == "special_bonds lj 1 1 1":
        assert touching["gran/mn"]
