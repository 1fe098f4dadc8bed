/* -*- c++ -*- ----------------------------------------------------------
   fix wall/gran/mn: flat walls with the boundary rule of the gran/mn law.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_WALL_GRAN_MN_H
#define LMP_FIX_WALL_GRAN_MN_H

#include "fix.h"

#include "mn_contact.h"

namespace LAMMPS_NS {

class FixWallGranMN : public Fix {
 public:
  FixWallGranMN(class LAMMPS *, int, char **);
  ~FixWallGranMN() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void post_force(int) override;
  double compute_vector(int) override;

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
  int axis;                   // 0: xplane, 1: yplane
  double lo, hi;              // wall positions; only those flagged exist
  bool has_lo, has_hi;
  // Material given on the fix line; what is not given comes from pair_style gran/mn.
  mn::Material material;
  bool given[4];
  mn::Options options;
  bool options_given;
  mn::Law law;
  bool own_law;               // the law is not exactly the pair style's
  bool use_history;           // mu > 0: per-atom u_t, one slot per wall
  double **ut;                // ut[i][0]: lower wall, ut[i][1]: upper wall
  class FixContactsMN *counters;    // nullptr unless fix contacts/mn is defined
  double wall_force[2], wall_force_all[2];
  bool force_reduced;

  void resolve_law();
};

}    // namespace LAMMPS_NS

#endif
