/* -*- c++ -*- ----------------------------------------------------------
   fix wall/gran/region/mn: the surface of any LAMMPS region as a wall with the boundary rule
   of the gran/mn law (2D and 3D; moving and rotating regions; several faces at once).
------------------------------------------------------------------------- */

#ifndef LMP_FIX_WALL_GRAN_REGION_MN_H
#define LMP_FIX_WALL_GRAN_REGION_MN_H

#include "fix_wall_gran_mn_base.h"
#include "granmn_region_surface.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

// An atom's slots (as many as the region's tmax: the faces one atom can touch at once) hold the
// faces it touches in slots 0 to [HELD] - 1, each keyed by the face's number
// (SurfaceContact::iwall), whether an observer is defined or not.
class FixWallGranRegionMN : public FixWallGranMNBase {
 public:
  FixWallGranRegionMN(class LAMMPS *, int, char **);
  void setup(int) override;
  void post_force(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

 private:
  std::string region_id;
  granmn::RegionSurface surface;    // the region's faces, and the parts they belong to
  // A moving part's velocity at the last step evaluated (track_motion), and its displacement
  // and angle there; one per part of the region (surface.parts()), used where the part moves
  struct Motion {
    static constexpr int SIZE = 14;    // step, v, omega, rpoint, at (displacement, angle)
    bigint step = -1;
    double v[3] = {0.0, 0.0, 0.0}, omega[3] = {0.0, 0.0, 0.0}, rpoint[3] = {0.0, 0.0, 0.0};
    double at[4] = {0.0, 0.0, 0.0, 0.0};
  };
  std::vector<Motion> motions;
  // The region's face layout when the fix last evaluated it: a region defined again with
  // another (its faces numbered otherwise) ends every contact at the next run's start
  std::string evaluated_layout;
  bool faces_renumbered;

  void find_region();
  void init_geometry() override;
  bool within_reach(int i, double reach) override;
  bool surface_moves() const override;
  bool can_move() const override { return true; }
  void track_motion();
  Motion motion_between(const Region *part, const double *at, const double *before) const;
  void wall_velocity(const granmn::SurfaceContact &face, const double *x, double *v) const;
  bool find_left_face(int i, int face, granmn::SurfaceContact &near, double v_wall[3]);
  template <int DIM>
  void face_left(int i, int face, const double *record, const double *ut, double *energy,
                 double dt_history);
  template <int DIM> void post_force_loop();
};

}    // namespace LAMMPS_NS

#endif
