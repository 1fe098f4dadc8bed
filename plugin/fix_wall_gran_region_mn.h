/* -*- c++ -*- ----------------------------------------------------------
   fix wall/gran/region/mn: the surface of any LAMMPS region as a wall with the boundary rule
   of the gran/mn law (2D and 3D; moving and rotating regions; several faces at once).
------------------------------------------------------------------------- */

#ifndef LMP_FIX_WALL_GRAN_REGION_MN_H
#define LMP_FIX_WALL_GRAN_REGION_MN_H

#include "fix_per_atom_state.h"
#include "granmn_contact_storage.h"
#include "granmn_law_arguments.h"
#include "granmn_region_surface.h"

#include "mn_contact_events.h"
#include "mn_integration.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixWallGranRegionMN : public FixPerAtomState, public granmn::HeldContacts {
 public:
  FixWallGranRegionMN(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void pre_neighbor() override;
  void post_force(int) override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  // With a contact observer (fix contacts/mn): the faces atom i touches (as of this fix's
  // last evaluation).
  int contacts_held(int i) const override;

 private:
  std::string region_id;
  granmn::RegionSurface surface;    // the region's faces, and the parts they belong to
  int max_contacts;           // the region's tmax: faces one atom can touch at once
  granmn::LawArguments parsed;
  mn::Law law;
  bool own_law;
  bool use_history;           // mu > 0: u_t per atom and face in contact
  mn::Integrator integrator;
  int ut_width;
  // An atom's row: [0] the number of faces it touches, then per slot k < max_contacts the
  // face's number (SurfaceContact::iwall, 1 + k), u_t (ut_block + k ut_width), the contact
  // observer's record (record_block + k RECORD_SIZE) and, under Adams-Bashforth 2, the previous
  // v_t (vt_block + k ut_width): each block at a place of its own whether kept or not, so that
  // a block kept from a later run on moves no other (restart files hold the rows so); the row
  // is kept up to its last block kept.
  int ut_block, record_block, vt_block;    // -1: not kept
  granmn::ContactObserver *observer;      // nullptr unless fix contacts/mn is defined
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
  double wall_force[3], wall_force_all[3];
  double force_per_mass_acceleration;
  bool force_reduced;
  // A region at rest: the atoms that can touch its surface before the next neighbour-list
  // build, in index order (those inside it within the neighbour skin of a face at the last
  // build, those outside it, and any still touching a face), as fix wall/gran/mn's near_wall.
  // A moving region's step visits every atom, and so does every step under a fix adapt
  // (radii_change: an atom can grow into a face without moving).
  std::vector<int> near_surface;
  bool radii_change;

  void find_region();
  void list_near_surface();
  void resolve_law();
  void track_motion();
  Motion motion_between(const Region *part, const double *at, const double *before) const;
  void wall_velocity(const granmn::SurfaceContact &face, const double *x, double *v) const;
  double ended_normal_velocity(int i, int face);
  template <int DIM> void post_force_loop();
};

}    // namespace LAMMPS_NS

#endif
