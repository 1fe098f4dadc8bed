/* ----------------------------------------------------------------------
   fix nve/disc/mn (and fix nve/ab2, its Adams-Bashforth 2 without keywords).
   velocity Verlet: v += dt/2 F/m, x += dt v; the force; v += dt/2 F/m (omega_z alike), the
     operations of fix nve/sphere disc, with F = the forces + m g;
   Adams-Bashforth 2: v(t+dt) = v + dt (3/2 a(t) - 1/2 a(t-dt)), x(t+dt) = x + dt/2 (v(t) +
     v(t+dt)), the same for spins (disks, I = m r^2/2); the force at a step sees that step's
     positions and velocities (no half-step velocity).
   Only x, y and omega_z move: nothing in a 2D gran/mn scene acts out of the plane.
------------------------------------------------------------------------- */

#include "fix_nve_disc_mn.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "granmn_compat.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

// fix ID group nve/disc/mn [scheme verlet|ab2] [gravity G X Y] [neigh_check yes|no]
// fix ID group nve/ab2
FixNVEDiscMN::FixNVEDiscMN(LAMMPS *lmp, int narg, char **arg) :
    FixPerAtomState(lmp, narg, arg), integrator(mn::Integrator::VelocityVerlet),
    has_gravity(false), gravity{0.0, 0.0}, dtv(0.0), dtf(0.0), factors_every_step(false),
    factors_lastcall(-1), neigh_check(false), trigger_sq(0.0), held_lastcall(-1)
{
  if (strcmp(style, "nve/ab2") == 0) {
    if (narg != 3) error->all(FLERR, "Illegal fix nve/ab2 command: it takes no arguments");
    integrator = mn::Integrator::AdamsBashforth2;
  }
  for (int iarg = 3; iarg < narg;) {
    if (strcmp(arg[iarg], "scheme") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "Illegal fix {} command: scheme needs verlet or ab2", style);
      if (strcmp(arg[iarg + 1], "verlet") == 0)
        integrator = mn::Integrator::VelocityVerlet;
      else if (strcmp(arg[iarg + 1], "ab2") == 0)
        integrator = mn::Integrator::AdamsBashforth2;
      else
        error->all(FLERR, "Illegal fix {} command: scheme must be verlet or ab2, not {}", style,
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "gravity") == 0) {
      if (iarg + 4 > narg)
        error->all(FLERR, "Illegal fix {} command: gravity needs G X Y (the acceleration and "
                          "its direction in the plane)", style);
      const double magnitude = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      const double x = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      const double y = utils::numeric(FLERR, arg[iarg + 3], false, lmp);
      // as fix gravity's vector style makes its acceleration, to the bit
      const double length = sqrt(x * x + y * y);
      if (length == 0.0)
        error->all(FLERR, "Illegal fix {} command: gravity direction 0 0 has no length", style);
      gravity[0] = magnitude * (x / length);
      gravity[1] = magnitude * (y / length);
      has_gravity = true;
      iarg += 4;
    } else if (strcmp(arg[iarg], "neigh_check") == 0) {
      if (iarg + 2 > narg ||
          (strcmp(arg[iarg + 1], "yes") != 0 && strcmp(arg[iarg + 1], "no") != 0))
        error->all(FLERR, "Illegal fix {} command: neigh_check needs yes or no", style);
      neigh_check = strcmp(arg[iarg + 1], "yes") == 0;
      iarg += 2;
    } else {
      error->all(FLERR, "Illegal fix {} command: unknown keyword {}", style, arg[iarg]);
    }
  }
  if (domain->dimension != 2)
    error->all(FLERR, "Fix {} integrates disks: it requires dimension 2", style);
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "Fix {} requires atom attributes radius, rmass, omega, torque "
                      "(atom_style sphere)", style);
  time_integrate = 1;
  if (neigh_check) {
    force_reneighbor = 1;
    next_reneighbor = -1;
  }
  if (integrator == mn::Integrator::AdamsBashforth2) register_state(NSTATE);
}

int FixNVEDiscMN::setmask()
{
  return integrator == mn::Integrator::VelocityVerlet ? INITIAL_INTEGRATE | FINAL_INTEGRATE
                                                      : INITIAL_INTEGRATE;
}

