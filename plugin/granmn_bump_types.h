/* -*- c++ -*- ----------------------------------------------------------
   The atom types pair_style gran/mn takes for immobile bumps (its wall_types keyword): which
   types they are, that their atoms can be bumps, and the neighbour exclusions that keep two
   bumps out of the neighbour list.
------------------------------------------------------------------------- */

#ifndef LMP_GRANMN_BUMP_TYPES_H
#define LMP_GRANMN_BUMP_TYPES_H

#include "lammps.h"

#include <utility>
#include <vector>

namespace granmn {

class BumpTypes {
 public:
  std::vector<int> types;    // as given (restart files keep them in this order)

  // Reads "wall_types T ..." at arg[iarg] into types; returns how many arguments it used, 0 if
  // arg[iarg] is another keyword.
  int parse(LAMMPS_NS::LAMMPS *lmp, int narg, char **arg, int iarg);
  // Checks types against the box's and marks them per type: before is_bump is asked.
  void check_types(LAMMPS_NS::LAMMPS *lmp);
  // The atoms of those types can be bumps: a radius, and no time integration.
  void check_atoms(LAMMPS_NS::LAMMPS *lmp) const;
  // Keeps pairs of two bump types out of the neighbour list, following types when the pair
  // style is given again with others.
  void exclude_bump_pairs(LAMMPS_NS::LAMMPS *lmp);
  // Takes out of the neighbour's type exclusions the ones exclude_bump_pairs added, and no others.
  void release_exclusions(LAMMPS_NS::LAMMPS *lmp);

  bool is_bump(int type) const { return marked[type]; }
  // per type, 1..ntypes: 1 for a bump type (what the force loop reads)
  const char *by_type() const { return marked.data(); }

 private:
  std::vector<char> marked;
  std::vector<std::pair<int, int>> excluded;    // type pairs exclude_bump_pairs added
};

}    // namespace granmn

#endif
