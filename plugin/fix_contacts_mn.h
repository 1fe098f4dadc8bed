/* -*- c++ -*- ----------------------------------------------------------
   fix contacts/mn: per-contact counters for the gran/mn styles.
   pair_style gran/mn and fix wall/gran/mn report contacts to it as events
   (mn_contact_events.h); a run without this fix pays nothing for it.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_CONTACTS_MN_H
#define LMP_FIX_CONTACTS_MN_H

#include "atom.h"
#include "fix_per_atom_state.h"
#include "update.h"

#include "mn_contact_events.h"
#include "mn_output_schema.h"

#include <vector>

namespace LAMMPS_NS {

class FixContactsMN : public FixPerAtomState, public granmn::ContactObserver {
 public:
  FixContactsMN(class LAMMPS *, int, char **);
  ~FixContactsMN() override;
  int setmask() override;
  void init() override;
  void setup_pre_force(int) override;
  void pre_force(int) override;
  void setup(int) override;
  void end_of_step() override;
  void post_run() override;
  void reset_dt() override;
  int modify_param(int, char **) override;
  double compute_vector(int) override;

  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // The contact events (mn_contact_events.h), one path for pairs and walls: the style that
  // keeps a contact's record reports it at every force evaluation while in contact and at the
  // first one after it ends (its row, if asked).
  void pair_touching(int i, int j, bool j_is_boundary, bool i_is_boundary, bool began,
                     bool tally_j) override;
  void pair_ended(int i, int j, bool j_is_boundary, bool i_is_boundary, const double *record,
                  double vn, bool write_row, bool tally_j,
                  const mn::ContactEnergy *energy) override;
  void boundary_touching(int i, bool began) override;
  void boundary_ended(int i, const double *record, double vn,
                      const mn::ContactEnergy *energy) override;

 private:
  // The state per atom: the output columns (granmn::output::Counter, mn_output_schema.h: the
  // per-atom array; the global vector adds the window's length and the group's size), then
  // what the times are made of. The times change only when an atom's contacts do:
  // `ACCUMULATED_*` hold each time up to the clock time `SINCE` of the atom's last change,
  // `CONTACTS_*` its contacts since then. The output's time columns are those plus the time
  // since, written at each change and whenever they are read (every `every` steps, at the end
  // of a run), so that no step costs work per contact or per atom; reading them never rounds
  // the sums (the output is a copy).
  enum { ACCUMULATED_PARTICLE = granmn::output::COUNTERS, ACCUMULATED_BOUNDARY,
         ACCUMULATED_MULTIPLE, SINCE, CONTACTS_PARTICLE, CONTACTS_BOUNDARY, STATE_COLS };
  // With energy yes, the state goes on with the atom's share of its contacts' energies: taken
  // (normal, tangential) and lost while sliding since the fix was defined (fix_modify reset
  // leaves them: they are the budget's), stored in its contacts' springs and the power of
  // their forces at the last evaluation, the budget's work in flight (mn_energy.h), and the
  // work the moving walls have done on it since the fix was defined.
  enum { TAKEN_NORMAL = STATE_COLS, TAKEN_TANGENTIAL, SLID, STORED_NORMAL, STORED_TANGENTIAL,
         POWER, IN_FLIGHT, WALL_WORK, STATE_COLS_WITH_ENERGY };
  bool energy;                    // energy yes
  mn::Integrator integrator;      // the run's (the work in flight under Adams-Bashforth 2)
  int row_columns;                // a row's columns: ROW_COLUMNS, more with energy yes
  int nmax_energy;
  double **energy_output;         // the per-atom output with energy yes: the counters, then
                                  // the energies (granmn::output::EnergySum)
  // Tallies of this step's pair contacts (owned + ghost), where contacts are counted anew at
  // a step: at every step on more than one process or without an atom map (brought home by
  // reverse communication, then compared with each atom's contacts), at a run's setup on one.
  // They are `step`, a member of ContactObserver: the pair style adds to them inline. A wall
  // fix's contacts are its atom's own: each begin and end changes the atom at once, and a
  // count anew takes them from what the wall fixes hold (holders).
  int nmax_step;
  // One process: a ghost's contacts are its image's (atom->map), each begin and end of a
  // contact changes its atoms' contacts at once, and a step costs nothing per contact beyond
  // its record. A run's setup counts all contacts anew and corrects any atom that differs
  // (one that lost a partner to delete_atoms, say); so does a step at which atoms were deleted
  // (fix evaporate, lost atoms): a contact with a deleted atom never ends in the force loop.
  bool fold_ghosts;
  bool recounting;             // this step's pair contacts are tallied too (one process: setup,
                               // a step after a deletion)
  bool atoms_deleted;          // since the last count (one process)
  int every;                   // the per-atom output is current at multiples of it
  // The fix's own clock: the time of the current step, the sum of the time steps actually
  // taken (a timestep changed between runs counts from then on; LAMMPS's time restarts at
  // zero after read_restart in this version, this clock does not): base_time at base_step
  // (the last run's start or change of time step), plus the steps since times dt: `now`, a
  // member of ContactObserver (the publishers' update_record reads it).
  double change_time;          // when a change found at this step happened: the last step's
                               // time (a contact found at step n was there for step n's dt)
  bigint clock_step;           // the step `now` belongs to
  double base_time;
  bigint base_step;
  double window_start;         // time at which accumulation (re)started
  // The publishers that remember their contacts (wall fixes), asked at a count anew
  std::vector<const granmn::HeldContacts *> holders;
  int rows_every;              // local rows: contacts completed in the last N steps (0: none)
  std::vector<double> rows;    // the columns of each completed contact, not yet dumped
  double **row_array;
  int nmax_rows;
  // The first rows_handed rows were handed to dump local at step handed_step (a multiple of N);
  // they go at the next step, whatever its number (reset_timestep may move it either way).
  int rows_handed;
  bigint handed_step;
  double vector_sums[granmn::output::VECTOR_SIZE_WITH_ENERGY];
  bigint vector_step;

  void set_recounting(bool);
  void advance_clock();
  void drop_handed_rows();
  int home(int j) const { return j < atom->nlocal ? j : atom->map(atom->tag[j]); }
  void change(int i, double particle, double boundary);
  void ended(const double *record, double tag_i, double tag_j, double kind, double vn_end,
             const mn::ContactEnergy *energy);
  void collect();
  void recount();
  void update_outputs();
  void zero_energy_step();
  void absorb_energies(bool setup);
  static void atom_energies(const double *state, double *sums);
  void grow_step_arrays();
  void zero_step_arrays();
  // the rows to dump local; `hand`: a dump writes them at this step if it is a multiple of N
  void publish_rows(bool hand);
};

// Inline: called for every contact at every step.
// Atom i's contacts change by `particle` and `boundary` at change_time: the time since its
// last change goes to its times as its contacts were, then the output columns are current.
inline void FixContactsMN::change(int i, double particle, double boundary)
{
  using namespace granmn::output;
  double *s = state[i];
  if (atom->mask[i] & groupbit) {
    const double elapsed = change_time - s[SINCE];
    if (s[CONTACTS_PARTICLE] > 0.0) s[ACCUMULATED_PARTICLE] += elapsed;
    if (s[CONTACTS_BOUNDARY] > 0.0) s[ACCUMULATED_BOUNDARY] += elapsed;
    if (s[CONTACTS_PARTICLE] + s[CONTACTS_BOUNDARY] >= 2.0) s[ACCUMULATED_MULTIPLE] += elapsed;
    s[TIME_PARTICLE] = s[ACCUMULATED_PARTICLE];
    s[TIME_BOUNDARY] = s[ACCUMULATED_BOUNDARY];
    s[TIME_MULTIPLE] = s[ACCUMULATED_MULTIPLE];
    s[NOW] = s[CONTACTS_PARTICLE] + particle + s[CONTACTS_BOUNDARY] + boundary;
  }
  s[CONTACTS_PARTICLE] += particle;
  s[CONTACTS_BOUNDARY] += boundary;
  s[SINCE] = change_time;
}

}    // namespace LAMMPS_NS

#endif