void FixNVEDiscMN::init()
{
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "Fix {} does not support run_style respa", style);
  // a point particle has no moment of inertia: its spin would be torque/0
  bigint points = 0;
  for (int i = 0; i < atom->nlocal; i++)
    if ((atom->mask[i] & groupbit) && atom->radius[i] == 0.0) points++;
  bigint points_all = 0;
  MPI_Allreduce(&points, &points_all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (points_all)
    error->all(FLERR, "Fix {} integrates disks: {} atoms of its group have diameter 0 "
                      "(point particles)", style, points_all);
  check_other_fixes();
  if (neigh_check) {
    // its test sees only the atoms it moves, in a box that keeps its size
    for (Fix *fix : granmn::all_fixes(modify))
      if (fix != this && fix->time_integrate)
        error->all(FLERR, "Fix {} ({}) with neigh_check yes tests only the atoms it moves, and "
                          "fix {} ({}) moves atoms too; use neigh_check no (LAMMPS's own test)",
                   id, style, fix->id, fix->style);
    // (a shrink-wrapped box changes only at builds, where LAMMPS's test does not look)
    for (Fix *fix : granmn::all_fixes(modify))
      if (fix->box_change)
        error->all(FLERR, "Fix {} ({}) with neigh_check yes needs a box that no fix changes "
                          "during a run, and fix {} ({}) does; use neigh_check no (LAMMPS's own "
                          "test)", id, style, fix->id, fix->style);
    trigger_sq = 0.25 * neighbor->skin * neighbor->skin;
  }
  factors_every_step = !granmn::fixes_by_style(modify, "^adapt").empty();
  dtv = update->dt;
  dtf = 0.5 * update->dt * force->ftm2v;
}

