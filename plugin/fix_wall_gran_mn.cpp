/* ----------------------------------------------------------------------
   fix wall/gran/mn: flat walls with the law of mn_contact.h.
   The per-atom u_t history follows LAMMPS's fix wall/gran (grow/exchange/restart).
------------------------------------------------------------------------- */

#include "fix_wall_gran_mn.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "granmn_compat.h"
#include "granmn_run_checks.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

// fix ID group wall/gran/mn xplane|yplane|zplane|zcylinder lo hi [kn K] [e E] [beta B]
//                                         [mu MU] [limit_damping] [coulomb_cutback]
// (zplane in dimension 3 only; zcylinder: radii of an inner and an outer cylinder about z)
FixWallGranMN::FixWallGranMN(LAMMPS *lmp, int narg, char **arg) :
    FixPerAtomState(lmp, narg, arg), own_law(false), use_history(false),
    integrator(mn::Integrator::VelocityVerlet), observer(nullptr),
    force_per_mass_acceleration(1.0), force_reduced(false), radii_change(false)
{
  const bool three_d = domain->dimension == 3;
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "Fix wall/gran/mn requires atom attributes radius, rmass, omega, torque "
                      "(atom_style sphere)");
  if (narg < 6)
    error->all(FLERR, "Illegal fix wall/gran/mn command: expected {} lo hi",
               three_d ? "xplane|yplane|zplane|zcylinder" : "xplane|yplane|zcylinder");

  if (strcmp(arg[3], "xplane") == 0)
    axis = 0;
  else if (strcmp(arg[3], "yplane") == 0)
    axis = 1;
  else if (strcmp(arg[3], "zplane") == 0 && three_d)
    axis = 2;
  else if (strcmp(arg[3], "zcylinder") == 0)
    axis = ZCYLINDER;
  else if (strcmp(arg[3], "zplane") == 0)
    error->all(FLERR, "Illegal fix wall/gran/mn command: zplane needs dimension 3 (in 2D the "
                      "walls are xplane, yplane or zcylinder)");
  else
    error->all(FLERR, "Illegal fix wall/gran/mn command: unknown wall style {} "
                      "(expected {}; other shapes: fix wall/gran/region/mn)", arg[3],
               three_d ? "xplane, yplane, zplane or zcylinder" : "xplane, yplane or zcylinder");
  has_lo = strcmp(arg[4], "NULL") != 0;
  has_hi = strcmp(arg[5], "NULL") != 0;
  lo = has_lo ? utils::numeric(FLERR, arg[4], false, lmp) : 0.0;
  hi = has_hi ? utils::numeric(FLERR, arg[5], false, lmp) : 0.0;
  if (!has_lo && !has_hi) error->all(FLERR, "Illegal fix wall/gran/mn command: both walls are NULL");
  if (has_lo && has_hi && lo >= hi)
    error->all(FLERR, "Illegal fix wall/gran/mn command: lower wall {} not below upper wall {}",
               lo, hi);
  if (axis == ZCYLINDER && ((has_lo && lo <= 0.0) || (has_hi && hi <= 0.0)))
    error->all(FLERR, "Illegal fix wall/gran/mn command: zcylinder radii must be positive "
                      "(inner {}, outer {})", arg[4], arg[5]);

  int iarg = 6;
  while (iarg < narg) {
    const int used = granmn::parse_law_keyword(lmp, "fix wall/gran/mn", narg, arg, iarg, parsed);
    if (!used) error->all(FLERR, "Illegal fix wall/gran/mn command: unknown keyword {}", arg[iarg]);
    iarg += used;
  }
  resolve_law();
  use_history = law.material.mu > 0.0;

  vector_flag = 1;
  size_vector = three_d ? 3 : 2;    // force exerted by the particles on the walls (x, y[, z])
  global_freq = 1;
  extvector = 1;
  // the columns come at init, where what is kept is known
  register_state(0);
  wall_force[0] = wall_force[1] = wall_force[2] = 0.0;
}

int FixWallGranMN::setmask()
{
  return POST_FORCE | PRE_NEIGHBOR;
}

// Material from the fix line where given, else from pair_style gran/mn.
void FixWallGranMN::resolve_law()
{
  const granmn::WallLaw wall = granmn::wall_law(lmp, "wall/gran/mn", parsed);
  law = wall.law;
  own_law = wall.own;
}

