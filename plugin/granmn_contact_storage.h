/* -*- c++ -*- ----------------------------------------------------------
   Where the gran/mn styles keep a contact's history: u_t, the previous v_t, the observer's
   record and flag (mn_contact_events.h), in the pair style's neighbour history and the wall
   fix's per-atom state; and how far a force evaluation advances it.
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
// handed out at init: in the pair style's neighbour history (pair_history_layout), in the
// wall fix's per-atom state for each wall side (wall_state_layout). The styles hand the
// record to the contact observer (mn_contact_events.h), which knows what a record holds, not
// where it is.
struct ContactLayout {
  int ut_width = 1;        // u_t's components: one in 2D, three in 3D (granmn::ut_width)
  int ut = -1;             // u_t, ut_width values (mu > 0)
  int vt_previous = -1;    // v_t at the previous force evaluation, ut_width values: Adams-
                           // Bashforth 2's rule for u_t (mu > 0)
  int record = -1;         // the observer's record (RECORD_SIZE values)
  int touching = -1;       // 1 while in contact (a wall side; a pair has its neighbour flag)
  int energy = -1;         // the contact's energy history (mn::energy_history_size values),
                           // where the observer books energies
  int size = 0;            // values the storage holds: per contact (pair), per atom (wall)
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

// An atom's row in the wall fix, both sides: each part at a place of its own whether kept or
// not (u_t of both sides, each side's record and flag, the previous v_t of both), so that a
// part kept from a later run on moves no other (restart files hold the rows so); `size` is
// the whole row's. A style keeps the row up to its last part kept. u_t and v_t have
// ut_width values each.
inline void wall_state_layout(ContactLayout side[2], int ut_width = 1)
{
  side[0].ut_width = side[1].ut_width = ut_width;
  int next = 0;
  for (int s : {0, 1}) {
    side[s].ut = next;
    next += side[s].ut_width;
  }
  for (int s : {0, 1}) {
    side[s].record = next;
    next += RECORD_SIZE;
    side[s].touching = next++;
  }
  for (int s : {0, 1}) {
    side[s].vt_previous = next;
    next += side[s].ut_width;
  }
  side[0].size = side[1].size = next;
}

}    // namespace granmn

#endif
