"""Decks for single collisions: two disks, a disk on a bump, a disk on the flat wall."""
import math

import numpy as np

from granmn_run import law, run_lammps

DISC_DENSITY = 4 / math.pi    # mass = diameter^2: unit disk has unit mass (docs/model.md section 1)


# the integrator's name: its scheme (verlet or ab2), with the fix that runs it
INTEGRATORS = {"verlet": "nve/sphere disc", "ab2": "nve/ab2",
               "disc/mn verlet": "nve/disc/mn", "disc/mn ab2": "nve/disc/mn scheme ab2"}


def _common(material, dt, extra_styles="", integrator="verlet"):
    kn, e, beta, mu = material
    return f"""
pair_style gran/mn kn {kn!r} e {e!r} beta {beta!r} mu {mu!r} {extra_styles}
pair_coeff * *
timestep {dt!r}
fix integrate mobile {INTEGRATORS[integrator]}
fix flat all enforce2d
variable st equal step
"""


def two_disks(material, dt, v_n=1.0, spin=0.0, d2=1.0, phase=0.5, pre_steps=10, tau=None,
              integrator="verlet"):
    """Disk 1 (diameter 1) moving at +v_n/2 towards disk 2 (diameter d2) at -v_n/2, both with
    spin `spin`; contact begins `phase` of a step after step `pre_steps`."""
    tau = tau or law(material[0], material[1], material[2])["tau_c"]
    contact = 0.5 * (1.0 + d2)
    gap = v_n * (pre_steps + phase) * dt
    steps = pre_steps + int(math.ceil(tau / dt)) + 20
    return f"""
region box block -5 5 -5 5 -0.5 0.5
create_box 1 box
create_atoms 1 single {-0.5 - gap / 2!r} 0 0
create_atoms 1 single {d2 / 2 + gap / 2!r} 0 0
set atom 1 diameter 1.0
set atom 2 diameter {d2!r}
set type 1 density/disc {DISC_DENSITY!r}
velocity all set 0 0 0
set atom 1 vx {v_n / 2!r} omega 0 0 {spin!r}
set atom 2 vx {-v_n / 2!r} omega 0 0 {spin!r}
group mobile type 1
{_common(material, dt, integrator=integrator)}
variable dist equal sqrt((x[1]-x[2])^2+(y[1]-y[2])^2)
fix trace all print 1 "${{st}} ${{dist}}" file trace.txt screen no
thermo 0
run {steps}
write_dump all custom final.txt id x y vx vy omegaz modify sort id format float %.17g
""", contact


def disk_on_boundary(material, dt, boundary, v_n=1.0, phase=0.5, pre_steps=10, spin=0.0,
                     integrator="verlet"):
    """A unit disk falling at v_n (no gravity), spinning at `spin`, onto a fixed bump below it
    (a type-2 atom listed in wall_types, not integrated) or onto the flat wall y = 0 (y not
    periodic: fix wall/gran/mn refuses a wall in a periodic dimension)."""
    tau = law(material[0], material[1], material[2])["tau_w"]
    gap = v_n * (pre_steps + phase) * dt
    steps = pre_steps + int(math.ceil(tau / dt)) + 20
    if boundary == "bump":
        atoms = f"""
create_atoms 2 single 0 0 0
create_atoms 1 single 0 {1.0 + gap!r} 0
"""
        styles = _common(material, dt, "wall_types 2", integrator)
        floor = 0.0
        contact = 1.0
    else:
        atoms = f"create_atoms 1 single 0 {0.5 + gap!r} 0\n"
        styles = (_common(material, dt, integrator=integrator) +
                  "fix floor mobile wall/gran/mn yplane 0.0 NULL\n")
        floor = 0.0
        contact = 0.5
    return f"""
boundary p f p
region box block -5 5 -5 5 -0.5 0.5
create_box 2 box
{atoms}
set type * diameter 1.0
set type * density/disc {DISC_DENSITY!r}
velocity all set 0 0 0
group mobile type 1
set group mobile vy {-v_n!r} omega 0 0 {spin!r}
{styles}
variable mobile_id equal count(all)
variable height equal y[v_mobile_id]-{floor!r}
fix trace all print 1 "${{st}} ${{height}}" file trace.txt screen no
thermo 0
run {steps}
write_dump all custom final.txt id x y vx vy omegaz modify sort id format float %.17g
""", contact


def contact_interval(trace, contact_distance, dt):
    """Start and end of the contact, linearly interpolated between steps, from a trace of
    (step, centre distance). Returns (duration, first step in contact, last step in contact)."""
    step, dist = trace[:, 0], trace[:, 1]
    inside = np.nonzero(dist < contact_distance)[0]
    if len(inside) == 0:
        raise AssertionError("the disks never touched")
    first, last = inside[0], inside[-1]
    if last + 1 >= len(dist) or np.any(np.diff(inside) != 1):
        raise AssertionError("the contact did not end cleanly within the run")

    def crossing(a, b):
        fa, fb = dist[a] - contact_distance, dist[b] - contact_distance
        return step[a] + (step[b] - step[a]) * fa / (fa - fb)

    return (crossing(last, last + 1) - crossing(first - 1, first)) * dt, first, last


def disk_over_floor(kn, height, dt, mu=0.5):
    """A unit disk at `height` over the flat wall y = 0 under gravity, with counters c (y not
    periodic)."""
    return f"""
boundary p f p
region box block -3 3 -1 5 -0.5 0.5
create_box 1 box
create_atoms 1 single 0 {height!r} 0
set type 1 diameter 1.0
set type 1 density/disc {DISC_DENSITY!r}
group mobile type 1
pair_style gran/mn kn {kn!r} e 0.7 beta 0.7 mu {mu!r}
pair_coeff * *
timestep {dt!r}
fix integrate mobile nve/sphere disc
fix flat all enforce2d
fix gravity mobile gravity 1.0 vector 0 -1 0
fix floor mobile wall/gran/mn yplane 0.0 NULL
fix c mobile contacts/mn
"""


def bounces(tmp_path, kn, height=0.1):
    """Contacts a disk dropped from `height` above the wall makes until it stays there."""
    ref = law(kn, 0.7, 0.7)
    dt = ref["tau_w"] / 50
    steps = int(6.0 / dt)
    deck = f"""
{disk_over_floor(kn, 0.5 + height, dt)}thermo 0
run {steps - int(1.0 / dt)}
variable bounces equal $(f_c[2])
fix_modify c reset
run {int(1.0 / dt)}
print "RESULT bounces ${{bounces}} $(f_c[2]) $(f_c[4]) $(f_c[7])"
"""
    begun, begun_last, t_boundary_last, window_last = run_lammps(
        deck, tmp_path / f"kn{kn:g}").result("bounces")
    # at rest for the last time unit: in contact throughout, no new contact
    assert begun_last == 0 and abs(t_boundary_last - window_last) < 1e-9
    return begun
