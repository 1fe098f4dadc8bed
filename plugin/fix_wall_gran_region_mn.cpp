/* ----------------------------------------------------------------------
   fix wall/gran/region/mn: a region's surface as a wall with the law of mn_contact.h.
   Which faces an atom touches, and where, comes from LAMMPS's Region::surface (as for LAMMPS's
   fix wall/gran/region), of each part of a union or intersect (granmn_region_surface.h); the
   history of each face in contact is kept by the face's number.
------------------------------------------------------------------------- */

#include "fix_wall_gran_region_mn.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "granmn_compat.h"
#include "region.h"
#include "update.h"

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

using namespace LAMMPS_NS;

// fix ID group wall/gran/region/mn region-ID [kn K] [e E] [beta B] [mu MU] [limit_damping]
//                                            [coulomb_cutback]
FixWallGranRegionMN::FixWallGranRegionMN(LAMMPS *lmp, int narg, char **arg) :
    FixWallGranMNBase(lmp, narg, arg), faces_renumbered(false)
{
  if (narg < 4) error->all(FLERR, "Illegal fix wall/gran/region/mn command: expected a region ID");
  region_id = arg[3];
  find_region();
  evaluated_layout = surface.layout();
  define_law_and_slots(narg, arg, 4, surface.region()->tmax, true);
  restart_global = 1;    // the region's motion: see write_restart
}

void FixWallGranRegionMN::find_region()
{
  Region *region = granmn::region_by_id(domain, region_id);
  if (!region)
    error->all(FLERR, "Fix wall/gran/region/mn: region {} does not exist", region_id);
  if (region->varshape)
    error->all(FLERR, "Fix wall/gran/region/mn: region {} changes its shape (variable "
                      "parameters): its surface velocity is not known; move or rotate it instead",
               region_id);
  surface.assign(domain, region);
  // a part's motion is kept where the region still has as many parts (the run's first
  // evaluation checks that it is the same motion)
  if (motions.size() != surface.parts().size()) motions.assign(surface.parts().size(), Motion());
}

// A deck may delete the region and define it again between runs (LAMMPS's
// examples/granregion turns its box so): the contacts carry on by face number where the faces
// are numbered as before, and end at the run's start where not.
void FixWallGranRegionMN::init_geometry()
{
  find_region();
  const Region *region = surface.region();
  if (region->tmax > slots.count)
    error->all(FLERR, "Fix wall/gran/region/mn: region {} was defined again with {} faces an "
                      "atom can touch at once, more than the {} the fix keeps: define the fix "
                      "again", region_id, region->tmax, slots.count);
  faces_renumbered = surface.layout() != evaluated_layout;
}

// Local atom i's face `face`, which it has just left, found again within the atom's diameter (it
// left it by less than a step's motion), with the wall's velocity there. At a run's start the
// face may be gone (the region defined again with it open, or the atom moved between runs):
// false.
bool FixWallGranRegionMN::find_left_face(int i, int face, granmn::SurfaceContact &near,
                                         double v_wall[3])
{
  double **x = atom->x;
  const bool moving = surface.region()->dynamic_check();
  const int nc = surface.surface(x[i], 2.0 * atom->radius[i]);
  for (int ic = 0; ic < nc; ic++) {
    near = surface.contact(ic);
    if (near.iwall != face || near.r <= 0.0) continue;
    if (moving) wall_velocity(near, x[i], v_wall);
    return true;
  }
  if (update->setupflag) return false;
  error->one(FLERR, "Fix wall/gran/region/mn: atom {} left face {} of region {} by more than "
                    "its radius within one step: the atom or the face moved that far in a step "
                    "(a time step far too large, or a move or rotate variable of the region "
                    "that jumps)", atom->tag[i], face, region_id);
  return false;
}

