/* ----------------------------------------------------------------------
   fix nve/disc/mn (and fix nve/ab2, its Adams-Bashforth 2 without keywords).
   velocity Verlet: v += dt/2 F/m, x += dt v; the force; v += dt/2 F/m (omega_z alike), the
     operations of fix nve/sphere disc, with F = the forces + m g, which goes into f (as fix
     gravity puts it there);
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
#include "granmn_flat_arrays.h"
#include "granmn_run_checks.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

// fix ID group nve/disc/mn [scheme verlet|ab2] [gravity G X Y] [neigh_check yes|no]
// fix ID group nve/ab2
FixNVEDiscMN::FixNVEDiscMN(LAMMPS *lmp, int narg, char **arg) :
    FixPerAtomState(lmp, narg, arg), integrator(mn::Integrator::VelocityVerlet),
    has_gravity(false), gravity{0.0, 0.0}, dtv(0.0), dtf(0.0), factors_every_step(false),
    factors_stale(false), factors_lastcall(-1), gravity_at_setup(true), gravity_pending(false),
    neigh_check(false), trigger_sq(0.0), held_lastcall(-1)
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

void *FixNVEDiscMN::extract(const char *name, int &dim)
{
  dim = 0;
  if (strcmp(name, granmn::INTEGRATOR_EXTRACT_NAME) == 0) return &integrator;
  // neigh_check yes: this fix decides when the neighbour lists are built
  if (strcmp(name, granmn::NEIGH_CHECK_EXTRACT_NAME) == 0) return &neigh_check;
  return nullptr;
}

// Adams-Bashforth 2 moves the disks in one pass at the start of a step; with gravity a second
// pass at its end puts m g into the step's forces. POST_RUN: the factors may be stale after it.
int FixNVEDiscMN::setmask()
{
  int mask = INITIAL_INTEGRATE | POST_RUN;
  if (integrator == mn::Integrator::VelocityVerlet || has_gravity) mask |= FINAL_INTEGRATE;
  return mask;
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
    // A box that changes between builds moves LAMMPS's trigger distance (its test adds the
    // box's corners' motion since the last build), which this test does not follow. A
    // shrink-wrapped box changes only at builds, and fix balance (BOX_CHANGE_DOMAIN) moves
    // only the sub-domains, at builds it forces itself (LAMMPS's decision, through its
    // next_reneighbor): between builds the box and the trigger stay.
    for (Fix *fix : granmn::all_fixes(modify))
      if (fix->box_change & ~Fix::BOX_CHANGE_DOMAIN)
        error->all(FLERR, "Fix {} ({}) with neigh_check yes needs a box that no fix changes "
                          "during a run, and fix {} ({}) does; use neigh_check no (LAMMPS's own "
                          "test)", id, style, fix->id, fix->style);
    trigger_sq = 0.25 * neighbor->skin * neighbor->skin;
  }
  // At a run's setup each fix adds its forces in its own setup, in the order of definition:
  // m g goes last there only if no fix after this one adds any (a post-force fix).
  gravity_at_setup = true;
  bool after_this = false;
  for (Fix *fix : granmn::all_fixes(modify)) {
    if (after_this && (fix->setmask() & POST_FORCE)) gravity_at_setup = false;
    if (fix == this) after_this = true;
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
  gravity_pending = has_gravity && !gravity_at_setup;
  if (has_gravity && gravity_at_setup) add_gravity();
}

// A command between runs may change masses or radii (set), and run ... pre no skips the setup.
void FixNVEDiscMN::post_run()
{
  factors_stale = true;
}

// m g into the forces of the group's atoms, as fix gravity adds it.
void FixNVEDiscMN::add_gravity()
{
  double **f = atom->f;
  for (const Member &m : members) {
    f[m.atom][0] += m.weight_x;
    f[m.atom][1] += m.weight_y;
  }
}

// The positions at the last build, as LAMMPS holds them (x is unchanged from the build to
// this fix's next pass), at x's row stride; the third of each row is not read.
void FixNVEDiscMN::hold_positions()
{
  double **x = atom->x;
  const int nlocal = atom->nlocal;
  held.resize(granmn::row_start(nlocal, 3));
  for (int i = 0; i < nlocal; i++) {
    held[granmn::row_start(i, 3)] = x[i][0];
    held[granmn::row_start(i, 3) + 1] = x[i][1];
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
  const int *mask = atom->mask;
  members.clear();
  const bool verlet = integrator == mn::Integrator::VelocityVerlet;
  const double scale = verlet ? dtf : force->ftm2v;
  // fix nve/sphere disc's operations: (dtf / inertia) / (r^2 m), inertia = 1/2
  const double scale_rotation = scale / 0.5;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double m = rmass[i], r = radius[i];
    members.push_back({granmn::row_start(i, 3), i, scale / m, scale_rotation / (r * r * m),
                       m * gravity[0], m * gravity[1]});
  }
  factors_lastcall = neighbor->lastcall;
  factors_stale = false;
}

// The factors follow the atoms: recomputed after a neighbour-list build (atoms re-sorted or
// exchanged), at the first step after another run, or at every step under a fix adapt.
void FixNVEDiscMN::refresh_factors()
{
  if (factors_stale || factors_every_step || neighbor->lastcall != factors_lastcall)
    compute_factors();
  if (neigh_check && neighbor->lastcall != held_lastcall) hold_positions();
}

// neigh_check: whether LAMMPS's Neighbor::decide() would look at this step (its `ago` is
// counted up when it decides, after this pass): the steps since the last build if at least
// `delay` and a multiple of `every`, else 0.
int FixNVEDiscMN::build_due() const
{
  const int ago = neighbor->ago + 1;
  return ago >= neighbor->delay && ago % neighbor->every == 0 ? ago : 0;
}

// neigh_check at a step where LAMMPS would decide: with check no, a build; with check yes,
// LAMMPS's own test (Neighbor::check_distance, the same operations: z does not move, reduced
// over the processes), and a build found needed at the first step it could be is dangerous,
// as LAMMPS counts it.
void FixNVEDiscMN::request_build(bool moved, int ago)
{
  int flag = 1;
  if (neighbor->dist_check) {
    flag = moved ? 1 : 0;
    if (comm->nprocs > 1) {
      int flag_all = 0;
      MPI_Allreduce(&flag, &flag_all, 1, MPI_INT, MPI_MAX, world);
      flag = flag_all;
    }
    if (flag && ago == MAX(neighbor->every, neighbor->delay)) neighbor->ndanger++;
  }
  if (flag) next_reneighbor = update->ntimestep;
}

void FixNVEDiscMN::initial_integrate(int)
{
  refresh_factors();
  if (gravity_pending) {
    add_gravity();
    gravity_pending = false;
  }
  const int ago = neigh_check ? build_due() : 0;    // > 0: LAMMPS would decide at this step
  const bool check = ago > 0 && neighbor->dist_check;
  const double *hold = held.data();
  // the largest squared displacement since the build, compared with the trigger once after
  // the pass: a flag set in the pass was kept on the stack, its store and reload a chain
  // through every disk's step (the same decision: max(d^2) > trigger iff some d^2 > trigger)
  double farthest = 0.0;

  if (integrator == mn::Integrator::VelocityVerlet) {
    // the vectors as flat arrays (granmn_flat_arrays.h), and the step in a local: the stores
    // to x could alias the member for the compiler, which would reload it. The new values are
    // computed into locals before any store: v, f, x and omega could alias for the compiler,
    // which would store and reload.
    double *const xs = granmn::rows(atom->x), *const vs = granmn::rows(atom->v);
    const double *const fs = granmn::rows(atom->f), *const ts = granmn::rows(atom->torque);
    double *const ws = granmn::rows(atom->omega);
    const double step = dtv;
    for (const Member &m : members) {
      const std::ptrdiff_t k = m.row;
      const double vx = vs[k] + m.per_mass * fs[k], vy = vs[k + 1] + m.per_mass * fs[k + 1];
      const double wz = ws[k + 2] + m.per_inertia * ts[k + 2];
      const double xi = xs[k] + step * vx, yi = xs[k + 1] + step * vy;
      vs[k] = vx;
      vs[k + 1] = vy;
      ws[k + 2] = wz;
      xs[k] = xi;
      xs[k + 1] = yi;
      if (check) {
        const double dx = xi - hold[k], dy = yi - hold[k + 1];
        farthest = std::max(farthest, dx * dx + dy * dy);
      }
    }
    if (ago) request_build(farthest > trigger_sq, ago);
    return;
  }
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  double **omega = atom->omega;
  double **torque = atom->torque;
  for (const Member &m : members) {
    const int i = m.atom;
    double *previous = state[i];
    const double a[3] = {f[i][0] * m.per_mass, f[i][1] * m.per_mass,
                         torque[i][2] * m.per_inertia};
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
      const double dx = x[i][0] - hold[m.row], dy = x[i][1] - hold[m.row + 1];
      farthest = std::max(farthest, dx * dx + dy * dy);
    }
  }
  if (ago) request_build(farthest > trigger_sq, ago);
}

// The end of a step: m g into the step's forces; under velocity Verlet the second half kick in
// the same pass (the atoms may have been re-sorted since the first).
void FixNVEDiscMN::final_integrate()
{
  refresh_factors();
  if (integrator != mn::Integrator::VelocityVerlet) {
    add_gravity();
    return;
  }
  // flat arrays and the new values in locals, as in initial_integrate
  double *const vs = granmn::rows(atom->v), *const fs = granmn::rows(atom->f);
  double *const ws = granmn::rows(atom->omega);
  const double *const ts = granmn::rows(atom->torque);
  if (has_gravity) {
    // m g first added to the step's force sum (after every other force)
    for (const Member &m : members) {
      const std::ptrdiff_t k = m.row;
      const double fx = fs[k] + m.weight_x, fy = fs[k + 1] + m.weight_y;
      const double vx = vs[k] + m.per_mass * fx, vy = vs[k + 1] + m.per_mass * fy;
      const double wz = ws[k + 2] + m.per_inertia * ts[k + 2];
      fs[k] = fx;
      fs[k + 1] = fy;
      vs[k] = vx;
      vs[k + 1] = vy;
      ws[k + 2] = wz;
    }
  } else {
    for (const Member &m : members) {
      const std::ptrdiff_t k = m.row;
      const double vx = vs[k] + m.per_mass * fs[k], vy = vs[k + 1] + m.per_mass * fs[k + 1];
      const double wz = ws[k + 2] + m.per_inertia * ts[k + 2];
      vs[k] = vx;
      vs[k + 1] = vy;
      ws[k + 2] = wz;
    }
  }
}

double FixNVEDiscMN::memory_usage()
{
  return FixPerAtomState::memory_usage() + (double) members.capacity() * sizeof(Member) +
      (double) held.capacity() * sizeof(double);
}
