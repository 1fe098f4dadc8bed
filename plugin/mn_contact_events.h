/* -*- c++ -*- ----------------------------------------------------------
   Contacts as events, free of LAMMPS and of the styles' classes: what a style that computes
   contacts (a publisher: pair_style gran/mn, fix wall/gran/mn) tells a style that follows
   them (the observer: fix contacts/mn). Neither includes the other's header.

   A publisher, at its init, looks for the observer among the fixes (find_observer): LAMMPS
   initialises the pair style before any fix (LAMMPS::init: force->init() before
   modify->init()), and the pair style must know then whether its neighbour history keeps a
   record per contact. With no observer a publisher keeps no record and makes no call: a
   scene without fix contacts/mn pays nothing. With one, the publisher keeps RECORD_SIZE
   values per contact (the record: the observer writes it, starting it anew when a contact
   begins; the publisher keeps it, and may clear it once the contact has ended) and reports each contact at every force evaluation while it touches, and
   once at the first one after it ended.

   A publisher that remembers between force evaluations which contacts it has (a wall fix's
   flag per atom and side) also implements HeldContacts: the observer finds it among the
   fixes at its init and asks it when it counts contacts anew (a run's setup, a step after
   atoms were deleted), so that the count does not depend on the order of the fixes' setups.

   A new wall fix (a cylinder or region wall, say) plugs in as fix wall/gran/mn does: derive
   from HeldContacts, find the observer at init, keep a record and a touching flag per atom
   and wall element in its per-atom state (granmn_contact_storage.h), and report each contact
   with boundary_touching / boundary_ended. Fix contacts/mn needs no change.
------------------------------------------------------------------------- */

#ifndef GRANMN_CONTACT_EVENTS_H
#define GRANMN_CONTACT_EVENTS_H

namespace granmn {

// What the observer keeps of a contact, its record: RECORD_SIZE values that the publisher
// stores with the contact where its layout says (granmn::ContactLayout).
enum ContactRecord { RECORD_START, RECORD_VN_START, RECORD_PEAK, RECORD_SIZE };

class ContactObserver {
 public:
  // Two atoms i, j (local; j may be a ghost) touch at this force evaluation: `began` at this
  // one, with overlap `delta` and normal velocity `vn`; `*_is_boundary`: the atom is an
  // immobile bump; `tally_j`: j's share is counted here (owned, or newton on).
  virtual void pair_touching(int i, int j, bool j_is_boundary, bool i_is_boundary,
                             double *record, bool began, double delta, double vn,
                             bool tally_j) = 0;
  // The pair stopped touching (found at the first evaluation after); `write_row`: this
  // process writes the contact's row (a pair stored on two processes has one row).
  virtual void pair_ended(int i, int j, bool j_is_boundary, bool i_is_boundary,
                          const double *record, double vn, bool write_row, bool tally_j) = 0;
  // Local atom i touches a boundary element a fix holds (a wall side), as pair_touching.
  virtual void boundary_touching(int i, double *record, bool began, double delta,
                                 double vn) = 0;
  // ... and stopped touching it.
  virtual void boundary_ended(int i, const double *record, double vn) = 0;

 protected:
  ~ContactObserver() = default;
};

// A publisher that remembers its contacts between force evaluations.
class HeldContacts {
 public:
  // The contacts local atom i has with this publisher's boundary elements, as of its last
  // evaluation (0 without an observer: none are kept).
  virtual int contacts_held(int i) const = 0;

 protected:
  ~HeldContacts() = default;
};

// The first of `fixes` (pointers to polymorphic objects, e.g. LAMMPS's Fix *) that is an
// observer, or nullptr.
template <class Fixes> ContactObserver *find_observer(const Fixes &fixes)
{
  for (auto *fix : fixes)
    if (auto *observer = dynamic_cast<ContactObserver *>(fix)) return observer;
  return nullptr;
}

}    // namespace granmn

#endif