// Local atom i's contact with `face` (-1: a face renumbered, gone) has ended: its record,
// u_t and energy history (nullptr where not booked) as they were at the last evaluation. The
// observer's row gets the normal velocity away from the face (nan where the face is gone) and,
// with energy yes, what the contact dissipated, its last force's second half booked (where the
// face is gone, at a run's start, the step is 0 long: only its spring's release is booked).
template <int DIM>
void FixWallGranRegionMN::face_left(int i, int face, const double *record, const double *ut,
                                    double *energy, double dt_history)
{
  granmn::SurfaceContact near;
  double v_wall[3] = {0.0, 0.0, 0.0};
  const bool found = face >= 0 && find_left_face(i, face, near, v_wall);
  double vn = std::numeric_limits<double>::quiet_NaN();
  double n[3] = {0.0, 0.0, 0.0}, dist = 1.0;
  if (found) {
    const double d[3] = {near.delx, near.dely, near.delz};
    vn = 0.0;
    for (int c = 0; c < 3; c++) vn += d[c] / near.r * (atom->v[i][c] - v_wall[c]);
    for (int c = 0; c < 3; c++) n[c] = d[c] / near.r;
    dist = near.r;
  }
  if (!energy) {
    observer->boundary_ended(i, record, vn, nullptr);
    return;
  }
  const bool moving = surface.region()->dynamic_check();
  const mn::ContactEnergy total = book_ended_wall_energy<DIM>(i, n, dist, dt_history, ut, energy,
                                                              moving ? v_wall : nullptr);
  observer->boundary_ended(i, record, vn, &total);
}

void FixWallGranRegionMN::setup(int vflag)
{
  FixWallGranMNBase::setup(vflag);
  faces_renumbered = false;
  evaluated_layout = surface.layout();
}

bool FixWallGranRegionMN::surface_moves() const
{
  return surface.region()->dynamic_check();
}

// Atom i outside the region (a region that is not open lets it in between builds, next to a
// face), or a face within reach. In 2D not a face's pure z contact (a slab's faces at z = +-0.5,
// right above and below every disk: no wall, the disks lie in the plane); a contact with a
// part in the plane counts (an open region reports only the nearest point to an atom outside
// it, which can be on a z face's rim: its part in the plane is no more than the distance to the
// faces in the plane), and so does one at distance 0.
bool FixWallGranRegionMN::within_reach(int i, double reach)
{
  double **x = atom->x;
  if (!surface.match(x[i])) return true;
  const bool planar = domain->dimension == 2;
  const int nc = surface.surface(x[i], reach);
  for (int ic = 0; ic < nc; ic++) {
    const granmn::SurfaceContact face = surface.contact(ic);
    if (!planar || face.delz == 0.0 || face.delx != 0.0 || face.dely != 0.0) return true;
  }
  return false;
}

void FixWallGranRegionMN::post_force(int)
{
  if (domain->dimension == 3)
    post_force_loop<3>();
  else
    post_force_loop<2>();
}

