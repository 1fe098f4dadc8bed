/* ----------------------------------------------------------------------
   fix contacts/mn: contact counts and times per atom, per-contact rows.
------------------------------------------------------------------------- */

#include "fix_contacts_mn.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "granmn_compat.h"
#include "granmn_run_checks.h"
#include "group.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;
using namespace granmn::output;

// fix ID group contacts/mn [local N] [every M] [energy yes|no]
FixContactsMN::FixContactsMN(LAMMPS *lmp, int narg, char **arg) :
    FixPerAtomState(lmp, narg, arg), energy(false),
    integrator(mn::Integrator::VelocityVerlet), row_columns(ROW_COLUMNS), nmax_energy(0),
    energy_output(nullptr), nmax_step(0),
    fold_ghosts(false), recounting(false), atoms_deleted(false), every(1),
    change_time(0.0), clock_step(0), base_time(0.0), base_step(0), window_start(0.0),
    rows_every(0), row_array(nullptr), nmax_rows(0), rows_handed(0), handed_step(-1),
    vector_step(-1)
{
  int iarg = 3;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "local") == 0) {
      if (iarg + 2 > narg) error->all(FLERR, "Illegal fix contacts/mn command: local needs N");
      rows_every = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (rows_every <= 0)
        error->all(FLERR, "Illegal fix contacts/mn command: local N needs N > 0 steps");
      iarg += 2;
    } else if (strcmp(arg[iarg], "every") == 0) {
      if (iarg + 2 > narg) error->all(FLERR, "Illegal fix contacts/mn command: every needs M");
      every = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (every <= 0)
        error->all(FLERR, "Illegal fix contacts/mn command: every M needs M > 0 steps");
      iarg += 2;
    } else if (strcmp(arg[iarg], "energy") == 0) {
      if (iarg + 2 > narg ||
          (strcmp(arg[iarg + 1], "yes") != 0 && strcmp(arg[iarg + 1], "no") != 0))
        error->all(FLERR, "Illegal fix contacts/mn command: energy needs yes or no");
      energy = strcmp(arg[iarg + 1], "yes") == 0;
      iarg += 2;
    } else {
      error->all(FLERR, "Illegal fix contacts/mn command: unknown keyword {}", arg[iarg]);
    }
  }
  books_energy = energy;
  // end_of_step at every step: on one process it has work only where an output reads the fix
  // or after a deletion; on more it compares every step's tallies with the atoms' contacts
  nevery = 1;
  peratom_flag = 1;
  size_peratom_cols = energy ? COUNTERS + ENERGY_SUMS : COUNTERS;
  peratom_freq = 1;
  vector_flag = 1;
  size_vector = energy ? VECTOR_SIZE_WITH_ENERGY : VECTOR_SIZE;
  global_freq = 1;
  extvector = -1;
  // sums and the group's size are extensive, the window's length is not
  extlist = new int[size_vector];
  for (int k = 0; k < size_vector; k++) extlist[k] = k != WINDOW;
  if (energy) row_columns = ROW_COLUMNS_WITH_ENERGY;
  if (rows_every) {
    local_flag = 1;
    size_local_cols = row_columns;
    size_local_rows = 0;
    local_freq = rows_every;
  }
  restart_global = 1;
  comm_reverse = energy ? 4 + granmn::STEP_ENERGIES : 4;
  register_state(energy ? (int) STATE_COLS_WITH_ENERGY : (int) STATE_COLS);
  // register_state grew the state only (a constructor calls no override): the energies' output
  if (energy) FixContactsMN::grow_arrays(atom->nmax);
  clock_step = base_step = update->ntimestep;
  now = base_time = update->ntimestep * update->dt;
  window_start = now;
}

FixContactsMN::~FixContactsMN()
{
  memory->destroy(step.particle);
  memory->destroy(step.boundary);
  memory->destroy(step.begun_particle);
  memory->destroy(step.begun_boundary);
  memory->destroy(row_array);
  memory->destroy(energy_step.values);
  memory->destroy(energy_output);
  delete[] extlist;
}

int FixContactsMN::setmask()
{
  return PRE_FORCE | END_OF_STEP | POST_RUN;
}

