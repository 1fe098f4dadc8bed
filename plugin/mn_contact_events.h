/* -*- c++ -*- ----------------------------------------------------------
   Contacts as events, free of LAMMPS and of the styles' classes: what a style that computes
   contacts (a publisher: pair_style gran/mn, fix wall/gran/mn) tells a style that follows
   them (the observer: fix contacts/mn). Neither includes the other's header.

   A publisher, at its init, looks for the observer among the fixes (find_observer): LAMMPS
   initialises the pair style before any fix (LAMMPS::init: force->init() before
   modify->init()), and the pair style must know then whether its neighbour history keeps a
   record per contact. With no observer a publisher keeps no record and makes no call: a
   scene without fix contacts/mn pays nothing. With one, the publisher keeps RECORD_SIZE
   values per contact (the record: the observer's update_record writes it, starting it anew
   when a contact begins; the publisher keeps it, and may clear it once the contact has
   ended). At every force evaluation a contact touches, the publisher calls update_record
   (inline), then pair_touching or boundary_touching if the contact began at it or the
   observer reports_every_contact() (on one process only the contacts begun need the call;
   where every step's contacts are tallied, a pair style adds each pair to pair_tallies()
   inline instead); at the first evaluation after it ended, pair_ended or boundary_ended.

   A publisher that remembers between force evaluations which contacts it has (a wall fix's
   slots per atom) also implements HeldContacts: the observer finds it among the
   fixes at its init and asks it when it counts contacts anew (a run's setup; every step where
   the pair contacts are tallied; a step after atoms were deleted), so that the count depends
   neither on the order of the fixes' setups nor on the processes.

   A new wall fix plugs in as fix wall/gran/mn and fix wall/gran/region/mn do: derive from
   their base (fix_wall_gran_mn_base.h: it is the HeldContacts, finds the observer at init and
   keeps a record and a key per atom and slot, granmn_contact_storage.h's WallSlots), and report
   each contact as above with update_record, boundary_touching and boundary_ended (the fixes'
   post_force_loop). Fix contacts/mn needs no change.
------------------------------------------------------------------------- */

#ifndef GRANMN_CONTACT_EVENTS_H
#define GRANMN_CONTACT_EVENTS_H

#include "mn_energy.h"
#include "mn_output_schema.h"

namespace granmn {

// What the observer keeps of a contact, its record: RECORD_SIZE values that the publisher
// stores with the contact where its layout says (granmn::ContactLayout).
enum ContactRecord { RECORD_START, RECORD_VN_START, RECORD_PEAK, RECORD_SIZE };

// An evaluation's contacts per atom (owned and ghost atoms), where the observer counts each
// evaluation's contacts anew (fix contacts/mn: on more than one process, or without an atom
// map): contacts, and of them those begun, with particles and with the boundary.
struct ContactTallies {
  double *particle = nullptr, *boundary = nullptr;
  double *begun_particle = nullptr, *begun_boundary = nullptr;

  // One contact of atom i (with a boundary element or not; begun at this evaluation or not).
  void add(int i, bool with_boundary, bool began) const
  {
    (with_boundary ? boundary : particle)[i] += 1.0;
    if (began) (with_boundary ? begun_boundary : begun_particle)[i] += 1.0;
  }
};

// An evaluation's energies per atom (owned and ghost atoms), where the observer books them
// (fix contacts/mn energy yes): the energy the contacts took (normal, tangential) and lost while
// sliding at this evaluation, what their springs store now, and the power of their forces
// (mn::EnergyStep). A contact's share of each goes to each of its atoms (share_i + share_j = 1).
enum StepEnergy { STEP_TAKEN_NORMAL, STEP_TAKEN_TANGENTIAL, STEP_DISSIPATED_SLIDING,
                  STEP_STORED_NORMAL, STEP_STORED_TANGENTIAL, STEP_POWER, STEP_ENERGIES };

struct EnergyTallies {
  double *values = nullptr;    // STEP_ENERGIES per atom
  // The observer's sum of the work the moving walls have done on each local atom, column
  // wall_work_column of its rows: a wall's contacts are its local atoms' own, so that their work
  // needs neither a tally per evaluation nor communication.
  double **work_rows = nullptr;
  int wall_work_column = 0;

