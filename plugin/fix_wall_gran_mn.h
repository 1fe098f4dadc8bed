/* -*- c++ -*- ----------------------------------------------------------
   fix wall/gran/mn: flat and cylindrical walls with the boundary rule of the gran/mn law (2D:
   xplane, yplane, zcylinder; 3D: also zplane).
------------------------------------------------------------------------- */

#ifndef LMP_FIX_WALL_GRAN_MN_H
#define LMP_FIX_WALL_GRAN_MN_H

#include "fix_wall_gran_mn_base.h"

namespace LAMMPS_NS {

class FixWallGranMN : public FixWallGranMNBase {
 public:
  FixWallGranMN(class LAMMPS *, int, char **);
  void init() override;
  void post_force(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  void unpack_restart(int, int) override;

 private:
  static constexpr int ZCYLINDER = 3;
  int axis;                   // 0: xplane, 1: yplane, 2: zplane (dimension 3), ZCYLINDER
  double lo, hi;              // wall positions (a zcylinder's radii); only those flagged exist
  bool has_lo, has_hi;
  // Where each side's values sit in an atom's row: side 0 (lower) in slot 0, 1 in slot 1
  granmn::ContactLayout side_layout[2];
  // The restart file read holds the rows in slots (see write_restart)
  bool restart_rows_in_slots;

  void init_geometry() override;
  bool within_reach(int i, double reach) override;
  template <int DIM> void post_force_for(bool cylinder, bool observed);
  template <int DIM, bool CYLINDER, bool OBSERVED> void post_force_loop();
  // called from post_force_loop only: hidden, so that the call is direct, not through the PLT
  template <int DIM, bool CYLINDER, bool OBSERVED>
  __attribute__((noinline, visibility("hidden"))) void
  touching_side(int i, int side, double dist, double rho, double dt_history, double *on_walls);
  template <int DIM, bool CYLINDER>
  __attribute__((noinline, visibility("hidden"))) void
  side_ended(int i, int side, double dist, double rho, double dt_history);
};

}    // namespace LAMMPS_NS

#endif