void FixContactsMN::init()
{
  if (granmn::fixes_by_style(modify, "^contacts/mn").size() > 1)
    error->all(FLERR, "Only one fix contacts/mn may be defined");
  holders.clear();
  for (Fix *fix : granmn::all_fixes(modify))
    if (const auto *holder = dynamic_cast<const granmn::HeldContacts *>(fix))
      holders.push_back(holder);
  if (!force->pair_match("gran/mn", 1) && holders.empty())
    error->all(FLERR, "Fix contacts/mn counts the contacts of pair_style gran/mn and fix "
                      "wall/gran/mn; neither is defined");
  integrator = granmn::integrator_in_use(modify);
  fold_ghosts = comm->nprocs == 1 && atom->map_style != Atom::MAP_NONE;
  set_recounting(recounting);
  // during a run, the per-atom output is current every `every` steps (between runs always)
  peratom_freq = every;
}

// Called once per step before any contact is reported: the clock moves on by the step just
// taken, with the time step it was taken with. The time is counted from the last run's start
// or change of time step, (steps since) x dt, not summed step by step: the difference of two
// times, a contact's duration, is then (steps) x dt to one rounding of each.
void FixContactsMN::advance_clock()
{
  change_time = now;
  if (update->ntimestep > clock_step)
    now = base_time + (update->ntimestep - base_step) * update->dt;
  clock_step = update->ntimestep;
}

// Rows handed to dump local at an earlier step (or before a reset_timestep) have been written.
void FixContactsMN::drop_handed_rows()
{
  if (rows_handed && update->ntimestep != handed_step) {
    rows.erase(rows.begin(), rows.begin() + (size_t) rows_handed * row_columns);
    rows_handed = 0;
  }
}

// fix dt/reset changed the time step from the next step on.
void FixContactsMN::reset_dt()
{
  base_time = now;
  base_step = clock_step;
}

/* ---------------------------------------------------------------------- */

void FixContactsMN::grow_step_arrays()
{
  if (atom->nmax <= nmax_step) return;
  nmax_step = atom->nmax;
  memory->destroy(step.particle);
  memory->destroy(step.boundary);
  memory->destroy(step.begun_particle);
  memory->destroy(step.begun_boundary);
  memory->create(step.particle, nmax_step, "contacts/mn:step_particle");
  memory->create(step.boundary, nmax_step, "contacts/mn:step_boundary");
  memory->create(step.begun_particle, nmax_step, "contacts/mn:begun_particle");
  memory->create(step.begun_boundary, nmax_step, "contacts/mn:begun_boundary");
}

void FixContactsMN::zero_step_arrays()
{
  grow_step_arrays();
  const int n = atom->nlocal + atom->nghost;
  for (int i = 0; i < n; i++)
    step.particle[i] = step.boundary[i] = step.begun_particle[i] = step.begun_boundary[i] = 0.0;
}

// This evaluation's energies, zero before the publishers book them (energy yes).
void FixContactsMN::zero_energy_step()
{
  if (!energy) return;
  if (atom->nmax > nmax_energy) {
    nmax_energy = atom->nmax;
    memory->destroy(energy_step.values);
    memory->create(energy_step.values, (bigint) nmax_energy * granmn::STEP_ENERGIES,
                   "contacts/mn:energy_step");
  }
  const bigint n = (bigint) (atom->nlocal + atom->nghost) * granmn::STEP_ENERGIES;
  for (bigint k = 0; k < n; k++) energy_step.values[k] = 0.0;
  energy_step.work_rows = state;
  energy_step.wall_work_column = WALL_WORK;
}

