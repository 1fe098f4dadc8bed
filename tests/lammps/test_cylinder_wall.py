"""fix wall/gran/mn zcylinder: the walls of an inner and an outer cylinder about z (in 2D
circles), with the boundary rule (2M -> m_i) as the planes: a radial bounce off either has
the plane's e_w; a disk rolling inside a circle swings with the rolling pendulum's period; a
sphere pressed against the inside of the cylinder rolls down it at 5/7 g_z; the counters
count its contacts as boundary contacts."""
import os
from pathlib import Path

import numpy as np
import pytest

from granmn_run import HEADER, PLUGIN, law, restitution_error_bound, run_lammps
from test_three_d import HEADER_3D, SPHERE_DENSITY

KN, E, BETA = 2e5, 0.7, 0.7
FINAL = ("write_dump all custom final.txt id x y z vx vy vz omegax omegay omegaz "
         "modify sort id format float %.17g\n")


def header(dimension):
    text = HEADER_3D if dimension == 3 else HEADER.format(plugin=PLUGIN)
    return text.replace("boundary p p p\n", "")


def box(dimension):
    if dimension == 3:
        return "boundary f f p\nregion box block -6 6 -6 6 -3 3\ncreate_box 1 box\n"
    return "boundary f f p\nregion box block -6 6 -6 6 -0.5 0.5\ncreate_box 1 box\n"


def styles(dimension, mu=0.5, extra=""):
    density = SPHERE_DENSITY if dimension == 3 else 4 / np.pi
    integrator = "nve/sphere" if dimension == 3 else "nve/sphere disc"
    return (f"set type 1 diameter 1.0\nset type 1 density {density!r}\n"
            f"pair_style gran/mn kn {KN} e {E} beta {BETA} mu {mu}{extra}\npair_coeff * *\n"
            f"fix integrate all {integrator}\n")


@pytest.mark.parametrize("dimension", [2, 3])
@pytest.mark.parametrize("wall", ["outer", "inner"])
def test_radial_bounce_off_either_cylinder_has_e_w(tmp_path, dimension, wall):
    """A disk or sphere moving radially at 1 onto the outer wall (radius 5, from inside) or
    the inner one (radius 1, from outside), along x at y = 0: there the cylinder's normal is
    exactly x's and its distance the plane's, so the bounce is the plane wall's at x = 5 or
    x = 1 bitwise (whose restitution test_boundary.py checks for its order of convergence) and
    comes back at e_w within velocity Verlet's bound, along the radius (no tangential motion,
    no spin)."""
    dt = law(KN, E, BETA)["tau_c"] / 100
    if wall == "outer":
        start, speed, radii, plane = "4.49 0 0", 1.0, "NULL 5.0", "NULL 5.0"
    else:
        start, speed, radii, plane = "1.51 0 0", -1.0, "1.0 NULL", "1.0 NULL"

    def bounce(style, where):
        deck = header(dimension) + box(dimension) + f"create_atoms 1 single {start}\n" + styles(
            dimension) + f"""set atom 1 vx {speed}
fix w all wall/gran/mn {style} {where}
timestep {dt!r}
thermo 0
run 600
""" + FINAL
        return run_lammps(deck, tmp_path / style, header=False)

    run = bounce("zcylinder", radii)
    as_plane = bounce("xplane", plane)
    assert (run.workdir / "final.txt").read_text() == (as_plane.workdir / "final.txt").read_text()
    atoms = run.atoms()
    e_w = law(KN, E, BETA)["e_w"]
    rebound = -atoms["vx"][0] / speed
    print(f"{dimension}D {wall}: rebound {rebound:.5f}, e_w {e_w:.5f}")
    assert abs(rebound - e_w) <= restitution_error_bound(e_w, 1 / 100)
    assert abs(atoms["vy"][0]) < 1e-12 and abs(atoms["omegaz"][0]) < 1e-12


