/* -*- c++ -*- ----------------------------------------------------------
   fix nve/ab2: the paper's integrator for disks (Mitarai & Nakanishi 2003):
   second-order Adams-Bashforth for velocities and spins, trapezoidal rule for positions.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_NVE_AB2_H
#define LMP_FIX_NVE_AB2_H

#include "fix.h"

namespace LAMMPS_NS {

class FixNVEAB2 : public Fix {
 public:
  FixNVEAB2(class LAMMPS *, int, char **);
  ~FixNVEAB2() override;
  int setmask() override;
  void init() override;
  void initial_integrate(int) override;

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

 private:
  // Per atom: the accelerations of the previous step (a_x, a_y, alpha_z), and 1 once they exist.
  enum { AX, AY, ALPHA, HAS_PREVIOUS, NSTATE };
  double **previous;
};

}    // namespace LAMMPS_NS

#endif
