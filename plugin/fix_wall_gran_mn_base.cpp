/* ----------------------------------------------------------------------
   What the gran/mn wall fixes share (fix_wall_gran_mn_base.h).
------------------------------------------------------------------------- */

#include "fix_wall_gran_mn_base.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "granmn_compat.h"
#include "granmn_run_checks.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

using namespace LAMMPS_NS;
using namespace FixConst;

FixWallGranMNBase::FixWallGranMNBase(LAMMPS *lmp, int narg, char **arg) :
    FixPerAtomState(lmp, narg, arg), own_law(false), use_history(false),
    integrator(mn::Integrator::VelocityVerlet), force_per_mass_acceleration(1.0),
    observer(nullptr), ut_block(-1), record_block(-1), vt_block(-1), energy_block(-1),
    energy_size(0), keyed(false),
    radii_change(false), force_reduced(false)
{
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "Fix {} requires atom attributes radius, rmass, omega, torque "
                      "(atom_style sphere)", style);
  vector_flag = 1;
  size_vector = domain->dimension == 3 ? 3 : 2;    // force exerted by the atoms on the wall
  global_freq = 1;
  extvector = 1;
  wall_force[0] = wall_force[1] = wall_force[2] = 0.0;
}

void FixWallGranMNBase::define_law_and_slots(int narg, char **arg, int iarg, int nslots,
                                             bool keyed_slots)
{
  const std::string command = std::string("fix ") + style;
  while (iarg < narg) {
    const int used = granmn::parse_law_keyword(lmp, command.c_str(), narg, arg, iarg, parsed);
    if (!used) error->all(FLERR, "Illegal {} command: unknown keyword {}", command, arg[iarg]);
    iarg += used;
  }
  resolve_law();
  use_history = law.material.mu > 0.0;
  slots.count = nslots;
  slots.ut_width = granmn::ut_width(lmp);
  keyed = keyed_slots;
  // the count, the keys and u_t where kept from the start; the observer's records and the
  // previous v_t come at init
  register_state(use_history ? slots.record_block() : keyed ? slots.ut_block() : 0);
  if (use_history) ut_block = slots.ut_block();
}

int FixWallGranMNBase::setmask()
{
  return POST_FORCE | PRE_NEIGHBOR;
}

// Material from the fix line where given, else from pair_style gran/mn.
void FixWallGranMNBase::resolve_law()
{
  const granmn::WallLaw wall = granmn::wall_law(lmp, style, parsed);
  law = wall.law;
  own_law = wall.own;
}

void FixWallGranMNBase::init()
{
  init_geometry();
  const std::string command = std::string("fix ") + style;
  resolve_law();
  if (law.material.mu > 0.0 && !use_history)
    error->all(FLERR, "Fix {} was defined with mu = 0 and keeps no tangential history; define "
                      "it again after giving mu > 0", style);
  granmn::check_disc_integration(lmp, command.c_str());
  // the law gives mass x acceleration; LAMMPS turns force back into acceleration with ftm2v
  force_per_mass_acceleration = 1.0 / force->ftm2v;
  integrator = granmn::integrator_in_use(modify);
  radii_change = !granmn::fixes_by_style(modify, "^adapt").empty();
  observer = granmn::find_observer(granmn::all_fixes(modify));
  keep_slots();
  // The pair style already checked the time step against the same law.
  if (own_law) granmn::check_timestep(lmp, command.c_str(), update->dt, law, integrator);
}

// The observer's record of each slot (with fix contacts/mn), and Adams-Bashforth 2's previous
// v_t of each slot: kept from then on (current under either integrator), also when a restart
// file brings them.
void FixWallGranMNBase::keep_slots()
{
  if (observer) widen_state(slots.vt_block());
  if (use_history && integrator == mn::Integrator::AdamsBashforth2) widen_state(slots.end());
  record_block = observer ? slots.record_block() : -1;
  vt_block = use_history && ncols >= slots.end() ? slots.vt_block() : -1;
  // the energy histories after the other blocks, only when booked: a run without them keeps
  // the rows as they were
  const bool energies = observer && observer->energy_tallies();
  energy_size = can_move() ? mn::moving_wall_energy_history_size(integrator, domain->dimension)
                           : mn::energy_history_size(integrator, domain->dimension);
  energy_block = energies ? slots.end() : -1;
  if (energies) widen_state(slots.end() + slots.count * energy_size);
}

static inline double ut_squared(int dimension, const double *ut)
{
  if (!ut) return 0.0;
  return dimension == 3 ? ut[0] * ut[0] + ut[1] * ut[1] + ut[2] * ut[2] : ut[0] * ut[0];
}

template <int DIM, class K>
void FixWallGranMNBase::add_wall_contact_with_energy(int i, double scale, const K &kin,
                                                     double *ut, double dt_history,
                                                     double *vt_previous, double *energy,
                                                     double *on_walls, bool began,
                                                     const double *v_wall)
{
  const double radius = atom->radius[i];
  const double *omega = atom->omega[i];
  const double lever[3] = {radius * omega[0], radius * omega[1], radius * omega[2]};
  const double tail = v_wall ? mn::previous_wall_power(integrator, DIM, energy, v_wall) : 0.0;
  double f[3];
  const mn::EnergyStep booked =
      mn::force_and_torques_with_energy(law, scale, kin, lever, ut, dt_history, integrator,
                                        vt_previous, energy, f, radius, atom->torque[i], 0.0,
                                        nullptr);
  for (int c = 0; c < DIM; c++) {
    atom->f[i][c] += f[c];
    on_walls[c] -= f[c];
  }
  // the wall takes no energy: the contact's energies are all the atom's
  const granmn::EnergyTallies *tallies = observer->energy_tallies();
  tallies->add(i, 1.0, booked, mn::stored_energy(law, scale, kin.delta, ut_squared(DIM, ut)));
  if (began && dt_history == 0.0)
    tallies->add(i, 1.0,
                 mn::open_energy_account(law, scale, kin.delta, ut_squared(DIM, ut), energy),
                 {0.0, 0.0});
  if (v_wall)
    tallies->add_wall_work(
        i, mn::book_wall_work(integrator, DIM, dt_history, tail, f, v_wall, energy));
}

