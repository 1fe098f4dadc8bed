"""neighbor multi with size intervals finds the same contacts as neighbor bin: its cutoffs come
from the disks' radii (through Pair::atom2cut/radii2cut before LAMMPS 4 Jul 2026, which gran/mn
overrides; LAMMPS's own 2 r and r_i + r_j from then on, plugin/granmn_compat.h)."""
import numpy as np

from granmn_run import run_lammps

# 81 disks of diameters 0.8-1.0 on a square lattice of spacing 0.9: neighbours whose radii sum
# past 0.9 overlap, by multiples of 0.001
PACKED = """
region box block 0 9 0 9 -0.5 0.5
create_box 1 box
lattice sq 0.9 origin 0.5 0.5 0
create_atoms 1 box
lattice none 1.0
variable diameter atom "0.8 + 0.2*((id*7919)%100)/100"
set group all diameter v_diameter
set type * density/disc 1.2732395447351628
pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5
pair_coeff * *
timestep 1e-4
fix integrate all nve/sphere disc
fix flat all enforce2d
run 0
write_dump all custom forces.txt id fx fy modify sort id format float %.17g
"""
MULTI = "neighbor 0.1 multi\nneigh_modify collection/interval 2 0.9 1.0\n"


def forces(tmp_path, neighbor):
    run_lammps(neighbor + PACKED, tmp_path / neighbor.split()[2])
    return np.loadtxt(tmp_path / neighbor.split()[2] / "forces.txt", skiprows=9)[:, 1:]


def test_multi_with_size_intervals_finds_the_same_contacts_as_bin(tmp_path):
    binned = forces(tmp_path, "neighbor 0.1 bin\n")
    multi = forces(tmp_path, MULTI)
    touching = np.hypot(binned[:, 0], binned[:, 1]) > 0
    assert touching.sum() >= 10
    # the same few contact forces per disk summed in another order: equal to a few ulps of the
    # largest (1e-12 of it bounds that); a contact the multi list missed (cutoffs of zero, or of
    # the types' largest disks only) would change a force by a whole contact force, 1e2 or more here
    assert np.allclose(multi, binned, rtol=0, atol=1e-12 * np.abs(binned).max())
