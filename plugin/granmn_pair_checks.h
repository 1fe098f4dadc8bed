/* -*- c++ -*- ----------------------------------------------------------
   What pair_style gran/mn checks of the input beyond the law's own values: the atom style, a
   second gran/mn, the neighbour builds, the plane of a 2D run, the contact history against a
   restart file's, and at a run's setup fix deform and special_bonds.
------------------------------------------------------------------------- */

#ifndef LMP_GRANMN_PAIR_CHECKS_H
#define LMP_GRANMN_PAIR_CHECKS_H

#include "lammps.h"

namespace LAMMPS_NS {
class Pair;
}

namespace granmn {

void check_sphere_attributes(LAMMPS_NS::LAMMPS *lmp);
void check_one_gran_mn(LAMMPS_NS::LAMMPS *lmp, const LAMMPS_NS::Pair *self);
void warn_builds_once(LAMMPS_NS::LAMMPS *lmp);
void check_in_plane(LAMMPS_NS::LAMMPS *lmp);
// needed: the history values per contact the run needs; set_up: those of the history the
// style has (-1: none yet); restored: those of a restart file read (-1: none).
void check_history_size(LAMMPS_NS::LAMMPS *lmp, int needed, int set_up, int restored);
// sends_ghost_velocity: the style sends the ghosts' velocities itself (LAMMPS does not).
void check_deform_remap(LAMMPS_NS::LAMMPS *lmp, bool sends_ghost_velocity);
void check_special_bonds(LAMMPS_NS::LAMMPS *lmp);

}    // namespace granmn

#endif