// Each face the region reports within an atom's radius is one contact, as a plane of
// fix wall/gran/mn: n along (delx, dely, delz) from the face's nearest point to the centre, the
// wall's velocity there (a moving or rotating part of the region) subtracted. A face's history
// follows it by its number from step to step; a face no longer touched loses it.
template <int DIM> void FixWallGranRegionMN::post_force_loop()
{
  const double dt_history = granmn::history_dt(update);
  const bool starting = update->setupflag;
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  double **omega = atom->omega;
  double **torque = atom->torque;
  const double *radius = atom->radius;
  const double *rmass = atom->rmass;
  const int *mask = atom->mask;
  const mn::Law contact = law;
  const double to_force = force_per_mass_acceleration;
  const mn::Integrator scheme = integrator;
  const int width = slots.ut_width;
  const int nslots = slots.count;
  granmn::ContactObserver *const events = observer;
  Region *region = surface.region();
  const bool moving = region->dynamic_check();
  double on_walls[3] = {0.0, 0.0, 0.0};
  // the slots of one atom as they were, to carry each face's history to its new slot
  std::vector<double> before(ncols);

  if (moving) {
    region->prematch();
    track_motion();
  }
  for (const int i : near_wall) {
    if (!(mask[i] & groupbit)) continue;
    double *row = state[i];
    int touching_before = static_cast<int>(row[granmn::WallSlots::HELD]);
    // A region defined again with its faces numbered otherwise: the contacts held end here
    // (no normal to the face they had)
    if (faces_renumbered && touching_before > 0) {
      for (int old = 0; events && old < touching_before; old++)
        face_left<DIM>(i, -1, &row[record_block + old * granmn::RECORD_SIZE],
                       ut_block >= 0 ? &row[ut_block + old * width] : nullptr,
                       slot_energy(i, old), dt_history);
      for (int k = 0; k < ncols; k++) row[k] = 0.0;
      touching_before = 0;
    }
    int nc = 0;
    // most atoms are far from the surface: no contact now or before, nothing to carry
    if (surface.match(x[i])) {
      nc = surface.surface(x[i], radius[i]);
    } else if (touching_before > 0 && !region->openflag && !starting) {
      error->one(FLERR, "Fix wall/gran/region/mn: atom {} has passed through the surface of "
                        "region {} (time step too large for the contact stiffness{}?)",
                 atom->tag[i], region_id,
                 moving ? ", or a move or rotate variable of the region that jumps" : "");
    }
    // in 2D a face normal to z is no wall (the disks lie in the plane): a slab thinner than a
    // disk reports its two z faces as well
    int in_plane = nc;
    if (DIM == 2)
      for (int ic = 0; ic < nc; ic++)
        if (surface.contact(ic).delz != 0.0) in_plane--;
    if (in_plane > nslots)
      error->one(FLERR, "Fix wall/gran/region/mn: atom {} touches {} faces of region {}, "
                        "more than the {} LAMMPS says an atom can touch at once (its tmax)",
                 atom->tag[i], in_plane, region_id, nslots);
    if (nc == 0 && touching_before == 0) continue;
    for (int k = 0; k < ncols; k++) before[k] = row[k];
    int kept = 0;
    for (int ic = 0; ic < nc; ic++) {
      const granmn::SurfaceContact face = surface.contact(ic);
      if (DIM == 2 && face.delz != 0.0) continue;
      if (face.r <= 0.0) {
        if (starting)
          error->one(FLERR, "Fix wall/gran/region/mn: atom {} has its centre on the surface of "
                            "region {} at the start of the run (placed so?)",
                     atom->tag[i], region_id);
        error->one(FLERR, "Fix wall/gran/region/mn: atom {} has reached the surface of region "
                          "{} with its centre (time step too large for the contact stiffness?)",
                   atom->tag[i], region_id);
      }
      // the face's slot: its history if it was touched at the last evaluation, else none
      const int slot = kept++;
      double *ut = ut_block >= 0 ? row + ut_block + slot * width : nullptr;
      double *vt_previous = vt_block >= 0 ? row + vt_block + slot * width : nullptr;
      double *record = record_block >= 0 ? row + record_block + slot * granmn::RECORD_SIZE
                                         : nullptr;
      int old = 0;
      while (old < touching_before && static_cast<int>(before[slots.key(old)]) != face.iwall)
        old++;
      const bool began = old == touching_before;
      if (!began) before[slots.key(old)] = -1.0;    // matched: not among the faces that ended
      row[slots.key(slot)] = face.iwall;
      for (int c = 0; c < width; c++) {
        if (ut) ut[c] = began ? 0.0 : before[ut_block + old * width + c];
        if (vt_previous) vt_previous[c] = began ? 0.0 : before[vt_block + old * width + c];
      }
      if (record && !began)
        for (int k = 0; k < granmn::RECORD_SIZE; k++)
          record[k] = before[record_block + old * granmn::RECORD_SIZE + k];
      double *energy = slot_energy(i, slot);
      if (energy)
        for (int k = 0; k < energy_size; k++)
          energy[k] = began ? 0.0 : before[energy_block + old * energy_size + k];
      double v_wall[3] = {0.0, 0.0, 0.0};
      if (moving) wall_velocity(face, x[i], v_wall);
      const double d[3] = {face.delx, face.dely, face.delz};
      const double dv[3] = {v[i][0] - v_wall[0], v[i][1] - v_wall[1], v[i][2] - v_wall[2]};
      const auto kin = mn::wall_kinematics<DIM>(d, face.r, radius[i], dv, omega[i]);
      if (events) {
        events->update_record(record, began, kin.delta, kin.vn);
        if (began || events->reports_every_contact()) events->boundary_touching(i, began);
      }
      const double scale = mn::boundary_mass_scale(rmass[i]) * to_force;
      if (energy)
        add_wall_contact_with_energy<DIM>(i, scale, kin, ut, dt_history, vt_previous, energy,
                                          on_walls, began, moving ? v_wall : nullptr);
      else
        mn::add_wall_contact<DIM>(contact, scale, kin, ut, dt_history, scheme, vt_previous,
                                  radius[i], f[i], torque[i], on_walls);
    }
    row[granmn::WallSlots::HELD] = kept;
    // the faces touched at the last evaluation and not at this one: their contacts ended
    for (int old = 0; events && old < touching_before; old++)
      if (before[slots.key(old)] >= 0.0)
        face_left<DIM>(i, static_cast<int>(before[slots.key(old)]),
                       &before[record_block + old * granmn::RECORD_SIZE],
                       ut_block >= 0 ? &before[ut_block + old * width] : nullptr,
                       energy_block >= 0 ? &before[energy_block + old * energy_size] : nullptr,
                       dt_history);
    // slots beyond the faces touched hold no history (a face touched again starts afresh)
    for (int slot = kept; slot < touching_before && slot < nslots; slot++) {
      row[slots.key(slot)] = 0.0;
      for (int c = 0; c < width; c++) {
        if (ut_block >= 0) row[ut_block + slot * width + c] = 0.0;
        if (vt_block >= 0) row[vt_block + slot * width + c] = 0.0;
      }
      if (energy_block >= 0)
        for (int k = 0; k < energy_size; k++) row[energy_block + slot * energy_size + k] = 0.0;
    }
  }
  forces_evaluated(on_walls);
}