// The evaluation's energies into each owned atom's state (a ghost's share home first: folded
// on one process, brought by collect's reverse communication on more). At a run's setup the
// forces are evaluated again for the same step: nothing is taken, nothing is in flight.
void FixContactsMN::absorb_energies(bool setup)
{
  if (!energy) return;
  using namespace granmn;
  double *values = energy_step.values;
  const int nlocal = atom->nlocal;
  if (fold_ghosts && force->newton_pair)
    for (int g = nlocal; g < nlocal + atom->nghost; g++) {
      const int k = home(g);
      if (k < 0 || k == g) continue;
      for (int c = 0; c < STEP_ENERGIES; c++)
        values[STEP_ENERGIES * k + c] += values[STEP_ENERGIES * g + c];
    }
  const double dt = update->dt;
  for (int i = 0; i < nlocal; i++) {
    const double *v = values + STEP_ENERGIES * i;
    double *s = state[i];
    s[TAKEN_NORMAL] += v[STEP_TAKEN_NORMAL];
    s[TAKEN_TANGENTIAL] += v[STEP_TAKEN_TANGENTIAL];
    s[SLID] += v[STEP_DISSIPATED_SLIDING];
    s[STORED_NORMAL] = v[STEP_STORED_NORMAL];
    s[STORED_TANGENTIAL] = v[STEP_STORED_TANGENTIAL];
    s[IN_FLIGHT] = setup ? 0.0 : mn::work_in_flight(integrator, dt, s[POWER], v[STEP_POWER]);
    s[POWER] = v[STEP_POWER];
  }
}

void FixContactsMN::atom_energies(const double *s, double *sums)
{
  granmn::atom_energy_sums(s[TAKEN_NORMAL], s[TAKEN_TANGENTIAL], s[SLID], s[STORED_NORMAL],
                           s[STORED_TANGENTIAL], sums);
}

// No time passes between runs: the step a run starts at is the clock's, also after
// reset_timestep moved it (either way). On one process the setup's pair contacts are tallied
// as well, to be checked against the atoms' contacts (recount).
void FixContactsMN::setup_pre_force(int)
{
  clock_step = base_step = update->ntimestep;
  base_time = now;
  advance_clock();
  zero_step_arrays();
  zero_energy_step();
  set_recounting(fold_ghosts);
  atoms_deleted = false;
  drop_handed_rows();
}

// On more than one process, this step's tallies are zero before the pair style and the wall
// fix fill them; on one, after atoms were deleted (fix evaporate, atoms lost at this step's
// exchange), this step's contacts are tallied to be counted anew.
void FixContactsMN::pre_force(int)
{
  advance_clock();
  if (!fold_ghosts || atoms_deleted) zero_step_arrays();
  zero_energy_step();
  set_recounting(atoms_deleted);
  atoms_deleted = false;
  drop_handed_rows();
}

// An atom deleted (delflag: LAMMPS moves the last atom into its place) takes its contacts with
// it, which on one process its partners still count. (On more, delflag also marks an atom
// that moved to another process, and each step's contacts are counted anew anyway.)
void FixContactsMN::copy_arrays(int i, int j, int delflag)
{
  FixPerAtomState::copy_arrays(i, j, delflag);
  if (delflag && fold_ghosts) atoms_deleted = true;
}

// On one process only a contact begun has work here, unless the step's pair contacts are
// recounted (reports_every_contact()); on more, the pair style tallies every pair contact
// itself (pair_tallies()) and the wall fixes report only the contacts begun.
void FixContactsMN::set_recounting(bool on)
{
  recounting = on;
  every_contact = recounting;
  tallies_every_pair = !fold_ghosts;
}

void FixContactsMN::pair_touching(int i, int j, bool j_is_boundary, bool i_is_boundary,
                                  bool began, bool tally_j)
{
  if (!fold_ghosts) {
    step.add(i, j_is_boundary, began);
    if (tally_j) step.add(j, i_is_boundary, began);
    return;
  }
  if (began) {
    const int *mask = atom->mask;
    change(i, !j_is_boundary, j_is_boundary);
    if (mask[i] & groupbit) state[i][j_is_boundary ? BEGUN_BOUNDARY : BEGUN_PARTICLE] += 1.0;
    if (tally_j) {
      const int k = home(j);
      change(k, !i_is_boundary, i_is_boundary);
      if (mask[k] & groupbit) state[k][i_is_boundary ? BEGUN_BOUNDARY : BEGUN_PARTICLE] += 1.0;
    }
  }
  if (recounting) {
    step.add(i, j_is_boundary, false);
    if (tally_j) step.add(home(j), i_is_boundary, false);
  }
}

