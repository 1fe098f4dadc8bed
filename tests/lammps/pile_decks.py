"""The pile scene shared by the consistency and counter tests: 48 disks (diameters 0.8-1.0)
on the floor of a box periodic in x, fixed bumps on the floor, a ceiling (fix wall/gran/mn)."""

from granmn_run import law

KN, E, BETA = 2e5, 0.7, 0.7


def styles(mu, tilt=0.3, integrator="nve/sphere disc"):
    """Pair style and time step (both kept in a restart file), then the fixes (not kept)."""
    dt = law(KN, E, BETA)["tau_c"] / 50
    return f"""
pair_style gran/mn kn {KN} e {E} beta {BETA} mu {mu} wall_types 2
pair_coeff * *
timestep {dt!r}
""" + FIXES.format(tilt=tilt, integrator=integrator)


FIXES = """
fix integrate mobile {integrator}
fix flat all enforce2d
fix gravity mobile gravity 1.0 vector {tilt} -1 0
fix floor mobile wall/gran/mn yplane 0.0 11.5
compute contacts mobile contact/atom
compute ncontacts mobile reduce sum c_contacts
variable ncontacts equal c_ncontacts/2
thermo_style custom step ke c_ncontacts
thermo_modify norm no
thermo 1000
"""


# The pile's box is periodic in x only: y holds the floor and the lid (fix wall/gran/mn refuses a
# wall in a periodic dimension). Given before create_box or read_data (a data file holds none).
BOUNDARY = "boundary p f p\n"

PILE = BOUNDARY + """
region box block 0 10 -1 12 -0.5 0.5
create_box 2 box
lattice sq 1.0 origin 0.5 0.5 0
region pile block 0 8 0 6 -0.5 0.5 units lattice
create_atoms 1 region pile
lattice none 1.0
create_atoms 2 single 1.0 -0.45 0
create_atoms 2 single 3.5 -0.45 0
create_atoms 2 single 6.0 -0.45 0
create_atoms 2 single 8.5 -0.45 0
group mobile type 1
group bumps type 2
variable diameter atom "0.8 + 0.2*((id*7919)%100)/100"
set group mobile diameter v_diameter
set group bumps diameter 1.0
set type * density/disc 1.2732395447351628
velocity mobile create 0.5 4928459 loop geom
"""

FINAL = "write_dump mobile custom final.txt id x y vx vy omegaz modify sort id format float %.17g\n"
