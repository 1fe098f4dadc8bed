/* -*- c++ -*- ----------------------------------------------------------
   A fix with a per-atom array of doubles that moves with its atom between processors and
   is written to restart files: the bookkeeping the gran/mn fixes share.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_PER_ATOM_STATE_H
#define LMP_FIX_PER_ATOM_STATE_H

#include "fix.h"

namespace LAMMPS_NS {

class FixPerAtomState : public Fix {
 public:
  FixPerAtomState(class LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg) {}
  ~FixPerAtomState() override;

  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  void write_data_header(FILE *, int) override;

 protected:
  double **state = nullptr;    // ncols per atom, zero for new atoms
  int ncols = 0;

  // Gives each atom `columns` values (0: none yet, widen_state adds them) and registers the
  // fix's per-atom callbacks with LAMMPS, which takes them only from a fix being constructed
  // (Atom::add_callback takes the fix being added): a subclass that keeps a state calls it
  // from its constructor, once; one that never calls it pays nothing.
  void register_state(int columns);
  // More columns (zero for every atom) for a need found later, e.g. at init; keeps the others.
  // Needs register_state first.
  void widen_state(int columns);
  // Atom nlocal's record of this fix in the restart file read (the nth fix's with per-atom
  // records): `stored` values.
  const double *restart_row(int nlocal, int nth, int &stored) const;

 private:
  bool has_callbacks = false;
};

}    // namespace LAMMPS_NS

#endif