void FixWallGranMN::init()
{
  // as LAMMPS's fix wall/gran: an atom that crosses the periodic boundary comes back on the
  // wall's other side, inside it (checked here, for change_box between runs too)
  for (int dim = 0; dim < 3; dim++) {
    const bool walled = axis == ZCYLINDER ? dim < 2 : dim == axis;
    if (walled && domain->periodicity[dim])
      error->all(FLERR, "Fix wall/gran/mn: cannot use wall in periodic dimension {}: an atom "
                        "re-entering through the boundary would be inside the wall; make the "
                        "boundary of {} non-periodic (f, s or m)", "xyz"[dim], "xyz"[dim]);
  }
  if (axis == ZCYLINDER)
    for (int dim = 0; dim < 2; dim++)
      if (domain->boxlo[dim] > 0.0 || domain->boxhi[dim] < 0.0)
        error->all(FLERR, "Fix wall/gran/mn: the zcylinder's axis (x = y = 0) lies outside the "
                          "box ({} from {} to {}): its walls are about the z axis",
                   "xy"[dim], domain->boxlo[dim], domain->boxhi[dim]);
  resolve_law();
  granmn::check_disc_integration(lmp, "fix wall/gran/mn");
  // the law gives mass x acceleration; LAMMPS turns force back into acceleration with ftm2v
  force_per_mass_acceleration = 1.0 / force->ftm2v;
  observer = granmn::find_observer(granmn::all_fixes(modify));
  integrator = granmn::integrator_in_use(modify);
  radii_change = !granmn::fixes_by_style(modify, "^adapt").empty();
  // The state keeps u_t (mu > 0), the contact observer's record and a touching flag of each
  // side (each wall fix its own, with fix contacts/mn), and the previous v_t of Adams-Bashforth
  // 2's rule for u_t, which is kept from then on (current under either integrator).
  granmn::ContactLayout all[2];
  granmn::wall_state_layout(all, granmn::ut_width(lmp));
  const granmn::ContactLayout &last = all[1];
  if (use_history) widen_state(last.ut + last.ut_width);
  if (observer) widen_state(last.touching + 1);
  if (use_history && integrator == mn::Integrator::AdamsBashforth2)
    widen_state(last.vt_previous + last.ut_width);
  for (int side : {0, 1}) {
    granmn::ContactLayout &kept = side_layout[side];
    kept = all[side];
    if (!use_history) kept.ut = -1;
    if (!observer) kept.record = kept.touching = -1;
    if (!use_history || ncols < last.vt_previous + last.ut_width) kept.vt_previous = -1;
    kept.size = ncols;
  }
  if (law.material.mu > 0.0 && !use_history)
    error->all(FLERR, "Fix wall/gran/mn was defined with mu = 0 and keeps no tangential "
                      "history; define it again after giving mu > 0");
  // The pair style already checked the time step against the same law.
  if (own_law)
    granmn::check_timestep(lmp, "fix wall/gran/mn", update->dt, law,
                           granmn::integrator_in_use(modify));
}

int FixWallGranMN::contacts_held(int i) const
{
  if (!observer || !(atom->mask[i] & groupbit)) return 0;
  int sides = 0;
  for (const granmn::ContactLayout &side : side_layout)
    if (state[i][side.touching] != 0.0) sides++;
  return sides;
}

// Listed here as well as at each build: a run with `pre no` has no build before its first step.
void FixWallGranMN::setup(int vflag)
{
  list_near_wall();
  post_force(vflag);
}

void FixWallGranMN::pre_neighbor()
{
  list_near_wall();
}

// whether atom i's row holds any side's touching flag, u_t or previous v_t
bool FixWallGranMN::holds_state(int i) const
{
  for (const granmn::ContactLayout &side : side_layout) {
    if (side.touching >= 0 && state[i][side.touching] != 0.0) return true;
    for (int k = 0; k < side.ut_width; k++)
      if ((side.ut >= 0 && state[i][side.ut + k] != 0.0) ||
          (side.vt_previous >= 0 && state[i][side.vt_previous + k] != 0.0))
        return true;
  }
  return false;
}

