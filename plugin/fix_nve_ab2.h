/* -*- c++ -*- ----------------------------------------------------------
   fix nve/ab2: the paper's integrator for disks (Mitarai & Nakanishi 2003):
   second-order Adams-Bashforth for velocities and spins, trapezoidal rule for positions.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_NVE_AB2_H
#define LMP_FIX_NVE_AB2_H

#include "fix_per_atom_state.h"

namespace LAMMPS_NS {

class FixNVEAB2 : public FixPerAtomState {
 public:
  FixNVEAB2(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void initial_integrate(int) override;


 private:
  // Per atom: the accelerations of the previous step (a_x, a_y, alpha_z), and 1 once they exist.
  enum { AX, AY, ALPHA, HAS_PREVIOUS, NSTATE };
};

}    // namespace LAMMPS_NS

#endif
