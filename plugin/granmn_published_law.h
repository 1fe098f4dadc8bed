/* -*- c++ -*- ----------------------------------------------------------
   pair_style gran/mn's law where decks and readers of the log find it: its derived values as
   the v_mn_* variables (mn_output_schema.h names them), and a report of them in the log.
------------------------------------------------------------------------- */

#ifndef LMP_GRANMN_PUBLISHED_LAW_H
#define LMP_GRANMN_PUBLISHED_LAW_H

#include "lammps.h"

#include "mn_contact.h"

namespace granmn {

// Sets the internal variables, so that decks can read the derived scales, e.g. timestep
// $(v_mn_tau_c/100); a variable of that name that the deck defined is an error.
void publish_law_variables(LAMMPS_NS::LAMMPS *lmp, const mn::Law &law);

// The law and its derived values, with the largest stable step of each integrator, in the log.
void report_law(LAMMPS_NS::LAMMPS *lmp, const mn::Law &law);

}    // namespace granmn

#endif