// A wall fix's contact is with an owned atom: changed at once, on any number of processes (a
// count anew takes the wall fixes' contacts from what they hold, contacts_held), so that
// neither the order of the fixes' setups nor the processes matter.
void FixContactsMN::boundary_touching(int i, bool began)
{
  if (!began) return;
  if (atom->mask[i] & groupbit) state[i][BEGUN_BOUNDARY] += 1.0;
  change(i, 0.0, 1.0);
}

void FixContactsMN::boundary_ended(int i, const double *record, double vn,
                                   const mn::ContactEnergy *energy)
{
  change(i, 0.0, -1.0);
  if (atom->mask[i] & groupbit) ended(record, atom->tag[i], 0, KIND_BOUNDARY, vn, energy);
}

void FixContactsMN::pair_ended(int i, int j, bool j_is_boundary, bool i_is_boundary,
                               const double *record, double vn, bool write_row, bool tally_j,
                               const mn::ContactEnergy *energy)
{
  if (fold_ghosts) {
    change(i, -(double) !j_is_boundary, -(double) j_is_boundary);
    if (tally_j) change(home(j), -(double) !i_is_boundary, -(double) i_is_boundary);
  }
  const int *mask = atom->mask;
  if (!write_row || !((mask[i] | mask[j]) & groupbit)) return;
  // the mobile atom first against a bump, else the smaller ID first (v_n is the same either way)
  const tagint *tag = atom->tag;
  if (i_is_boundary) std::swap(i, j);
  const bool boundary = i_is_boundary || j_is_boundary;
  const bool swap = !boundary && tag[j] < tag[i];
  ended(record, tag[swap ? j : i], tag[swap ? i : j], boundary ? KIND_BOUNDARY : KIND_DISKS, vn,
        energy);
}

// A completed contact's row: IDs, kind, start, duration, v_n in and out, peak overlap; with
// energy yes what it dissipated, in all and while sliding (every publisher books it).
void FixContactsMN::ended(const double *record, double tag_i, double tag_j, double kind,
                          double vn_end, const mn::ContactEnergy *energy)
{
  if (!rows_every) return;
  double row[ROW_COLUMNS_WITH_ENERGY];
  row[ROW_ID_I] = tag_i;
  row[ROW_ID_J] = tag_j;
  row[ROW_KIND] = kind;
  row[ROW_START] = record[granmn::RECORD_START];
  row[ROW_DURATION] = now - record[granmn::RECORD_START];
  row[ROW_VN_START] = record[granmn::RECORD_VN_START];
  row[ROW_VN_END] = vn_end;
  row[ROW_PEAK] = record[granmn::RECORD_PEAK];
  if (energy) {
    row[ROW_DISSIPATED] = energy->dissipated();
    row[ROW_DISSIPATED_SLIDING] = energy->dissipated_sliding;
  }
  rows.insert(rows.end(), row, row + row_columns);
}

/* ---------------------------------------------------------------------- */

// More than one process, or no atom map: bring the pair style's ghost tallies home, add the
// contacts begun, and change each atom whose contacts at this step (those tallied and those
// the wall fixes hold) differ from its last.
void FixContactsMN::collect()
{
  if (force->newton_pair) granmn::reverse_comm(comm, this);
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    double *s = state[i];
    if (mask[i] & groupbit) {
      s[BEGUN_PARTICLE] += step.begun_particle[i];
      s[BEGUN_BOUNDARY] += step.begun_boundary[i];
    }
    double boundary = step.boundary[i];
    for (const granmn::HeldContacts *holder : holders) boundary += holder->contacts_held(i);
    const double particle_change = step.particle[i] - s[CONTACTS_PARTICLE];
    const double boundary_change = boundary - s[CONTACTS_BOUNDARY];
    if (particle_change != 0.0 || boundary_change != 0.0)
      change(i, particle_change, boundary_change);
  }
}

