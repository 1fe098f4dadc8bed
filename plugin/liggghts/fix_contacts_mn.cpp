// LIGGGHTS 3.8 fix contacts/mn (fix_contacts_mn.h): `model mn` adds each touching contact of
// each force evaluation to this fix's tallies (granmn::ContactCounter); at the end of the step
// the fix turns them into the per-atom counters, so that a contact counts at every step whose
// force evaluation found it (the run's setup excluded: the tallies are cleared before each
// step's evaluation). With energy yes it adds each contact's energies as booked at the
// evaluation (mn_energy.h) to the atoms' sums, the setup's too (it books no work: its springs'
// energy is the account's start).
#include "fix_contacts_mn.h"

#include <cstring>
#include <mpi.h>
#include <string>

#include "atom.h"
#include "error.h"
#include "fix_property_atom.h"
#include "group.h"
#include "modify.h"
#include "update.h"

#include "mn_output_schema.h"

using namespace LAMMPS_NS;
using namespace FixConst;
// the per-atom columns and the global vector's, the plugin's fix contacts/mn's (its group's
// size aside)
using namespace granmn::output;

FixContactsMN::FixContactsMN(LAMMPS *lmp, int narg, char **arg)
    : Fix(lmp, narg, arg), energy(false), columns(COUNTERS), accumulated(NULL), window(0.0)
{
  if (narg != 3 && !(narg == 5 && strcmp(arg[3], "energy") == 0))
    error->all(FLERR, "Illegal fix contacts/mn command: it takes no arguments but energy yes|no");
  if (narg == 5) {
    if (strcmp(arg[4], "yes") != 0 && strcmp(arg[4], "no") != 0)
      error->all(FLERR, "Illegal fix contacts/mn command: energy needs yes or no");
    energy = strcmp(arg[4], "yes") == 0;
  }
  if (modify->find_fix_style("contacts/mn", 0))
    error->all(FLERR, "Only one fix contacts/mn may be defined");
  books_energy = energy;
  vector_flag = 1;
  size_vector = energy ? VECTOR_SIZE_WITH_ENERGY : VECTOR_SIZE;
  global_freq = 1;
  extvector = 0;
  peratom_flag = 1;
  size_peratom_cols = energy ? COUNTERS + ENERGY_SUMS : COUNTERS;
  if (energy) columns = COLUMNS_WITH_ENERGY;
  peratom_freq = 1;
}

// The per-atom counters, a property/atom that migrates with the atoms. Not in restart files:
// the window's length is not either, and a read restart starts both anew at zero together
// (counters of a window with a length of 0 would be nonsense).
void FixContactsMN::post_create()
{
  const std::string name = std::string("contacts_mn_") + id;
  std::vector<const char *> fixarg = {name.c_str(), group->names[igroup], "property/atom",
                                      name.c_str(), "vector", "no", "no", "no"};
  fixarg.resize(8 + columns, "0.0");
  accumulated = modify->add_fix_property_atom(8 + columns, const_cast<char **>(fixarg.data()),
                                              style);
}

int FixContactsMN::setmask()
{
  return PRE_FORCE | END_OF_STEP;
}

void FixContactsMN::init()
{
  array_atom = accumulated->array_atom;
}

void FixContactsMN::setup_pre_force(int)
{
  clear_tallies();
}

void FixContactsMN::pre_force(int)
{
  clear_tallies();
}

// zeros for this evaluation's contacts, owned and ghost atoms
void FixContactsMN::clear_tallies()
{
  const std::size_t n = atom->nmax;
  for (std::vector<double> *tally : {&particle, &boundary, &begun_particle, &begun_boundary})
    tally->assign(n, 0.0);
  step.particle = particle.data();
  step.boundary = boundary.data();
  step.begun_particle = begun_particle.data();
  step.begun_boundary = begun_boundary.data();
  if (!energy) return;
  energies.assign(n * granmn::STEP_ENERGIES, 0.0);
  energy_step.values = energies.data();
}

// The setup's evaluation: no work booked (no time passed), the springs' energy now.
void FixContactsMN::setup(int)
{
  absorb_energies();
}

// This evaluation's energies into the atoms' sums (newton off, which LIGGGHTS's granular pair
// styles require: a ghost's share is booked by its owner's process, which computes the pair
// too) and their energies as written.
void FixContactsMN::absorb_energies()
{
  if (!energy) return;
  using namespace granmn;
  double **s = accumulated->array_atom;
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double *v = energies.data() + STEP_ENERGIES * i;
    double *a = s[i];
    a[TAKEN_NORMAL] += v[STEP_TAKEN_NORMAL];
    a[TAKEN_TANGENTIAL] += v[STEP_TAKEN_TANGENTIAL];
    a[SLID] += v[STEP_DISSIPATED_SLIDING];
    a[STORED_NORMAL] = v[STEP_STORED_NORMAL];
    a[STORED_TANGENTIAL] = v[STEP_STORED_TANGENTIAL];
    atom_energy_sums(a[TAKEN_NORMAL], a[TAKEN_TANGENTIAL], a[SLID], a[STORED_NORMAL],
                     a[STORED_TANGENTIAL], a + COUNTERS);
  }
}

void FixContactsMN::end_of_step()
{
  const double dt = update->dt;
  double **counters = array_atom = accumulated->array_atom;
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double *c = counters[i];
    c[BEGUN_PARTICLE] += begun_particle[i];
    c[BEGUN_BOUNDARY] += begun_boundary[i];
    if (particle[i] > 0.0) c[TIME_PARTICLE] += dt;
    if (boundary[i] > 0.0) c[TIME_BOUNDARY] += dt;
    if (particle[i] + boundary[i] >= 2.0) c[TIME_MULTIPLE] += dt;
    c[NOW] = particle[i] + boundary[i];
  }
  absorb_energies();
  window += dt;
}

// the sums over the group, the window's length, the group's size; with energy yes the
// energies' sums and the work in flight (none: velocity Verlet's step has applied the first
// half of each force it booked, mn::work_in_flight)
double FixContactsMN::compute_vector(int n)
{
  if (n == WINDOW) return window;
  if (n == GROUP_SIZE) return group->count(igroup);
  if (n == VECTOR_SIZE + ENERGY_SUMS) return 0.0;
  if (n >= VECTOR_SIZE) n = COUNTERS + (n - VECTOR_SIZE);
  double **counters = accumulated->array_atom;
  const int *mask = atom->mask;
  double local = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & groupbit) local += counters[i][n];
  double sum = 0.0;
  MPI_Allreduce(&local, &sum, 1, MPI_DOUBLE, MPI_SUM, world);
  return sum;
}

// fix_modify ID reset: a new window (the per-atom counters and the sums start again at zero)
int FixContactsMN::modify_param(int narg, char **arg)
{
  if (narg >= 1 && strcmp(arg[0], "reset") == 0) {
    reset_window();
    return 1;
  }
  return 0;
}

void FixContactsMN::reset_window()
{
  double **counters = accumulated->array_atom;
  for (int i = 0; i < atom->nlocal; i++)
    for (int c = 0; c < COUNTERS; c++) counters[i][c] = 0.0;
  window = 0.0;
}