// One integrator per atom, and gravity once: either would be a silently wrong trajectory.
void FixNVEDiscMN::check_other_fixes()
{
  for (Fix *fix : granmn::all_fixes(modify)) {
    const bool integrates = fix->time_integrate;
    const bool pulls = has_gravity && utils::strmatch(fix->style, "^gravity");
    if (fix == this || !(integrates || pulls)) continue;
    bigint shared = 0;
    for (int i = 0; i < atom->nlocal; i++)
      if ((atom->mask[i] & groupbit) && (atom->mask[i] & fix->groupbit)) shared++;
    bigint shared_all = 0;
    MPI_Allreduce(&shared, &shared_all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
    if (!shared_all) continue;
    if (integrates)
      error->all(FLERR, "Fix {} ({}): fix {} ({}) integrates {} atoms of its group too; an "
                        "atom takes one integrator", id, style, fix->id, fix->style, shared_all);
    error->all(FLERR, "Fix {} ({}) applies gravity, and fix {} (gravity) pulls {} atoms of its "
                      "group too: gravity would act twice; drop one of them",
               id, style, fix->id, shared_all);
  }
}

void FixNVEDiscMN::setup(int)
{
  compute_factors();
  if (neigh_check) hold_positions();
}

// The positions at the last build, as LAMMPS holds them (x is unchanged from the build to
// this fix's next pass).
void FixNVEDiscMN::hold_positions()
{
  double **x = atom->x;
  const int nlocal = atom->nlocal;
  held.resize(2 * nlocal);
  for (int i = 0; i < nlocal; i++) {
    held[2 * i] = x[i][0];
    held[2 * i + 1] = x[i][1];
  }
  held_lastcall = neighbor->lastcall;
}

void FixNVEDiscMN::reset_dt()
{
  dtv = update->dt;
  dtf = 0.5 * update->dt * force->ftm2v;
  compute_factors();
}

// LAMMPS re-sorts and exchanges atoms only when it builds the neighbour list.
void FixNVEDiscMN::compute_factors()
{
  const int nlocal = atom->nlocal;
  const double *rmass = atom->rmass;
  const double *radius = atom->radius;
  factors.resize(nlocal);
  const bool verlet = integrator == mn::Integrator::VelocityVerlet;
  const double scale = verlet ? dtf : force->ftm2v;
  // fix nve/sphere disc's operations: (dtf / inertia) / (r^2 m), inertia = 1/2
  const double scale_rotation = scale / 0.5;
  for (int i = 0; i < nlocal; i++) {
    const double m = rmass[i], r = radius[i];
    factors[i] = {scale / m, scale_rotation / (r * r * m), m * gravity[0], m * gravity[1]};
  }
  factors_lastcall = neighbor->lastcall;
}

// Velocity Verlet's half step of one disk's velocity and spin. The new values are computed
// into locals first: v, f and omega could alias for the compiler, which would store and reload.
static inline void half_kick(const FixNVEDiscMN::Factors &c, const double *f,
                             const double *torque, double *v, double *omega)
{
  const double vx = v[0] + c.per_mass * (f[0] + c.weight_x);
  const double vy = v[1] + c.per_mass * (f[1] + c.weight_y);
  const double wz = omega[2] + c.per_inertia * torque[2];
  v[0] = vx;
  v[1] = vy;
  omega[2] = wz;
}

// The factors follow the atoms: recomputed after a neighbour-list build (atoms re-sorted or
// exchanged) or at every step under a fix adapt.
void FixNVEDiscMN::refresh_factors()
{
  if (factors_every_step || neighbor->lastcall != factors_lastcall) compute_factors();
  if (neigh_check && neighbor->lastcall != held_lastcall) hold_positions();
}

// neigh_check: LAMMPS's own test (Neighbor::check_distance, the same operations: z does not
// move), so that the lists are built at the same steps.
void FixNVEDiscMN::request_build(bool moved)
{
  int flag = moved ? 1 : 0;
  if (comm->nprocs > 1) {
    int flag_all = 0;
    MPI_Allreduce(&flag, &flag_all, 1, MPI_INT, MPI_MAX, world);
    flag = flag_all;
  }
  if (flag) next_reneighbor = update->ntimestep;
}

void FixNVEDiscMN::initial_integrate(int)
{
  refresh_factors();
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  double **omega = atom->omega;
  double **torque = atom->torque;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const Factors *c = factors.data();

  const bool check = neigh_check;
  const double *hold = held.data();
  const double trigger = trigger_sq;
  bool moved = false;

  if (integrator == mn::Integrator::VelocityVerlet) {
    for (int i = 0; i < nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      half_kick(c[i], f[i], torque[i], v[i], omega[i]);
      x[i][0] += dtv * v[i][0];
      x[i][1] += dtv * v[i][1];
      if (check) {
        const double dx = x[i][0] - hold[2 * i], dy = x[i][1] - hold[2 * i + 1];
        if (dx * dx + dy * dy > trigger) moved = true;
      }
    }
    if (check) request_build(moved);
    return;
  }
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double *previous = state[i];
    const double a[3] = {(f[i][0] + c[i].weight_x) * c[i].per_mass,
                         (f[i][1] + c[i].weight_y) * c[i].per_mass,
                         torque[i][2] * c[i].per_inertia};
    // The first step has no previous acceleration: it takes a(t - dt) = a(t), an Euler step.
    if (previous[HAS_PREVIOUS] == 0.0) {
      for (int k = 0; k < 3; k++) previous[k] = a[k];
      previous[HAS_PREVIOUS] = 1.0;
    }
    for (int k = 0; k < 2; k++) {
      const double v_new = mn::ab2_velocity(v[i][k], a[k], previous[k], dtv);
      x[i][k] = mn::trapezoidal_position(x[i][k], v[i][k], v_new, dtv);
      v[i][k] = v_new;
    }
    omega[i][2] = mn::ab2_velocity(omega[i][2], a[2], previous[ALPHA], dtv);
    for (int k = 0; k < 3; k++) previous[k] = a[k];
    if (check) {
      const double dx = x[i][0] - hold[2 * i], dy = x[i][1] - hold[2 * i + 1];
      if (dx * dx + dy * dy > trigger) moved = true;
    }
  }
  if (check) request_build(moved);
}

// velocity Verlet's second half (the atoms may have been re-sorted since the first)
void FixNVEDiscMN::final_integrate()
{
  refresh_factors();
  double **v = atom->v;
  double **f = atom->f;
  double **omega = atom->omega;
  double **torque = atom->torque;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const Factors *c = factors.data();
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit) half_kick(c[i], f[i], torque[i], v[i], omega[i]);
}

double FixNVEDiscMN::memory_usage()
{
  return FixPerAtomState::memory_usage() + (double) factors.capacity() * sizeof(Factors) +
      (double) held.capacity() * sizeof(double);
}