// One process, at a run's setup or after a deletion: each atom's contacts are those the pair
// style tallied and those the wall fixes hold (as they keep them, whether they have evaluated
// this step yet or not: each change of theirs is reported). An atom that differs (one whose
// partner was deleted) takes the count from here on.
void FixContactsMN::recount()
{
  set_recounting(false);
  for (int i = 0; i < atom->nlocal; i++) {
    double boundary = step.boundary[i];
    for (const granmn::HeldContacts *holder : holders) boundary += holder->contacts_held(i);
    const double particle_change = step.particle[i] - state[i][CONTACTS_PARTICLE];
    const double boundary_change = boundary - state[i][CONTACTS_BOUNDARY];
    if (particle_change != 0.0 || boundary_change != 0.0)
      change(i, particle_change, boundary_change);
  }
}

// The per-atom output's times as of now, for the atoms in contact (the others' were written
// at their last change).
void FixContactsMN::update_outputs()
{
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    double *s = state[i];
    if (!(mask[i] & groupbit)) continue;
    const double elapsed = now - s[SINCE];
    const double particle = s[CONTACTS_PARTICLE], boundary = s[CONTACTS_BOUNDARY];
    s[TIME_PARTICLE] = s[ACCUMULATED_PARTICLE] + (particle > 0.0 ? elapsed : 0.0);
    s[TIME_BOUNDARY] = s[ACCUMULATED_BOUNDARY] + (boundary > 0.0 ? elapsed : 0.0);
    s[TIME_MULTIPLE] = s[ACCUMULATED_MULTIPLE] + (particle + boundary >= 2.0 ? elapsed : 0.0);
  }
  if (!energy) return;
  for (int i = 0; i < atom->nlocal; i++) {
    double *out = energy_output[i];
    for (int c = 0; c < COUNTERS; c++) out[c] = state[i][c];
    if (mask[i] & groupbit)
      atom_energies(state[i], out + COUNTERS);
    else
      for (int c = 0; c < ENERGY_SUMS; c++) out[COUNTERS + c] = 0.0;
  }
}

// Contacts that exist when a run starts are counted once, at its setup (the global vector
// anew: it may have been read at this step in the last run).
void FixContactsMN::setup(int)
{
  if (fold_ghosts)
    recount();
  else
    collect();
  absorb_energies(true);
  update_outputs();
  // a run that starts at the step the last one ended at, a multiple of N, finds the rows of
  // that step handed and written (a dump writes a step once): the rows of contacts ended at
  // this setup go with the next multiple
  publish_rows(handed_step != update->ntimestep);
  vector_step = -1;
}

// On one process after a deletion, the atoms that lost a partner lose its contact at this
// step, as a contact found ended by this step's force evaluation. The global vector is
// computed anew from here (an output may have read it earlier in this step).
void FixContactsMN::end_of_step()
{
  if (!fold_ghosts) collect();
  if (recounting) recount();
  absorb_energies(false);
  if (update->ntimestep % every == 0) update_outputs();
  if (rows_every && update->ntimestep % rows_every == 0) publish_rows(true);
  vector_step = -1;
}

// Between runs the per-atom output is current (write_dump, variables).
void FixContactsMN::post_run()
{
  update_outputs();
  peratom_freq = 1;
}

void FixContactsMN::publish_rows(bool hand)
{
  if (!rows_every) return;
  const int n = rows.size() / row_columns;
  if (n > nmax_rows) {
    nmax_rows = n;
    memory->destroy(row_array);
    memory->create(row_array, nmax_rows, row_columns, "contacts/mn:rows");
  }
  for (int r = 0; r < n; r++)
    for (int c = 0; c < row_columns; c++) row_array[r][c] = rows[row_columns * r + c];
  array_local = row_array;
  size_local_rows = n;
  // dump local N writes them at this step
  if (hand && update->ntimestep % rows_every == 0) {
    rows_handed = n;
    handed_step = update->ntimestep;
  }
}

int FixContactsMN::pack_reverse_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++) {
    buf[m++] = step.particle[i];
    buf[m++] = step.boundary[i];
    buf[m++] = step.begun_particle[i];
    buf[m++] = step.begun_boundary[i];
    if (energy)
      for (int c = 0; c < granmn::STEP_ENERGIES; c++)
        buf[m++] = energy_step.values[granmn::STEP_ENERGIES * i + c];
  }
  return m;
}

