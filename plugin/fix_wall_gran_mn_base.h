/* -*- c++ -*- ----------------------------------------------------------
   What the gran/mn wall fixes share, as LAMMPS's fix wall/gran/region derives from fix
   wall/gran: the law (the fix line's keywords, the rest from pair_style gran/mn), the run's
   checks, the contact observer, the list of atoms near the wall, the contacts' per-atom slots
   (granmn::WallSlots), the force on the wall and its global vector. A wall fix (fix
   wall/gran/mn, fix wall/gran/region/mn) adds its geometry: which elements of the wall (a
   plane's sides, a region's faces) an atom touches, and which slot holds each contact.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_WALL_GRAN_MN_BASE_H
#define LMP_FIX_WALL_GRAN_MN_BASE_H

#include "fix_per_atom_state.h"
#include "granmn_contact_storage.h"
#include "granmn_law_arguments.h"

#include "mn_contact_events.h"
#include "mn_integration.h"

#include <vector>

namespace LAMMPS_NS {

class FixWallGranMNBase : public FixPerAtomState, public granmn::HeldContacts {
 public:
  int setmask() override;
  void init() override;
  void setup(int) override;
  void pre_neighbor() override;
  double compute_vector(int) override;
  // With a contact observer (fix contacts/mn): the wall elements atom i touches (as of this
  // fix's last evaluation).
  int contacts_held(int i) const override;

 protected:
  // Refuses an atom style without the attributes the law needs.
  FixWallGranMNBase(class LAMMPS *, int, char **);
  // The law keywords arg[iarg...] (the fix's geometry comes before them), and `nslots` slots
  // per atom (the wall elements one atom can touch at once); `keyed_slots`: the slots' keys and
  // the count are kept in every run (a wall that matches its contacts to slots by key), else
  // only with an observer.
  void define_law_and_slots(int narg, char **arg, int iarg, int nslots, bool keyed_slots);

  // The geometry's checks at init, before the law's.
  virtual void init_geometry() = 0;
  // Whether atom i can touch the wall before the next neighbour-list build: an element of the
  // wall lies within `reach` (its radius and the skin) of its centre, or the geometry says so
  // for another reason (an atom outside a region).
  virtual bool within_reach(int i, double reach) = 0;
  // A wall that moves: every atom is visited.
  virtual bool surface_moves() const { return false; }
  // Whether the wall can move at all (in some run): with energy yes its contacts then keep
  // what booking its work on the atoms needs (mn::moving_wall_energy_history_size).
  virtual bool can_move() const { return false; }

  // Slot `slot`'s energy history in atom i's row, nullptr unless energies are booked.
  double *slot_energy(int i, int slot) const
  {
    return energy_block >= 0 ? state[i] + energy_block + slot * energy_size : nullptr;
  }
  // A touching contact of atom i (kin: mn::wall_kinematics) with its energies booked into
  // energy (slot_energy) and the observer's tallies: the force and torque on i, minus the force
  // into on_walls, as mn::add_wall_contact. v_wall: the wall's velocity at the contact (the one
  // kin subtracts) where it moves, whose work on the atom is booked too; else nullptr. began: a
  // contact new at this evaluation (at a run's setup its account opens with what its springs
  // hold: mn::open_energy_account).
  template <int DIM, class K>
  void add_wall_contact_with_energy(int i, double scale, const K &kin, double *ut,
                                    double dt_history, double *vt_previous, double *energy,
                                    double *on_walls, bool began,
                                    const double *v_wall = nullptr);
  // The first evaluation after atom i's contact along inward normal n ended (its centre at
  // dist from the wall; v_wall as above), its history not yet cleared: its last force's second
  // half booked; what it dissipated in all.
  template <int DIM>
  mn::ContactEnergy book_ended_wall_energy(int i, const double n[3], double dist,
                                           double dt_history, const double *ut, double *energy,
                                           const double *v_wall = nullptr);

  // Ends a force evaluation: the force the atoms exerted on the wall (x, y[, z]).
  void forces_evaluated(const double *on_walls)
  {
    for (int c = 0; c < size_vector; c++) wall_force[c] = on_walls[c];
    force_reduced = false;
  }

  granmn::LawArguments parsed;    // the law keywords given on the fix line
  mn::Law law;
  bool own_law;                   // the law is not exactly the pair style's
  bool use_history;               // mu > 0: u_t per contact (fixed at the fix's definition)
  mn::Integrator integrator;      // the run's, found at init
  double force_per_mass_acceleration;    // 1/ftm2v: mass x acceleration in force units
  granmn::ContactObserver *observer;     // nullptr unless fix contacts/mn is defined
  granmn::WallSlots slots;
  // Where this run keeps each block of the slots (granmn::WallSlots), -1 where it does not
  int ut_block, record_block, vt_block;
  // Where the energy histories start (-1: energies not booked) and their size per slot
  int energy_block, energy_size;
  // The atoms that can touch the wall before the next neighbour-list build, in index order:
  // those within the neighbour skin of an element at the last build, and any still holding a
  // contact's state. Between builds an atom moves less than the skin (LAMMPS's trigger is half
  // of it) and keeps its index; an atom left out holds no state. A moving wall, or a fix adapt
  // (a disk can grow into a wall without moving), lists every atom.
  std::vector<int> near_wall;

 private:
  bool keyed;
  bool radii_change;    // a fix adapt is defined
  double wall_force[3], wall_force_all[3];
  bool force_reduced;

  void resolve_law();
  void keep_slots();
  bool holds_state(int i) const;
  void list_near_wall();
};

}    // namespace LAMMPS_NS

#endif