void FixWallGranMN::list_near_wall()
{
  double **x = atom->x;
  const double *radius = atom->radius;
  const int nlocal = atom->nlocal;
  const double skin = neighbor->skin;
  near_wall.clear();
  // every atom, in the group or not: a dynamic group can change between builds
  for (int i = 0; i < nlocal; i++) {
    if (radii_change) {
      near_wall.push_back(i);
      continue;
    }
    const double at = axis == ZCYLINDER ? std::sqrt(x[i][0] * x[i][0] + x[i][1] * x[i][1])
                                        : x[i][axis];
    const bool near =
        (has_lo && at - lo < radius[i] + skin) || (has_hi && hi - at < radius[i] + skin);
    // an atom beyond the skin that still holds a contact's state (it moved that far in one
    // step, or came so from another processor) stays listed until the contact has ended
    if (near || holds_state(i)) near_wall.push_back(i);
  }
}

void FixWallGranMN::post_force(int)
{
  const bool cylinder = axis == ZCYLINDER, observed = observer != nullptr;
  if (domain->dimension == 3)
    post_force_for<3>(cylinder, observed);
  else
    post_force_for<2>(cylinder, observed);
}

// The loop compiled for the wall's kind and for a contact observer or not: a run without fix
// contacts/mn pays no test of each atom for it.
template <int DIM> void FixWallGranMN::post_force_for(bool cylinder, bool observed)
{
  if (cylinder)
    observed ? post_force_loop<DIM, true, true>() : post_force_loop<DIM, true, false>();
  else
    observed ? post_force_loop<DIM, false, true>() : post_force_loop<DIM, false, false>();
}

// The inward normal of side `normal` (+1: lo, -1: hi; a cylinder's: radial, 0 on its axis) at
// atom i, rho its distance from a cylinder's axis; returns the normal velocity along it.
template <bool CYLINDER>
static inline double inward_normal(double **x, double **v, int i, int wall_axis, double normal,
                                   double rho, double n[3])
{
  n[0] = n[1] = n[2] = 0.0;
  if (!CYLINDER) {
    n[wall_axis] = normal;
  } else if (rho > 0.0) {
    n[0] = normal * x[i][0] / rho;
    n[1] = normal * x[i][1] / rho;
  }
  return n[0] * v[i][0] + n[1] * v[i][1] + n[2] * v[i][2];
}

// The force loop in dimension DIM: 2, disks against lines or circles (u_t a scalar); 3,
// spheres against planes normal to x, y or z or cylinders about z (u_t a vector); CYLINDER:
// the zcylinder's two walls, side 0 the inner one (the atoms outside it), side 1 the outer
// one; OBSERVED: a contact observer (fix contacts/mn) is told of contacts. Each contact as in
// the pair style's loop. Only the atoms near a wall are visited (near_wall); of those most do
// not touch it: the scan over them is kept small, and a contact's work is a call
// (touching_side, side_ended). With that work inlined the scan reloaded its own values from
// the stack: 37 instructions an atom away from a wall (callgrind, the 2D frictional scene).
template <int DIM, bool CYLINDER, bool OBSERVED> void FixWallGranMN::post_force_loop()
{
  const double dt_history = granmn::history_dt(update);
  double **x = atom->x;
  const double *radius = atom->radius;
  const int *mask = atom->mask;
  const int group = groupbit;    // a local: the force stores could alias the member
  double **history = state;
  const granmn::ContactLayout layouts[2] = {side_layout[0], side_layout[1]};
  double on_walls[3] = {0.0, 0.0, 0.0};
  const int wall_axis = axis;
  const double wall_at[2] = {lo, hi};

  // One wall side (0: lo, 1: hi; a constant where called) against atom i; rho is i's distance
  // from a cylinder's axis.
  const auto against_side = [&](int i, int side, double rho) __attribute__((always_inline)) {
    const granmn::ContactLayout &layout = layouts[side];
    // u_t's width as a constant, so that clearing it is a store or three, not a call of memset
    constexpr int width = granmn::ut_width(DIM);
    const int ut_at = layout.ut, vt_previous_at = layout.vt_previous;
    // distance from the wall to the centre, along the wall's inward normal
    const double dist = CYLINDER ? (side == 0 ? rho - wall_at[0] : wall_at[1] - rho)
                                 : (side == 0 ? x[i][wall_axis] - wall_at[0]
                                              : wall_at[1] - x[i][wall_axis]);
    double *row = history[i];
    if (!(dist < radius[i])) {
      // the work here is only for a contact that has just ended, the observer's event and the
      // history to clear (as in the pair style)
      if (OBSERVED && __builtin_expect(row[layout.touching] != 0.0, 0))
        side_ended<CYLINDER>(i, side, rho);
      if (ut_at >= 0)
        for (int k = 0; k < width; k++) row[ut_at + k] = 0.0;
      if (vt_previous_at >= 0)
        for (int k = 0; k < width; k++) row[vt_previous_at + k] = 0.0;
      return;
    }
    touching_side<DIM, CYLINDER, OBSERVED>(i, side, dist, rho, dt_history, on_walls);
  };

  // the sides as constants, each atom's lo side before its hi side as before
  const bool lo_side = has_lo, hi_side = has_hi;
  for (const int i : near_wall) {
    if (!(mask[i] & group)) continue;
    const double rho = CYLINDER ? std::sqrt(x[i][0] * x[i][0] + x[i][1] * x[i][1]) : 0.0;
    if (lo_side) against_side(i, 0, rho);
    if (hi_side) against_side(i, 1, rho);
  }
  for (int c = 0; c < DIM; c++) wall_force[c] = on_walls[c];
  force_reduced = false;
}