void FixContactsMN::unpack_reverse_comm(int n, int *list, double *buf)
{
  int m = 0;
  for (int k = 0; k < n; k++) {
    const int j = list[k];
    step.particle[j] += buf[m++];
    step.boundary[j] += buf[m++];
    step.begun_particle[j] += buf[m++];
    step.begun_boundary[j] += buf[m++];
    if (energy)
      for (int c = 0; c < granmn::STEP_ENERGIES; c++)
        energy_step.values[granmn::STEP_ENERGIES * j + c] += buf[m++];
  }
}

// fix_modify ID reset: a fresh accumulation window from now on.
int FixContactsMN::modify_param(int narg, char **arg)
{
  if (strcmp(arg[0], "reset") != 0) return 0;
  if (narg > 1)
    error->all(FLERR, "Illegal fix_modify command: fix contacts/mn reset takes no arguments");
  for (int i = 0; i < atom->nlocal; i++) {
    double *s = state[i];
    for (int c = BEGUN_PARTICLE; c <= TIME_MULTIPLE; c++) s[c] = 0.0;
    s[ACCUMULATED_PARTICLE] = s[ACCUMULATED_BOUNDARY] = s[ACCUMULATED_MULTIPLE] = 0.0;
    s[SINCE] = now;
  }
  window_start = now;
  vector_step = -1;
  return 1;
}

// Sums over the group of the per-atom columns, the window's length, the group's size.
double FixContactsMN::compute_vector(int n)
{
  if (vector_step != update->ntimestep) {
    // the times as of now (update_outputs' sums, without writing them)
    double local[COUNTERS] = {0.0};
    const int *mask = atom->mask;
    for (int i = 0; i < atom->nlocal; i++) {
      const double *s = state[i];
      if (!(mask[i] & groupbit)) continue;
      const double elapsed = now - s[SINCE];
      const double particle = s[CONTACTS_PARTICLE], boundary = s[CONTACTS_BOUNDARY];
      local[BEGUN_PARTICLE] += s[BEGUN_PARTICLE];
      local[BEGUN_BOUNDARY] += s[BEGUN_BOUNDARY];
      local[TIME_PARTICLE] += s[ACCUMULATED_PARTICLE] + (particle > 0.0 ? elapsed : 0.0);
      local[TIME_BOUNDARY] += s[ACCUMULATED_BOUNDARY] + (boundary > 0.0 ? elapsed : 0.0);
      local[TIME_MULTIPLE] +=
          s[ACCUMULATED_MULTIPLE] + (particle + boundary >= 2.0 ? elapsed : 0.0);
      local[NOW] += s[NOW];
    }
    MPI_Allreduce(local, vector_sums, COUNTERS, MPI_DOUBLE, MPI_SUM, world);
    vector_sums[WINDOW] = now - window_start;
    vector_sums[GROUP_SIZE] = group->count(igroup);
    if (energy) {
      double energies[ENERGY_SUMS + 2] = {0.0}, atom_sums[ENERGY_SUMS];
      for (int i = 0; i < atom->nlocal; i++) {
        if (!(mask[i] & groupbit)) continue;
        atom_energies(state[i], atom_sums);
        for (int c = 0; c < ENERGY_SUMS; c++) energies[c] += atom_sums[c];
        energies[ENERGY_SUMS] += state[i][IN_FLIGHT];
        energies[ENERGY_SUMS + 1] += state[i][WALL_WORK];
      }
      MPI_Allreduce(energies, vector_sums + VECTOR_SIZE, ENERGY_SUMS + 2, MPI_DOUBLE, MPI_SUM,
                    world);
    }
    vector_step = update->ntimestep;
  }
  return vector_sums[n];
}

/* ---------------------------------------------------------------------- */

double FixContactsMN::memory_usage()
{
  return FixPerAtomState::memory_usage() + 4.0 * nmax_step * sizeof(double) +
      (double) rows.capacity() * sizeof(double) +
      (energy ? (double) nmax_energy * granmn::STEP_ENERGIES * sizeof(double) +
               (double) atom->nmax * (COUNTERS + ENERGY_SUMS) * sizeof(double)
              : 0.0);
}

