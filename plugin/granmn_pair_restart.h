/* -*- c++ -*- ----------------------------------------------------------
   What pair_style gran/mn keeps of its settings in a restart file: the material, the options,
   the bump types and the size of a contact's history, in the order files of today hold them.
------------------------------------------------------------------------- */

#ifndef LMP_GRANMN_PAIR_RESTART_H
#define LMP_GRANMN_PAIR_RESTART_H

#include "lammps.h"

#include "mn_contact.h"

#include <cstdio>
#include <vector>

namespace granmn {

struct PairSettings {
  mn::Material material;
  mn::Options options;
  std::vector<int> bump_types;
  int history_size;    // values per contact of the neighbour history (0: none kept)
};

void write_pair_settings(FILE *fp, const PairSettings &settings);
// Read on process 0, handed to all.
PairSettings read_pair_settings(LAMMPS_NS::LAMMPS *lmp, FILE *fp);

}    // namespace granmn

#endif