// The velocity of the region's surface at `face` for an atom at x: the part's translation,
// and its rotation about its axis through rpoint at the face's nearest point (as
// Region::velocity_contact).
void FixWallGranRegionMN::wall_velocity(const granmn::SurfaceContact &face, const double *x,
                                        double *v_wall) const
{
  const Region *part = surface.parts()[face.part];
  const Motion &motion = motions[face.part];
  v_wall[0] = v_wall[1] = v_wall[2] = 0.0;
  if (part->moveflag)
    for (int c = 0; c < 3; c++) v_wall[c] = motion.v[c];
  if (part->rotateflag) {
    const double xc[3] = {x[0] - face.delx, x[1] - face.dely, x[2] - face.delz};
    const double *w = motion.omega, *p = motion.rpoint;
    v_wall[0] += w[1] * (xc[2] - p[2]) - w[2] * (xc[1] - p[1]);
    v_wall[1] += w[2] * (xc[0] - p[0]) - w[0] * (xc[2] - p[2]);
    v_wall[2] += w[0] * (xc[1] - p[1]) - w[1] * (xc[0] - p[0]);
  }
}

// A part's displacement and angle as its move and rotate variables give them (prematch).
static std::array<double, 4> displacement_of(const Region *part)
{
  return {part->moveflag ? part->dx : 0.0, part->moveflag ? part->dy : 0.0,
          part->moveflag ? part->dz : 0.0, part->rotateflag ? part->theta : 0.0};
}

// A part's motion at this step, `at` its displacement and angle now, `before` a step earlier:
// v = (at - before)/dt and the angular velocity along its unit axis, as Region::set_velocity
// computes them (which takes the axis as given: a rotate axis of length 2 turned the wall's
// surface twice as fast as the region).
FixWallGranRegionMN::Motion FixWallGranRegionMN::motion_between(const Region *part,
                                                               const double *at,
                                                               const double *before) const
{
  Motion motion;
  motion.step = update->ntimestep;
  for (int k = 0; k < 4; k++) motion.at[k] = at[k];
  if (part->moveflag)
    for (int c = 0; c < 3; c++) motion.v[c] = (at[c] - before[c]) / update->dt;
  if (part->rotateflag) {
    const double *point = granmn::RegionSurface::rotation_point(part);
    const double *axis = granmn::RegionSurface::rotation_axis(part);
    const double angular_speed = (at[3] - before[3]) / update->dt;
    for (int c = 0; c < 3; c++) {
      motion.rpoint[c] = point[c] + at[c];
      motion.omega[c] = angular_speed * axis[c];
    }
  }
  return motion;
}