// The per-atom output is the first COUNTERS columns of the state; with energy yes a copy of
// them followed by the energies, written where the counters are (update_outputs).
void FixContactsMN::grow_arrays(int nmax)
{
  FixPerAtomState::grow_arrays(nmax);
  if (energy) {
    memory->grow(energy_output, nmax, COUNTERS + ENERGY_SUMS, "contacts/mn:energy_output");
    array_atom = energy_output;
  } else {
    array_atom = state;
  }
}

// The first value marks the layout, STATE_LAYOUT: the clock, then the rows not yet dumped,
// gathered from all processes (a run continued from the file dumps them at its next multiple
// of N); the per-atom state holds what the times are made of. Earlier versions of the plugin
// marked other layouts by the same first value (a step >= 0, kept contact start steps;
// -2, the clock alone; -3, clock and rows; the per-atom state of the output columns only):
// refused by it, rather than converted (they lack what this state is made of). With energy
// yes the layout is STATE_LAYOUT_WITH_ENERGY: the rows have the energy columns (the per-atom
// state its columns: LAMMPS's per-atom restart records say how many).
static constexpr double STATE_LAYOUT = -4.0;
static constexpr double STATE_LAYOUT_WITH_ENERGY = -5.0;
static constexpr int CLOCK_VALUES = 4;

void FixContactsMN::write_restart(FILE *fp)
{
  // rows handed to a dump are in its file already
  const int skip = rows_handed * row_columns;
  // not const: a serial LAMMPS's STUBS mpi.h declares the send buffers `void *`
  int mine = (int) rows.size() - skip;
  std::vector<int> counts(comm->nprocs), offsets(comm->nprocs, 0);
  MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, world);
  int total = 0;
  for (int p = 0; p < comm->nprocs; p++) {
    offsets[p] = total;
    total += counts[p];
  }
  std::vector<double> values(CLOCK_VALUES + 1 + (comm->me == 0 ? total : 0));
  MPI_Gatherv(rows.data() + skip, mine, MPI_DOUBLE, values.data() + CLOCK_VALUES + 1,
              counts.data(), offsets.data(), MPI_DOUBLE, 0, world);
  if (comm->me == 0) {
    values[0] = energy ? STATE_LAYOUT_WITH_ENERGY : STATE_LAYOUT;
    values[1] = now;
    values[2] = (double) clock_step;
    values[3] = window_start;
    values[4] = total / row_columns;
    const int size = values.size() * sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(values.data(), sizeof(double), values.size(), fp);
  }
}

void FixContactsMN::restart(char *buf)
{
  double layout;
  memcpy(&layout, buf, sizeof(double));
  if (layout != STATE_LAYOUT && layout != STATE_LAYOUT_WITH_ENERGY)
    error->all(FLERR, "Fix contacts/mn: the restart file was written by a version of the "
                      "gran/mn plugin before 1 Dec 2026 (its counters record begins with {:g}, "
                      "this version's with {:g}), whose counters this version does not read: "
                      "continue the run with the version that wrote it, or start it afresh",
               layout, STATE_LAYOUT);
  double clock[CLOCK_VALUES + 1];
  memcpy(clock, buf, sizeof(clock));
  now = clock[1];
  clock_step = (bigint) clock[2];
  window_start = clock[3];
  // the pending rows go to the first process (dump local gathers them all); kept only if
  // this run asks for rows
  rows.clear();
  rows_handed = 0;
  const bool energy_rows = layout == STATE_LAYOUT_WITH_ENERGY;
  if (rows_every && clock[CLOCK_VALUES] > 0 && energy_rows != energy)
    error->all(FLERR, "Fix contacts/mn: the restart file holds {:g} contact rows not yet dumped "
                      "{} the energy columns; this fix has energy {}: define it with energy {} "
                      "as in the run that wrote the file",
               clock[CLOCK_VALUES], energy_rows ? "with" : "without", energy ? "yes" : "no",
               energy_rows ? "yes" : "no");
  if (comm->me == 0 && rows_every) {
    rows.resize((size_t) clock[CLOCK_VALUES] * row_columns);
    memcpy(rows.data(), buf + sizeof(clock), rows.size() * sizeof(double));
  }
}