// Side `side` of the wall has just stopped touching atom i: the observer's event, the flag
// cleared.
template <bool CYLINDER> void FixWallGranMN::side_ended(int i, int side, double rho)
{
  const granmn::ContactLayout &layout = side_layout[side];
  double *row = state[i];
  row[layout.touching] = 0.0;
  double n[3];
  observer->boundary_ended(i, row + layout.record,
                           inward_normal<CYLINDER>(atom->x, atom->v, i, axis,
                                                   side == 0 ? 1.0 : -1.0, rho, n));
}

// Side `side` of the wall touches atom i, whose centre is at dist from it (rho: from a
// cylinder's axis): the law's force and torque on i, the force on the wall into on_walls.
template <int DIM, bool CYLINDER, bool OBSERVED>
void FixWallGranMN::touching_side(int i, int side, double dist, double rho, double dt_history,
                                  double *on_walls)
{
  const granmn::ContactLayout &layout = side_layout[side];
  double **x = atom->x, **v = atom->v;
  const double *radius = atom->radius;
  const double normal = side == 0 ? 1.0 : -1.0;
  double *row = state[i];
  double n[3];
  const double vn = inward_normal<CYLINDER>(x, v, i, axis, normal, rho, n);
  double *ut = layout.ut >= 0 ? row + layout.ut : nullptr;
  double *vt_previous = layout.vt_previous >= 0 ? row + layout.vt_previous : nullptr;
  if (OBSERVED) {
    granmn::ContactObserver *const events = observer;
    double &touching = row[layout.touching];
    const bool began = touching == 0.0;
    events->update_record(row + layout.record, began, radius[i] - dist, vn);
    touching = 1.0;
    if (began || events->reports_every_contact()) events->boundary_touching(i, began);
  }
  if (dist <= 0.0) {
    // at a run's start no step has moved it there: it was placed so (or the wall was)
    if (update->setupflag)
      error->one(FLERR, "Fix wall/gran/mn: atom {} is {} {} at the start of the run, its "
                        "centre on the wall or beyond it (placed so?)",
                 atom->tag[i],
                 CYLINDER ? (side == 0 ? "inside the inner zcylinder of radius"
                                       : "outside the outer zcylinder of radius")
                          : "behind the wall at",
                 side == 0 ? lo : hi);
    error->one(FLERR, "Fix wall/gran/mn: atom {} has passed through the {} {} "
                      "(time step too large for the contact stiffness?)",
               atom->tag[i], CYLINDER ? "zcylinder of radius" : "wall at", side == 0 ? lo : hi);
  }
  const double d[3] = {n[0] * dist, n[1] * dist, n[2] * dist};    // dist > 0 here
  const auto kin = mn::wall_kinematics<DIM>(d, dist, radius[i], v[i], atom->omega[i]);
  mn::add_wall_contact<DIM>(law, mn::boundary_mass_scale(atom->rmass[i]) *
                                     force_per_mass_acceleration,
                            kin, ut, dt_history, integrator, vt_previous, radius[i], atom->f[i],
                            atom->torque[i], on_walls);
}

double FixWallGranMN::compute_vector(int n)
{
  if (!force_reduced) {
    MPI_Allreduce(wall_force, wall_force_all, size_vector, MPI_DOUBLE, MPI_SUM, world);
    force_reduced = true;
  }
  return wall_force_all[n];
}