  void add(int i, double share, const mn::EnergyStep &booked, const mn::StoredEnergy &stored) const
  {
    double *v = values + STEP_ENERGIES * i;
    v[STEP_TAKEN_NORMAL] += share * booked.taken_normal;
    v[STEP_TAKEN_TANGENTIAL] += share * booked.taken_tangential;
    v[STEP_DISSIPATED_SLIDING] += share * booked.dissipated_sliding;
    v[STEP_STORED_NORMAL] += share * stored.normal;
    v[STEP_STORED_TANGENTIAL] += share * stored.tangential;
    v[STEP_POWER] += share * booked.power;
  }
  // A moving wall's work on local atom i (all of it the atom's); its power is part of the
  // atom's.
  void add_wall_work(int i, const mn::WallWork &wall) const
  {
    work_rows[i][wall_work_column] += wall.work;
    values[STEP_ENERGIES * i + STEP_POWER] += wall.power;
  }
};

// An atom's energies (granmn::output::EnergySum, the per-atom columns and global sums of fix
// contacts/mn energy yes) from its share of what its contacts took from the motion (normal,
// tangential) and lost while sliding since booking began, and of what their springs store now:
// what a contact's force took and its spring does not hold is dissipated (mn::contact_energy).
inline void atom_energy_sums(double taken_normal, double taken_tangential, double slid,
                             double stored_normal, double stored_tangential, double *sums)
{
  using namespace output;
  sums[DISSIPATED_NORMAL] = taken_normal - stored_normal;
  sums[DISSIPATED_SLIDING] = slid;
  sums[DISSIPATED_STICKING] = taken_tangential - stored_tangential - slid;
  sums[STORED] = stored_normal + stored_tangential;
}

class ContactObserver {
 public:
  // The one piece of work the observer needs of every contact at every force evaluation while
  // it touches: its record brought up to date (inline: no call per contact). `began`: at this
  // evaluation; `delta`: the overlap; `vn`: the normal velocity.
  void update_record(double *record, bool began, double delta, double vn) const
  {
    if (began) {
      record[RECORD_START] = now;
      record[RECORD_VN_START] = vn;
      record[RECORD_PEAK] = delta;
    } else if (delta > record[RECORD_PEAK]) {
      record[RECORD_PEAK] = delta;
    }
  }
  // Whether pair_touching / boundary_touching want every contact touching at this evaluation
  // (else only those that began at it).
  bool reports_every_contact() const { return every_contact; }
  // Where the observer counts every evaluation's contacts anew, the tallies a publisher may add
  // a touching pair's shares to (inline), which is all pair_touching would do; else nullptr.
  const ContactTallies *pair_tallies() const { return tallies_every_pair ? &step : nullptr; }

  // Where the observer books the contacts' energies (fix contacts/mn energy yes), the tallies a
  // publisher adds each contact's booking to at every evaluation (inline; a ghost's share as
  // pair_touching's tally_j says); else nullptr: the publisher keeps no energy history and
  // books nothing.
  const EnergyTallies *energy_tallies() const { return books_energy ? &energy_step : nullptr; }

  // Two atoms i, j (local; j may be a ghost) touch, after update_record; `*_is_boundary`: the
  // atom is an immobile bump; `tally_j`: j's share is counted here (owned, or newton on).
  virtual void pair_touching(int i, int j, bool j_is_boundary, bool i_is_boundary, bool began,
                             bool tally_j) = 0;
  // The pair stopped touching (found at the first evaluation after); `write_row`: this
  // process writes the contact's row (a pair stored on two processes has one row);
  // `energy`: what it dissipated, in all and while sliding, where energies are booked (else
  // nullptr).
  virtual void pair_ended(int i, int j, bool j_is_boundary, bool i_is_boundary,
                          const double *record, double vn, bool write_row, bool tally_j,
                          const mn::ContactEnergy *energy) = 0;
  // Local atom i touches a boundary element a fix holds (a wall side), as pair_touching.
  virtual void boundary_touching(int i, bool began) = 0;
  // ... and stopped touching it.
  // energy: what the contact dissipated (nullptr where energies are not booked).
  virtual void boundary_ended(int i, const double *record, double vn,
                              const mn::ContactEnergy *energy) = 0;

 protected:
  ~ContactObserver() = default;
  double now = 0.0;             // the observer's clock at this evaluation: a record's start
  bool every_contact = true;    // reports_every_contact()
  ContactTallies step;          // this evaluation's contacts, where they are tallied
  bool tallies_every_pair = false;    // pair_tallies()
  EnergyTallies energy_step;          // this evaluation's energies, where they are booked
  bool books_energy = false;          // energy_tallies()
};

// An observer that counts every evaluation's contacts anew and keeps no per-contact record
// (LIGGGHTS's fix contacts/mn, plugin/liggghts/): a publisher adds each touching contact to
// tallies() (ContactTallies::add, inline), marking those begun at this evaluation, which it
// tells from a flag it keeps with the contact, and, where energies are booked, each contact's
// booking to energy_tallies(), an ended contact's at the first evaluation after it ended; it
// makes no other call.
class ContactCounter {
 public:
  const ContactTallies &tallies() const { return step; }
  // Where the observer books the contacts' energies (energy yes), the tallies a publisher adds
  // each contact's booking to (EnergyTallies::add); else nullptr.
  const EnergyTallies *energy_tallies() const { return books_energy ? &energy_step : nullptr; }

 protected:
  ~ContactCounter() = default;
  ContactTallies step;          // this evaluation's contacts, owned and ghost atoms
  EnergyTallies energy_step;    // this evaluation's energies, owned and ghost atoms
  bool books_energy = false;    // energy_tallies()
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
// Observer (ContactObserver, ContactCounter), or nullptr.
template <class Observer = ContactObserver, class Fixes>
Observer *find_observer(const Fixes &fixes)
{
  for (auto *fix : fixes)
    if (auto *observer = dynamic_cast<Observer *>(fix)) return observer;
  return nullptr;
}

}    // namespace granmn

#endif
