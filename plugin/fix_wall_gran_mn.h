/* -*- c++ -*- ----------------------------------------------------------
   fix wall/gran/mn: flat and cylindrical walls with the boundary rule of the gran/mn law (2D:
   xplane, yplane, zcylinder; 3D: also zplane).
------------------------------------------------------------------------- */

#ifndef LMP_FIX_WALL_GRAN_MN_H
#define LMP_FIX_WALL_GRAN_MN_H

#include "fix_per_atom_state.h"
#include "granmn_contact_storage.h"
#include "granmn_law_arguments.h"

#include "mn_contact_events.h"
#include "mn_integration.h"

#include <vector>

namespace LAMMPS_NS {

class FixWallGranMN : public FixPerAtomState, public granmn::HeldContacts {
 public:
  FixWallGranMN(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void pre_neighbor() override;
  void post_force(int) override;
  double compute_vector(int) override;
  // With a contact observer (fix contacts/mn): the wall sides atom i touches (as of this fix's
  // last evaluation).
  int contacts_held(int i) const override;

 private:
  static constexpr int ZCYLINDER = 3;
  int axis;                   // 0: xplane, 1: yplane, 2: zplane (dimension 3), ZCYLINDER
  double lo, hi;              // wall positions (a zcylinder's radii); only those flagged exist
  bool has_lo, has_hi;
  // Law keywords given on the fix line; what is not given comes from pair_style gran/mn.
  granmn::LawArguments parsed;
  mn::Law law;
  bool own_law;               // the law is not exactly the pair style's
  bool use_history;           // mu > 0: u_t per atom and side (fixed at the fix's definition)
  mn::Integrator integrator;    // the run's, found at init
  // Where each side's values sit in an atom's row of the state: side 0 lower, 1 upper
  granmn::ContactLayout side_layout[2];
  granmn::ContactObserver *observer;    // nullptr unless fix contacts/mn is defined
  double wall_force[3], wall_force_all[3];    // x, y (and z in dimension 3)
  double force_per_mass_acceleration;    // 1/ftm2v: mass x acceleration in force units
  bool force_reduced;
  // The atoms that can touch a side before the next neighbour-list build, in index
  // order: those within the neighbour skin of a side at the last build, and any still holding
  // a contact's state. Between builds an atom moves less than the skin (LAMMPS's trigger is
  // half of it) and keeps its index; an atom left out holds no state. Under a fix adapt
  // (radii_change) a disk can grow into a wall without moving: every atom is listed.
  std::vector<int> near_wall;
  bool radii_change;

  void resolve_law();
  void list_near_wall();
  bool holds_state(int i) const;
  template <int DIM> void post_force_for(bool cylinder, bool observed);
  template <int DIM, bool CYLINDER, bool OBSERVED> void post_force_loop();
  // called from post_force_loop only: hidden, so that the call is direct, not through the PLT
  template <int DIM, bool CYLINDER, bool OBSERVED>
  __attribute__((noinline, visibility("hidden"))) void
  touching_side(int i, int side, double dist, double rho, double dt_history, double *on_walls);
  template <bool CYLINDER>
  __attribute__((noinline, visibility("hidden"))) void side_ended(int i, int side, double rho);
};

}    // namespace LAMMPS_NS

#endif