// mn::book_ended_contact_energy in the dimension of the kinematics (3D: velocity Verlet).
static inline mn::EnergyStep book_ended_energy(const mn::Law &law, double scale,
                                               const mn::Kinematics &k, const double lever[3],
                                               double ut2, double dt, mn::Integrator integrator,
                                               double *energy)
{
  return mn::book_ended_contact_energy(law, scale, k, lever[2], ut2, dt, integrator, energy);
}

static inline mn::EnergyStep book_ended_energy(const mn::Law &law, double scale,
                                               const mn::Kinematics3 &k, const double lever[3],
                                               double ut2, double dt, mn::Integrator,
                                               double *energy)
{
  return mn::book_ended_contact_energy(law, scale, k, lever, ut2, dt, energy);
}

template <int DIM>
mn::ContactEnergy FixWallGranMNBase::book_ended_wall_energy(int i, const double n[3],
                                                            double dist, double dt_history,
                                                            const double *ut, double *energy,
                                                            const double *v_wall)
{
  const double radius = atom->radius[i];
  const double *omega = atom->omega[i];
  const double *v = atom->v[i];
  const double d[3] = {n[0] * dist, n[1] * dist, n[2] * dist};
  const double dv[3] = {v[0] - (v_wall ? v_wall[0] : 0.0), v[1] - (v_wall ? v_wall[1] : 0.0),
                        v[2] - (v_wall ? v_wall[2] : 0.0)};
  const auto kin = mn::wall_kinematics<DIM>(d, dist, radius, dv, omega);
  const double lever[3] = {radius * omega[0], radius * omega[1], radius * omega[2]};
  const double scale = mn::boundary_mass_scale(atom->rmass[i]) * force_per_mass_acceleration;
  const double tail = v_wall ? mn::previous_wall_power(integrator, DIM, energy, v_wall) : 0.0;
  const mn::EnergyStep booked = book_ended_energy(law, scale, kin, lever, ut_squared(DIM, ut),
                                                  dt_history, integrator, energy);
  const granmn::EnergyTallies *tallies = observer->energy_tallies();
  tallies->add(i, 1.0, booked, {0.0, 0.0});
  if (v_wall) {
    const double no_force[3] = {0.0, 0.0, 0.0};
    tallies->add_wall_work(
        i, mn::book_wall_work(integrator, DIM, dt_history, tail, no_force, v_wall, energy));
  }
  const mn::ContactEnergy total = mn::contact_energy(law, scale, 0.0, 0.0, energy);
  // the slot's next contact starts its account afresh
  for (int s = 0; s < energy_size; s++) energy[s] = 0.0;
  return total;
}

template void FixWallGranMNBase::add_wall_contact_with_energy<2, mn::Kinematics>(
    int, double, const mn::Kinematics &, double *, double, double *, double *, double *, bool,
    const double *);
template void FixWallGranMNBase::add_wall_contact_with_energy<3, mn::Kinematics3>(
    int, double, const mn::Kinematics3 &, double *, double, double *, double *, double *, bool,
    const double *);
template mn::ContactEnergy FixWallGranMNBase::book_ended_wall_energy<2>(
    int, const double *, double, double, const double *, double *, const double *);
template mn::ContactEnergy FixWallGranMNBase::book_ended_wall_energy<3>(
    int, const double *, double, double, const double *, double *, const double *);

int FixWallGranMNBase::contacts_held(int i) const
{
  if (!observer || !(atom->mask[i] & groupbit)) return 0;
  return static_cast<int>(state[i][granmn::WallSlots::HELD]);
}

// Listed here as well as at each build: a run with `pre no` has no build before its first step.
void FixWallGranMNBase::setup(int vflag)
{
  list_near_wall();
  post_force(vflag);
}

void FixWallGranMNBase::pre_neighbor()
{
  list_near_wall();
}

// whether atom i's row holds a contact, u_t or a previous v_t
bool FixWallGranMNBase::holds_state(int i) const
{
  const double *row = state[i];
  if ((keyed || observer) && row[granmn::WallSlots::HELD] != 0.0) return true;
  for (int k = 0; k < slots.count * slots.ut_width; k++)
    if ((ut_block >= 0 && row[ut_block + k] != 0.0) ||
        (vt_block >= 0 && row[vt_block + k] != 0.0))
      return true;
  return false;
}

void FixWallGranMNBase::list_near_wall()
{
  const double *radius = atom->radius;
  const double skin = neighbor->skin;
  const bool every = radii_change || surface_moves();
  near_wall.clear();
  // every atom, in the group or not: a dynamic group can change between builds. An atom
  // beyond the skin that still holds a contact's state (it moved that far in one step, or came
  // so from another processor) stays listed until the contact has ended.
  for (int i = 0; i < atom->nlocal; i++)
    if (every || holds_state(i) || within_reach(i, radius[i] + skin)) near_wall.push_back(i);
}

double FixWallGranMNBase::compute_vector(int n)
{
  if (!force_reduced) {
    MPI_Allreduce(wall_force, wall_force_all, size_vector, MPI_DOUBLE, MPI_SUM, world);
    force_reduced = true;
  }
  return wall_force_all[n];
}
