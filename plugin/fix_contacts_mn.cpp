/* ----------------------------------------------------------------------
   fix contacts/mn: contact counts and times per atom, per-contact rows.
------------------------------------------------------------------------- */

#include "fix_contacts_mn.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "granmn_compat.h"
#include "granmn_glue.h"
#include "group.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

static constexpr int ROW_COLS = 8;          // tag_i tag_j kind start duration vn_start vn_end peak

// fix ID group contacts/mn [local N]
FixContactsMN::FixContactsMN(LAMMPS *lmp, int narg, char **arg) :
    FixPerAtomState(lmp, narg, arg), step_particle(nullptr),
    step_boundary(nullptr), begun_particle(nullptr), begun_boundary(nullptr), nmax_step(0),
    fold_ghosts(false),
    now(0.0), clock_step(0), window_start(0.0), rows_every(0), row_array(nullptr), nmax_rows(0),
    rows_handed(0), handed_step(-1), vector_step(-1)
{
  int iarg = 3;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "local") == 0) {
      if (iarg + 2 > narg) error->all(FLERR, "Illegal fix contacts/mn command: local needs N");
      rows_every = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (rows_every <= 0)
        error->all(FLERR, "Illegal fix contacts/mn command: local N needs N > 0 steps");
      iarg += 2;
    } else {
      error->all(FLERR, "Illegal fix contacts/mn command: unknown keyword {}", arg[iarg]);
    }
  }
  nevery = 1;
  peratom_flag = 1;
  size_peratom_cols = NCOLS;
  peratom_freq = 1;
  vector_flag = 1;
  size_vector = 8;
  global_freq = 1;
  extvector = -1;
  extlist = new int[size_vector]{1, 1, 1, 1, 1, 1, 0, 1};
  if (rows_every) {
    local_flag = 1;
    size_local_cols = ROW_COLS;
    size_local_rows = 0;
    local_freq = rows_every;
  }
  restart_global = 1;
  comm_reverse = 4;
  allocate_state(NCOLS);
  clock_step = update->ntimestep;
  now = update->ntimestep * update->dt;
  window_start = now;
}

FixContactsMN::~FixContactsMN()
{
  memory->destroy(step_particle);
  memory->destroy(step_boundary);
  memory->destroy(begun_particle);
  memory->destroy(begun_boundary);
  memory->destroy(row_array);
  delete[] extlist;
}

int FixContactsMN::setmask()
{
  return PRE_FORCE | END_OF_STEP;
}

void FixContactsMN::init()
{
  if (granmn::fixes_by_style(modify, "^contacts/mn").size() > 1)
    error->all(FLERR, "Only one fix contacts/mn may be defined");
  if (!force->pair_match("gran/mn", 1) && !granmn::first_fix(modify, "^wall/gran/mn"))
    error->all(FLERR, "Fix contacts/mn counts the contacts of pair_style gran/mn and fix "
                      "wall/gran/mn; neither is defined");
  fold_ghosts = comm->nprocs == 1 && atom->map_style != Atom::MAP_NONE;
}

// Called once per step before any contact is reported: the clock moves on by the step just
// taken, with the time step it was taken with.
void FixContactsMN::advance_clock()
{
  if (update->ntimestep > clock_step) now += (update->ntimestep - clock_step) * update->dt;
  clock_step = update->ntimestep;
}

// Rows handed to dump local at an earlier step (or before a reset_timestep) have been written.
void FixContactsMN::drop_handed_rows()
{
  if (rows_handed && update->ntimestep != handed_step) {
    rows.erase(rows.begin(), rows.begin() + (size_t) rows_handed * ROW_COLS);
    rows_handed = 0;
  }
}

/* ---------------------------------------------------------------------- */

void FixContactsMN::grow_step_arrays()
{
  if (atom->nmax <= nmax_step) return;
  nmax_step = atom->nmax;
  memory->destroy(step_particle);
  memory->destroy(step_boundary);
  memory->destroy(begun_particle);
  memory->destroy(begun_boundary);
  memory->create(step_particle, nmax_step, "contacts/mn:step_particle");
  memory->create(step_boundary, nmax_step, "contacts/mn:step_boundary");
  memory->create(begun_particle, nmax_step, "contacts/mn:begun_particle");
  memory->create(begun_boundary, nmax_step, "contacts/mn:begun_boundary");
  // zero once: collect zeroes what the tallies wrote (one process), or pre_force all of it
  for (int i = 0; i < nmax_step; i++)
    step_particle[i] = step_boundary[i] = begun_particle[i] = begun_boundary[i] = 0.0;
  touched.clear();
}