def test_disk_rolling_inside_a_circle_swings_with_the_rolling_pendulums_period(tmp_path):
    """2D: a disk (I = m r^2/2) rolling without sliding at the bottom of a circle of radius R
    swings about it like a pendulum of length R - r slowed by its spin: for small amplitudes
    the period is 2 pi sqrt((1 + 1/2)(R - r)/g). Started 0.1 rad from the bottom at rest,
    measured from the zero crossings of x over three periods, within 0.5 % (the amplitude's
    correction, (0.1)^2/16, is 6e-4). Frictionless it would slide, with the period of the
    plain pendulum, 18 % shorter; without the wall's curvature it would not swing."""
    radius, g, amplitude = 5.0, 1.0, 0.1
    length = radius - 0.5
    dt = law(KN, E, BETA)["tau_c"] / 50
    period = 2 * np.pi * np.sqrt(1.5 * length / g)
    deck = header(2) + box(2) + (
        f"create_atoms 1 single {length * np.sin(amplitude)!r} {-length * np.cos(amplitude)!r} 0\n"
    ) + styles(2, extra=" coulomb_cutback") + f"""fix down all gravity {g} vector 0 -1 0
fix w all wall/gran/mn zcylinder NULL {radius}
timestep {dt!r}
thermo 0
variable t equal step*dt
fix trace all print {int(round(0.01 / dt))} "$(v_t:%.15g) $(x[1]:%.15g)" file trace.txt screen no
run {int(round(3.2 * period / dt))}
"""
    trace = run_lammps(deck, tmp_path, header=False).table("trace.txt")
    t, x = trace[:, 0], trace[:, 1]
    crossing = np.nonzero((x[:-1] > 0) & (x[1:] <= 0))[0]
    times = t[crossing] - x[crossing] * (t[crossing + 1] - t[crossing]) / (x[crossing + 1] - x[crossing])
    measured = np.mean(np.diff(times))
    print(f"period {measured:.5f}, rolling pendulum {period:.5f} ({len(times)} crossings)")
    assert len(times) >= 3
    assert abs(measured - period) < 0.005 * period


def test_sphere_pressed_against_the_inside_rolls_down_at_five_sevenths_g_z(tmp_path):
    """3D: gravity (1, 0, -0.2) presses a sphere against the outer cylinder's wall at +x and
    pulls it along -z (periodic): it rolls down the wall without sliding (mu = 0.5 > 2/7 0.2)
    at a = 5/7 g_z = 0.1429, within 0.5 %, and stays on the wall's line y = 0."""
    g_x, g_z = 1.0, 0.2
    dt = law(KN, E, BETA)["tau_c"] / 50
    deck = header(3) + box(3) + f"create_atoms 1 single {4.5 - g_x / KN!r} 0 0\n" + styles(
        3, extra=" coulomb_cutback") + f"""fix down all gravity 1.0 vector {g_x} 0 0
fix w all wall/gran/mn zcylinder NULL 5.0
timestep {dt!r}
thermo 0
run {int(round(2 / dt))}
unfix down
fix down all gravity {np.hypot(g_x, g_z)!r} vector {g_x} 0 {-g_z}
variable t equal step*dt
fix trace all print {int(round(0.05 / dt))} "$(v_t:%.15g) $(vz[1]:%.15g) $(y[1]:%.15g)" file trace.txt screen no
run {int(round(4 / dt))}
"""
    trace = run_lammps(deck, tmp_path, header=False).table("trace.txt")
    t, vz = trace[:, 0] - trace[0, 0], trace[:, 1]
    late = t > 1.0
    slope = -np.polyfit(t[late], vz[late], 1)[0]
    print(f"a = {slope:.6f}, 5/7 g_z = {5 / 7 * g_z:.6f}")
    assert abs(slope - 5 / 7 * g_z) < 0.005 * 5 / 7 * g_z
    assert np.abs(trace[:, 2]).max() < 1e-9


def test_the_counters_count_a_cylinder_contact(tmp_path):
    """fix contacts/mn counts the radial bounce off the outer cylinder as one boundary contact
    begun (none between disks), and writes its row, whose normal velocities at the start and
    the end give the bounce's e_w (the end's was once written as 0: the cylinder's normal was
    taken only in contact, and the contact's end is the first step out of it)."""
    dt = law(KN, E, BETA)["tau_c"] / 100
    deck = header(2) + box(2) + "create_atoms 1 single 4.49 0 0\n" + styles(2) + f"""set atom 1 vx 1.0
fix w all wall/gran/mn zcylinder NULL 5.0
fix c all contacts/mn local 100
dump rows all local 100 rows.txt f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] f_c[6] f_c[7] f_c[8]
timestep {dt!r}
thermo 0
run 600
print "RESULT counters $(f_c[1]) $(f_c[2])"
"""
    run = run_lammps(deck, tmp_path, header=False)
    assert run.result("counters") == [0.0, 1.0]
    # the rows of every dump block: the lines of 8 numbers
    rows = [line.split() for line in (run.workdir / "rows.txt").read_text().splitlines()
            if len(line.split()) == 8 and not line.startswith("ITEM")]
    assert len(rows) == 1
    assert rows[0][1:3] == ["0", "2"]    # a wall (ID 0), a boundary contact
    vn_start, vn_end = float(rows[0][5]), float(rows[0][6])
    e_w = law(KN, E, BETA)["e_w"]
    print(f"row: vn {vn_start:.5f} -> {vn_end:.5f}, e_w {e_w:.5f}")
    assert vn_start == pytest.approx(-1.0, abs=1e-3)
    assert abs(-vn_end / vn_start - e_w) <= restitution_error_bound(e_w, 1 / 100)


