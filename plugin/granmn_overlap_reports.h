/* -*- c++ -*- ----------------------------------------------------------
   What pair_style gran/mn says of particles that overlap too far: the error for two whose
   centres came within the larger radius (and what stops them), the warning for pairs placed
   deep in each other at a run's start.
------------------------------------------------------------------------- */

#ifndef LMP_GRANMN_OVERLAP_REPORTS_H
#define LMP_GRANMN_OVERLAP_REPORTS_H

#include "granmn_bump_types.h"
#include "lammps.h"

#include "mn_contact.h"

namespace LAMMPS_NS {
class NeighList;
}

namespace granmn {

// Atoms i and j, their centres r apart, have passed through each other: an error that says
// what stops them. cutsq: the pair style's squared cut-offs per type pair.
void report_passed_through(LAMMPS_NS::LAMMPS *lmp, const mn::Law &law, const BumpTypes &bumps,
                           double **cutsq, int i, int j, double r);

// Pairs of `list` that overlap deeply (mn::deep_overlap): a warning with their number and the
// deepest.
void warn_deep_overlaps(LAMMPS_NS::LAMMPS *lmp, const mn::Law &law, const BumpTypes &bumps,
                        const LAMMPS_NS::NeighList *list);

}    // namespace granmn

#endif