// No time passes between runs: the step a run starts at is the clock's, also after
// reset_timestep moved it (either way).
void FixContactsMN::setup_pre_force(int vflag)
{
  clock_step = update->ntimestep;
  pre_force(vflag);
}

// This step's tallies are zero before the pair style and the wall fix fill them: on one
// process collect zeroed the entries it visited; else zero them all here.
void FixContactsMN::pre_force(int)
{
  advance_clock();
  grow_step_arrays();
  if (!fold_ghosts) {
    const int n = atom->nlocal + atom->nghost;
    for (int i = 0; i < n; i++)
      step_particle[i] = step_boundary[i] = begun_particle[i] = begun_boundary[i] = 0.0;
    touched.clear();
  }
  drop_handed_rows();
}

void FixContactsMN::pair_ended(int i, int j, bool boundary, const double *record, double vn,
                               bool write_row)
{
  const int *mask = atom->mask;
  if (!write_row || !((mask[i] | mask[j]) & groupbit)) return;
  // the mobile atom first against a bump, else the smaller ID first (v_n is the same either way)
  const tagint *tag = atom->tag;
  const bool swap = !boundary && tag[j] < tag[i];
  ended(record, tag[swap ? j : i], tag[swap ? i : j], boundary ? 2 : 1, vn);
}

// A completed contact's row: IDs, kind, start, duration, v_n in and out, peak overlap.
void FixContactsMN::ended(const double *record, double tag_i, double tag_j, double kind,
                          double vn_end)
{
  if (!rows_every) return;
  const double row[ROW_COLS] = {tag_i, tag_j, kind, record[RECORD_START],
                                now - record[RECORD_START], record[RECORD_VN_START], vn_end,
                                record[RECORD_PEAK]};
  rows.insert(rows.end(), row, row + ROW_COLS);
}

/* ---------------------------------------------------------------------- */

// Add this step to atom i's counts and times.
static inline void add_step(double *p, double begun_particle, double begun_boundary,
                            double step_particle, double step_boundary, bool accumulate_time,
                            double dt)
{
  p[FixContactsMN::BEGUN_PARTICLE] += begun_particle;
  p[FixContactsMN::BEGUN_BOUNDARY] += begun_boundary;
  p[FixContactsMN::NOW] = step_particle + step_boundary;
  if (accumulate_time) {
    if (step_particle > 0.0) p[FixContactsMN::TIME_PARTICLE] += dt;
    if (step_boundary > 0.0) p[FixContactsMN::TIME_BOUNDARY] += dt;
    if (p[FixContactsMN::NOW] >= 2.0) p[FixContactsMN::TIME_MULTIPLE] += dt;
  }
}

// Bring ghost tallies home, then add this step to each atom's counts and times. An atom with
// no contact at this step gains nothing but NOW = 0.
void FixContactsMN::collect(bool accumulate_time)
{
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const double dt = update->dt;
  if (!fold_ghosts) {
    if (force->newton_pair) granmn::reverse_comm(comm, this);
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit)
        add_step(state[i], begun_particle[i], begun_boundary[i], step_particle[i],
                 step_boundary[i], accumulate_time, dt);
    return;
  }
  // the atoms of the last step's list keep their indices unless LAMMPS re-sorted or exchanged
  // them at this step (a neighbour-list build, or a run's setup)
  if (update->setupflag || neighbor->lastcall == update->ntimestep) {
    for (int i = 0; i < nlocal; i++) state[i][NOW] = 0.0;
  } else {
    for (int i : touched_before) state[i][NOW] = 0.0;
  }
  for (int i : touched) {
    if (mask[i] & groupbit)
      add_step(state[i], begun_particle[i], begun_boundary[i], step_particle[i],
               step_boundary[i], accumulate_time, dt);
    step_particle[i] = step_boundary[i] = begun_particle[i] = begun_boundary[i] = 0.0;
  }
  touched.swap(touched_before);
  touched.clear();
}

// Contacts that exist when a run starts are counted once, at its setup.
void FixContactsMN::setup(int)
{
  collect(false);
  publish_rows();
}

void FixContactsMN::end_of_step()
{
  collect(true);
  if (rows_every && update->ntimestep % rows_every == 0) publish_rows();
}

void FixContactsMN::publish_rows()
{
  if (!rows_every) return;
  const int n = rows.size() / ROW_COLS;
  if (n > nmax_rows) {
    nmax_rows = n;
    memory->destroy(row_array);
    memory->create(row_array, nmax_rows, ROW_COLS, "contacts/mn:rows");
  }
  for (int r = 0; r < n; r++)
    for (int c = 0; c < ROW_COLS; c++) row_array[r][c] = rows[ROW_COLS * r + c];
  array_local = row_array;
  size_local_rows = n;
  // dump local N writes them at this step
  if (update->ntimestep % rows_every == 0) {
    rows_handed = n;
    handed_step = update->ntimestep;
  }
}

