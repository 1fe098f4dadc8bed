/* -*- c++ -*- ----------------------------------------------------------
   The largest radius of each atom type a run will see, which pair_style gran/mn's cut-offs
   follow: of the atoms present and of those fix pour and fix deposit will insert.
------------------------------------------------------------------------- */

#ifndef LMP_GRANMN_INSERTION_RADII_H
#define LMP_GRANMN_INSERTION_RADII_H

#include "lammps.h"

namespace granmn {

// max_radius[type] for types 1..ntypes, the same on every process.
void largest_radii(LAMMPS_NS::LAMMPS *lmp, double *max_radius);

}    // namespace granmn

#endif