// The velocity of each moving part at this step. Region::set_velocity differences a part's
// displacement and angle from the last step it was called at: it gives 0 at step 0 and at
// every run's start (Region::init forgets that step: a sphere rolling on a moving floor got a
// kick of mu m g), and a region defined (or defined again) while it moves takes its whole
// displacement over one step for its velocity (a sphere resting on a floor rising at 0.01 was
// launched at 14). Within a run the fix takes the displacement of the step before from its
// own record; at a run's start it evaluates the part's variables at the step before (time -
// dt). Where its record of this step still holds (the same displacement, and a velocity that
// differs by rounding only: the variables unchanged) it keeps that record, so that a run
// continued, also from a restart file, goes on as the uninterrupted one.
void FixWallGranRegionMN::track_motion()
{
  const bigint step = update->ntimestep;
  const std::vector<Region *> &parts = surface.parts();
  const int nparts = static_cast<int>(parts.size());
  bool recorded = !update->setupflag;
  for (int p = 0; p < nparts; p++)
    if (parts[p]->dynamic && motions[p].step != step - 1) recorded = false;
  std::vector<std::array<double, 4>> earlier;    // at a run's start: a step before
  if (!recorded) {
    // on every process: a variable may sum over the atoms
    update->ntimestep = step - 1;
    surface.region()->prematch();
    for (const Region *part : parts) earlier.push_back(displacement_of(part));
    update->ntimestep = step;
    surface.region()->prematch();
  }
  for (int p = 0; p < nparts; p++) {
    if (!parts[p]->dynamic) continue;
    const std::array<double, 4> at = displacement_of(parts[p]);
    const double *before = recorded ? motions[p].at : earlier[p].data();
    Motion now = motion_between(parts[p], at.data(), before);
    const Motion &last = motions[p];
    if (update->setupflag && last.step == step) {
      // to the rounding of the displacements over dt: LAMMPS sums a variable's time anew at
      // each run, and the step before, evaluated now, may round otherwise than it did
      const double eps = std::numeric_limits<double>::epsilon();
      bool same = true;
      for (int k = 0; k < 4; k++) {
        const double tolerance =
            64.0 * eps * (std::fabs(at[k]) + std::fabs(before[k])) / update->dt;
        same = same && at[k] == last.at[k];
        if (k < 3 && parts[p]->moveflag)
          same = same && std::fabs(now.v[k] - last.v[k]) <= tolerance;
        if (k == 3 && parts[p]->rotateflag)
          for (int c = 0; c < 3; c++)
            same = same && std::fabs(now.omega[c] - last.omega[c]) <= tolerance;
      }
      if (same) now = last;
    }
    motions[p] = now;
  }
}

// The motion of the moving parts: one part's as the fix wrote it before it knew unions and
// intersects (14 values, step >= -1), or -(1 + parts) and each part's 14.
void FixWallGranRegionMN::write_restart(FILE *fp)
{
  if (comm->me) return;
  std::vector<double> values;
  std::vector<const Motion *> moving;
  for (size_t p = 0; p < motions.size(); p++)
    if (surface.parts()[p]->dynamic) moving.push_back(&motions[p]);
  const Motion at_rest;
  if (moving.size() > 1) values.push_back(-1.0 - moving.size());
  if (moving.empty()) moving.push_back(&at_rest);
  for (const Motion *motion : moving) {
    values.push_back(static_cast<double>(motion->step));
    values.insert(values.end(), motion->v, motion->v + 3);
    values.insert(values.end(), motion->omega, motion->omega + 3);
    values.insert(values.end(), motion->rpoint, motion->rpoint + 3);
    values.insert(values.end(), motion->at, motion->at + 4);
  }
  const int size = values.size() * sizeof(double);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(values.data(), sizeof(double), values.size(), fp);
}

// Read where the region has as many moving parts as the file (else their velocities are found
// at the run's start).
void FixWallGranRegionMN::restart(char *buf)
{
  std::vector<Motion *> moving;
  for (size_t p = 0; p < motions.size(); p++)
    if (surface.parts()[p]->dynamic) moving.push_back(&motions[p]);
  double first;
  memcpy(&first, buf, sizeof(double));
  const size_t written = first >= -1.0 ? 1 : static_cast<size_t>(-1.0 - first);
  if (written != moving.size()) return;
  const char *at = buf + (first >= -1.0 ? 0 : sizeof(double));
  for (Motion *motion : moving) {
    double values[Motion::SIZE];
    memcpy(values, at, sizeof(values));
    at += sizeof(values);
    motion->step = static_cast<bigint>(values[0]);
    for (int c = 0; c < 3; c++) {
      motion->v[c] = values[1 + c];
      motion->omega[c] = values[4 + c];
      motion->rpoint[c] = values[7 + c];
    }
    for (int k = 0; k < 4; k++) motion->at[k] = values[10 + k];
  }
}