# Disks in the annulus between the two cylinders, under gravity, with friction, the contact
# counters and Adams-Bashforth 2 (so that an atom's row holds each side's u_t, record and
# touching flag, and previous v_t); HALF steps, then as many again.
ANNULUS = """boundary f f p
region box block -6 6 -6 6 -0.5 0.5
create_box 1 box
region outer cylinder z 0 0 4.4 -0.5 0.5
region inner cylinder z 0 0 2.1 -0.5 0.5 side out
region ring intersect 2 outer inner
lattice sq 1.0
create_atoms 1 region ring
set type 1 diameter 0.9
set type 1 density 1.2732395447351628
velocity all create 1.0 87287 loop geom
"""
ANNULUS_STYLES = """pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5
pair_coeff * *
timestep 0.0002
fix w all wall/gran/mn zcylinder 1.5 5.0
fix c all contacts/mn local 200
fix integrate all nve/ab2
fix down all gravity 1.0 vector 0 -1 0
thermo 0
"""
ANNULUS_SECOND_HALF = """dump rows all local 200 rows.txt f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] f_c[6] f_c[7] f_c[8]
dump_modify rows format float %.17g
run {half}
write_dump all custom final.txt id x y vx vy omegaz modify sort id format float %.17g
"""
HALF = 10000
# The annulus at step HALF, written (`run {HALF}` then `write_restart`) by the plugin of restart
# layout 1 (fix checkpoint/mn's number), which kept an atom's row of fix wall/gran/mn as u_t of
# both sides, each side's record and touching flag, the previous v_t of both.
LAYOUT_1_RESTART = Path(__file__).resolve().parent / "restart_files" / "annulus_layout1.restart"


def rows_after(run, step):
    """The lines of the dump blocks of rows.txt after `step` (the block at `step` itself holds
    the rows of the run before, which a restart file does not carry)."""
    kept, at, lines = [], None, (run.workdir / "rows.txt").read_text().splitlines()
    for k, line in enumerate(lines):
        if k > 0 and lines[k - 1] == "ITEM: TIMESTEP":
            at = int(line)
        if at is not None and at > step:
            kept.append(line)
    return kept


@pytest.mark.skipif(os.environ.get("GRANMN_LAMMPS_GENERATION", "debian12") != "debian12",
                    reason="the file is of LAMMPS 29 Sep 2021: LAMMPS 4 Feb 2025 and 4 Jul 2026 "
                           "continue it into another trajectory than the uninterrupted run "
                           "(which is 2021's), with the plugin that wrote it as with this one")
def test_a_restart_file_of_the_layout_before_continues_the_run(tmp_path):
    """A restart file whose wall rows are of restart layout 1 is read into the slots: the run
    continued from it gives the uninterrupted run's contact rows and final state to the bit.
    Rows read as if in slots (or not at all) lose the u_t, the records and the touching flags
    of the contacts held at the restart: their rows' start, peak and the trajectory differ."""
    uninterrupted = run_lammps(header(2) + ANNULUS + ANNULUS_STYLES + f"run {HALF}\n"
                               + ANNULUS_SECOND_HALF.format(half=HALF), tmp_path / "whole",
                               header=False)
    continued = run_lammps(f"plugin load {PLUGIN}\nread_restart {LAYOUT_1_RESTART}\n"
                           "neighbor 0.1 bin\ncomm_modify vel yes\n" + ANNULUS_STYLES
                           + ANNULUS_SECOND_HALF.format(half=HALF), tmp_path / "continued",
                           header=False)
    rows = rows_after(uninterrupted, HALF)
    wall_rows = [line for line in rows if line.split()[1:3] == ["0", "2"]]
    print(f"{len(wall_rows)} rows of wall contacts after the restart")
    assert len(wall_rows) > 20
    assert rows_after(continued, HALF) == rows
    assert ((continued.workdir / "final.txt").read_text()
            == (uninterrupted.workdir / "final.txt").read_text())