int FixContactsMN::pack_reverse_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++) {
    buf[m++] = step_particle[i];
    buf[m++] = step_boundary[i];
    buf[m++] = begun_particle[i];
    buf[m++] = begun_boundary[i];
  }
  return m;
}

void FixContactsMN::unpack_reverse_comm(int n, int *list, double *buf)
{
  int m = 0;
  for (int k = 0; k < n; k++) {
    const int j = list[k];
    step_particle[j] += buf[m++];
    step_boundary[j] += buf[m++];
    begun_particle[j] += buf[m++];
    begun_boundary[j] += buf[m++];
  }
}

// fix_modify ID reset: a fresh accumulation window from now on.
int FixContactsMN::modify_param(int narg, char **arg)
{
  if (strcmp(arg[0], "reset") != 0) return 0;
  if (narg > 1)
    error->all(FLERR, "Illegal fix_modify command: fix contacts/mn reset takes no arguments");
  for (int i = 0; i < atom->nlocal; i++)
    for (int c = BEGUN_PARTICLE; c <= TIME_MULTIPLE; c++) state[i][c] = 0.0;
  window_start = now;
  vector_step = -1;
  return 1;
}

// Sums over the group of the per-atom columns, the window's length, the group's size.
double FixContactsMN::compute_vector(int n)
{
  if (vector_step != update->ntimestep) {
    double local[NCOLS] = {0.0};
    const int *mask = atom->mask;
    for (int i = 0; i < atom->nlocal; i++)
      if (mask[i] & groupbit)
        for (int c = 0; c < NCOLS; c++) local[c] += state[i][c];
    MPI_Allreduce(local, vector_sums, NCOLS, MPI_DOUBLE, MPI_SUM, world);
    vector_sums[6] = now - window_start;
    vector_sums[7] = group->count(igroup);
    vector_step = update->ntimestep;
  }
  return vector_sums[n];
}

/* ---------------------------------------------------------------------- */

double FixContactsMN::memory_usage()
{
  return FixPerAtomState::memory_usage() + 4.0 * nmax_step * sizeof(double) +
      (double) rows.capacity() * sizeof(double);
}

// The per-atom output is the first NCOLS columns of the state.
void FixContactsMN::grow_arrays(int nmax)
{
  FixPerAtomState::grow_arrays(nmax);
  array_atom = state;
}

// The first value marks the layout: earlier versions wrote one value, a step (>= 0), and kept
// contact start steps rather than times in the pair history; then the clock alone (-2). Now
// (-3) the rows not yet dumped follow the clock, gathered from all processes: a run continued
// from the file dumps them at its next multiple of N.
static constexpr double CLOCK_LAYOUT = -2.0, CLOCK_AND_ROWS_LAYOUT = -3.0;
static constexpr int CLOCK_VALUES = 4;

void FixContactsMN::write_restart(FILE *fp)
{
  // rows handed to a dump are in its file already
  const int skip = rows_handed * ROW_COLS;
  const int mine = (int) rows.size() - skip;
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
    values[0] = CLOCK_AND_ROWS_LAYOUT;
    values[1] = now;
    values[2] = (double) clock_step;
    values[3] = window_start;
    values[4] = total / ROW_COLS;
    const int size = values.size() * sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(values.data(), sizeof(double), values.size(), fp);
  }
}

void FixContactsMN::restart(char *buf)
{
  double layout;
  memcpy(&layout, buf, sizeof(double));
  if (layout != CLOCK_LAYOUT && layout != CLOCK_AND_ROWS_LAYOUT)
    error->all(FLERR, "Fix contacts/mn: the restart file was written by an earlier version that "
                      "kept steps, not times; write a new one");
  double clock[CLOCK_VALUES + 1];
  memcpy(clock, buf, sizeof(double) * (layout == CLOCK_LAYOUT ? CLOCK_VALUES : CLOCK_VALUES + 1));
  now = clock[1];
  clock_step = (bigint) clock[2];
  window_start = clock[3];
  // the pending rows go to the first process (dump local gathers them all); kept only if
  // this run asks for rows
  rows.clear();
  rows_handed = 0;
  if (layout == CLOCK_AND_ROWS_LAYOUT && comm->me == 0 && rows_every) {
    rows.resize((size_t) clock[CLOCK_VALUES] * ROW_COLS);
    memcpy(rows.data(), buf + sizeof(clock), rows.size() * sizeof(double));
  }
}
