/* ----------------------------------------------------------------------
   fix wall/gran/mn: flat walls with the law of mn_contact.h.
   The per-atom u_t history follows LAMMPS's fix wall/gran (grow/exchange/restart).
------------------------------------------------------------------------- */

#include "fix_wall_gran_mn.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

// fix ID group wall/gran/mn xplane|yplane|zplane|zcylinder lo hi [kn K] [e E] [beta B]
//                                         [mu MU] [limit_damping] [coulomb_cutback]
// (zplane in dimension 3 only; zcylinder: radii of an inner and an outer cylinder about z)
FixWallGranMN::FixWallGranMN(LAMMPS *lmp, int narg, char **arg) :
    FixWallGranMNBase(lmp, narg, arg), restart_rows_in_slots(false)
{
  const bool three_d = domain->dimension == 3;
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

  // a slot per side, side s in slot s; its key says whether the side touches (with an observer)
  define_law_and_slots(narg, arg, 6, 2, false);
  restart_global = 1;    // that the rows are in slots: see write_restart
}

void FixWallGranMN::init_geometry()
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
}

void FixWallGranMN::init()
{
  FixWallGranMNBase::init();
  for (int side : {0, 1}) {
    granmn::ContactLayout &kept = side_layout[side];
    kept.ut_width = slots.ut_width;
    kept.ut = ut_block >= 0 ? ut_block + side * slots.ut_width : -1;
    kept.record = record_block >= 0 ? record_block + side * granmn::RECORD_SIZE : -1;
    kept.touching = observer ? slots.key(side) : -1;
    kept.vt_previous = vt_block >= 0 ? vt_block + side * slots.ut_width : -1;
  }
}

bool FixWallGranMN::within_reach(int i, double reach)
{
  double **x = atom->x;
  const double at = axis == ZCYLINDER ? std::sqrt(x[i][0] * x[i][0] + x[i][1] * x[i][1])
                                      : x[i][axis];
  return (has_lo && at - lo < reach) || (has_hi && hi - at < reach);
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
// the stack at every atom near a wall, the many that do not touch it included.
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
        side_ended<DIM, CYLINDER>(i, side, dist, rho, dt_history);
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
  forces_evaluated(on_walls);
}

// Side `side` of the wall has just stopped touching atom i, now at dist from it: its last
// force's energies booked (energy yes), the observer's event, the flag cleared.
template <int DIM, bool CYLINDER>
void FixWallGranMN::side_ended(int i, int side, double dist, double rho, double dt_history)
{
  const granmn::ContactLayout &layout = side_layout[side];
  double *row = state[i];
  row[layout.touching] = 0.0;
  row[granmn::WallSlots::HELD] -= 1.0;
  double n[3];
  const double vn =
      inward_normal<CYLINDER>(atom->x, atom->v, i, axis, side == 0 ? 1.0 : -1.0, rho, n);
  double *energy = slot_energy(i, side);
  if (!energy) {
    observer->boundary_ended(i, row + layout.record, vn, nullptr);
    return;
  }
  const mn::ContactEnergy total = book_ended_wall_energy<DIM>(
      i, n, dist, dt_history, layout.ut >= 0 ? row + layout.ut : nullptr, energy);
  observer->boundary_ended(i, row + layout.record, vn, &total);
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
  const bool began = OBSERVED && row[layout.touching] == 0.0;
  if (OBSERVED) {
    granmn::ContactObserver *const events = observer;
    double &touching = row[layout.touching];
    events->update_record(row + layout.record, began, radius[i] - dist, vn);
    touching = 1.0;
    if (began) row[granmn::WallSlots::HELD] += 1.0;
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
  const double scale = mn::boundary_mass_scale(atom->rmass[i]) * force_per_mass_acceleration;
  double *energy = OBSERVED ? slot_energy(i, side) : nullptr;
  if (energy)
    add_wall_contact_with_energy<DIM>(i, scale, kin, ut, dt_history, vt_previous, energy,
                                      on_walls, began);
  else
    mn::add_wall_contact<DIM>(law, scale, kin, ut, dt_history, integrator, vt_previous,
                              radius[i], atom->f[i], atom->torque[i], on_walls);
}

// The rows are in slots (granmn::WallSlots): a global record (the number of slots) says so. A
// restart file without it holds each row as the fix kept it before the walls shared their
// slots (u_t of both sides, each side's record and touching flag, the previous v_t of both),
// which unpack_restart moves into the slots.
void FixWallGranMN::write_restart(FILE *fp)
{
  if (comm->me) return;
  const double nslots = slots.count;
  const int size = sizeof(double);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(&nslots, sizeof(double), 1, fp);
}

void FixWallGranMN::restart(char *)
{
  restart_rows_in_slots = true;
}

void FixWallGranMN::unpack_restart(int nlocal, int nth)
{
  if (restart_rows_in_slots) {
    FixPerAtomState::unpack_restart(nlocal, nth);
    return;
  }
  int stored = 0;
  const double *written = restart_row(nlocal, nth, stored);
  // each part of the row as written where the row reaches it: u_t of both sides, each side's
  // record and touching flag, the previous v_t of both
  const int width = slots.ut_width, record_size = granmn::RECORD_SIZE;
  const int records_at = 2 * width, vt_at = records_at + 2 * (record_size + 1);
  const bool has_ut = stored >= records_at, has_records = stored >= vt_at,
             has_vt = stored >= vt_at + 2 * width;
  widen_state(has_vt        ? slots.end()
              : has_records ? slots.vt_block()
              : has_ut      ? slots.record_block()
                            : 0);
  double *row = state[nlocal];
  for (int k = 0; k < ncols; k++) row[k] = 0.0;
  for (int side : {0, 1}) {
    for (int c = 0; c < width; c++) {
      if (has_ut) row[slots.ut_block() + side * width + c] = written[side * width + c];
      if (has_vt) row[slots.vt_block() + side * width + c] = written[vt_at + side * width + c];
    }
    if (has_records) {
      const double *record = written + records_at + side * (record_size + 1);
      for (int k = 0; k < record_size; k++)
        row[slots.record_block() + side * record_size + k] = record[k];
      row[slots.key(side)] = record[record_size];
      row[granmn::WallSlots::HELD] += record[record_size];
    }
  }
}
