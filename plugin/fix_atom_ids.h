/* -*- c++ -*- ----------------------------------------------------------
   fix GRANMN/ATOM_IDS, internal to pair_style gran/mn (which defines it when it keeps a
   contact history): each atom's ID as it was, carried with the atom. LAMMPS keys per-contact
   history by atom IDs, so an ID that changed (delete_atoms compress yes) loses it; this fix
   says at each run's init that it happened.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_ATOM_IDS_H
#define LMP_FIX_ATOM_IDS_H

#include "fix_per_atom_state.h"

namespace LAMMPS_NS {

class FixAtomIDs : public FixPerAtomState {
 public:
  FixAtomIDs(class LAMMPS *, int, char **);
  int setmask() override { return 0; }
  void init() override;
  void set_arrays(int) override;

 private:
  // Atoms (over all processes) whose ID changed since the last call; records the IDs anew.
  bigint renumbered();
};

}    // namespace LAMMPS_NS

#endif
