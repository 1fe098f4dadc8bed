/* -*- c++ -*- ----------------------------------------------------------
   Where the gran/mn styles keep a contact's history: u_t, the previous v_t, the observer's
   record and flag (mn_contact_events.h), in the pair style's neighbour history and the wall
   fixes' per-atom slots; and how far a force evaluation advances it.
------------------------------------------------------------------------- */

#ifndef LMP_GRANMN_CONTACT_STORAGE_H
#define LMP_GRANMN_CONTACT_STORAGE_H

#include "domain.h"
#include "lammps.h"
#include "update.h"

#include "mn_contact_events.h"

namespace granmn {

// The time over which a force evaluation advances u_t: none for the forces LAMMPS re-evaluates
// in a run's setup (u_t must not advance twice for one step).
inline double history_dt(LAMMPS_NS::Update *update)
{
  return update->setupflag ? 0.0 : update->dt;
}

// u_t's components: a scalar along t in 2D, a vector in the tangent plane in 3D (a constant
// where the dimension is one, as in the styles' loops).
constexpr int ut_width(int dimension)
{
  return dimension == 3 ? 3 : 1;
}

inline int ut_width(LAMMPS_NS::LAMMPS *lmp)
{
  return ut_width(lmp->domain->dimension);
}

// Where a contact's values sit in the storage of the style that keeps it (-1: not kept),
// handed out at init: in the pair style's neighbour history (pair_history_layout), in a wall
// fix's per-atom state for each slot (WallSlots). The styles hand the
// record to the contact observer (mn_contact_events.h), which knows what a record holds, not
// where it is.
struct ContactLayout {
  int ut_width = 1;        // u_t's components: one in 2D, three in 3D (granmn::ut_width)
  int ut = -1;             // u_t, ut_width values (mu > 0)
  int vt_previous = -1;    // v_t at the previous force evaluation, ut_width values: Adams-
                           // Bashforth 2's rule for u_t (mu > 0)
  int record = -1;         // the observer's record (RECORD_SIZE values)
  int touching = -1;       // 1 while in contact (a plane wall's side: its slot's key; a pair
                           // has its neighbour flag)
  int energy = -1;         // the contact's energy history (mn::energy_history_size values),
                           // where the observer books energies
  int size = 0;            // values the pair style's neighbour history holds per contact
};

// A contact's neighbour history: its parts one after the other, only those kept (restart files
// hold the history in this order); energy_size: the energy history's values (0: none kept).
inline ContactLayout pair_history_layout(bool friction, bool adams_bashforth, bool observed,
                                         int ut_width = 1, int energy_size = 0)
{
  ContactLayout layout;
  layout.ut_width = ut_width;
  auto take = [&layout](bool kept, int width) {
    if (!kept) return -1;
    layout.size += width;
    return layout.size - width;
  };
  layout.ut = take(friction, layout.ut_width);
  layout.vt_previous = take(friction && adams_bashforth, layout.ut_width);
  layout.record = take(observed, RECORD_SIZE);
  layout.energy = take(energy_size > 0, energy_size);
  return layout;
}

// An atom's row in a wall fix's per-atom state: `count` slots, one for each contact it can
// hold at once (a plane wall's two sides, a region's faces an atom can touch at once). [HELD]
// the contacts held and [key(k)] slot k's key: the element it holds (a region's face number; a
// plane's side, 1 while it touches); then u_t of each slot, the observer's record of each, the
// previous v_t of each: each block at a place of its own whether kept or not, so that a block
// kept from a later run on moves no other (restart files hold the rows so). A fix keeps the row
// up to its last block kept. u_t and v_t have ut_width values each. With energies booked
// (fix contacts/mn energy yes) each slot's energy history follows, energy_size values a slot
// from end() on: a run without them keeps the rows as before.
struct WallSlots {
  static constexpr int HELD = 0;
  int count = 0;
  int ut_width = 1;

  int key(int slot) const { return 1 + slot; }
  int ut_block() const { return 1 + count; }
  int record_block() const { return ut_block() + count * ut_width; }
  int vt_block() const { return record_block() + count * RECORD_SIZE; }
  int end() const { return vt_block() + count * ut_width; }
};

}    // namespace granmn

#endif
