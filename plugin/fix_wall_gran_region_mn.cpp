/* ----------------------------------------------------------------------
   fix wall/gran/region/mn: a region's surface as a wall with the law of mn_contact.h.
   Which faces an atom touches, and where, comes from LAMMPS's Region::surface (as for LAMMPS's
   fix wall/gran/region); the history of each face in contact is kept by the face's number.
------------------------------------------------------------------------- */

#include "fix_wall_gran_region_mn.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "granmn_compat.h"
#include "granmn_run_checks.h"
#include "modify.h"
#include "neighbor.h"
#include "region.h"
#include "update.h"

#include <cmath>
#include <cstring>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;

// fix ID group wall/gran/region/mn region-ID [kn K] [e E] [beta B] [mu MU] [limit_damping]
//                                            [coulomb_cutback]
FixWallGranRegionMN::FixWallGranRegionMN(LAMMPS *lmp, int narg, char **arg) :
    FixPerAtomState(lmp, narg, arg), region(nullptr), max_contacts(0), own_law(false),
    use_history(false), integrator(mn::Integrator::VelocityVerlet), ut_width(1),
    ut_block(-1), record_block(-1), vt_block(-1), observer(nullptr),
    force_per_mass_acceleration(1.0), force_reduced(false), radii_change(false)
{
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "Fix wall/gran/region/mn requires atom attributes radius, rmass, omega, "
                      "torque (atom_style sphere)");
  if (narg < 4) error->all(FLERR, "Illegal fix wall/gran/region/mn command: expected a region ID");
  region_id = arg[3];
  find_region();
  max_contacts = region->tmax;
  int iarg = 4;
  while (iarg < narg) {
    const int used =
        granmn::parse_law_keyword(lmp, "fix wall/gran/region/mn", narg, arg, iarg, parsed);
    if (!used)
      error->all(FLERR, "Illegal fix wall/gran/region/mn command: unknown keyword {}", arg[iarg]);
    iarg += used;
  }
  resolve_law();
  use_history = law.material.mu > 0.0;
  ut_width = granmn::ut_width(lmp);

  restart_global = 1;    // the region's motion: see write_restart
  vector_flag = 1;
  size_vector = domain->dimension == 3 ? 3 : 2;    // the force of the atoms on the region
  global_freq = 1;
  extvector = 1;
  // [0] the count, the faces, u_t of each slot; the record's and the previous v_t's blocks
  // come at init
  register_state(1 + max_contacts + (use_history ? max_contacts * ut_width : 0));
  if (use_history) ut_block = 1 + max_contacts;
  wall_force[0] = wall_force[1] = wall_force[2] = 0.0;
}

int FixWallGranRegionMN::setmask()
{
  return POST_FORCE | PRE_NEIGHBOR;
}

void FixWallGranRegionMN::find_region()
{
  region = granmn::region_by_id(domain, region_id);
  if (!region)
    error->all(FLERR, "Fix wall/gran/region/mn: region {} does not exist", region_id);
  if (region->varshape)
    error->all(FLERR, "Fix wall/gran/region/mn: region {} changes its shape (variable "
                      "parameters): its surface velocity is not known; move or rotate it instead",
               region_id);
}

// Material from the fix line where given, else from pair_style gran/mn (as fix wall/gran/mn).
void FixWallGranRegionMN::resolve_law()
{
  const granmn::WallLaw wall = granmn::wall_law(lmp, "wall/gran/region/mn", parsed);
  law = wall.law;
  own_law = wall.own;
}

void FixWallGranRegionMN::init()
{
  // A deck may delete the region and define it again between runs (LAMMPS's
  // examples/granregion turns its box so): the contacts carry on by face number, and the
  // region's motion is the new one's unless the region is the one the fix last saw (its
  // displacement and angle of the last step as the fix left them: also after a restart).
  const Region *before = region;
  find_region();
  if (region->tmax > max_contacts)
    error->all(FLERR, "Fix wall/gran/region/mn: region {} was defined again with {} faces an "
                      "atom can touch at once, more than the {} the fix keeps: define the fix "
                      "again", region_id, region->tmax, max_contacts);
  bool same_motion = region == before;
  for (int k = 0; k < 4; k++) same_motion = same_motion && region->prev[k] == motion.prev[k];
  if (!same_motion) motion = Motion();
  resolve_law();
  if (law.material.mu > 0.0 && !use_history)
    error->all(FLERR, "Fix wall/gran/region/mn was defined with mu = 0 and keeps no tangential "
                      "history; define it again after giving mu > 0");
  granmn::check_disc_integration(lmp, "fix wall/gran/region/mn");
  force_per_mass_acceleration = 1.0 / force->ftm2v;
  integrator = granmn::integrator_in_use(modify);
  radii_change = !granmn::fixes_by_style(modify, "^adapt").empty();
  observer = granmn::find_observer(granmn::all_fixes(modify));
  // The observer's record of each slot (with fix contacts/mn), and Adams-Bashforth 2's
  // previous v_t of each slot: kept from then on (current under either integrator), as by
  // fix wall/gran/mn, also when a restart brings them
  const int record_start = 1 + max_contacts + max_contacts * ut_width;
  const int vt_start = record_start + max_contacts * granmn::RECORD_SIZE;
  if (observer) widen_state(vt_start);
  if (use_history && integrator == mn::Integrator::AdamsBashforth2)
    widen_state(vt_start + max_contacts * ut_width);
  record_block = observer ? record_start : -1;
  vt_block = use_history && ncols >= vt_start + max_contacts * ut_width ? vt_start : -1;
  if (own_law) granmn::check_timestep(lmp, "fix wall/gran/region/mn", update->dt, law, integrator);
}

// The normal velocity (away from the face) of local atom i against a face it has just left,
// for the observer's row of the ended contact: the face is found again within the atom's
// diameter (it left it by less than a step's motion).
double FixWallGranRegionMN::ended_normal_velocity(int i, int face)
{
  double **x = atom->x;
  const int nc = region->surface(x[i][0], x[i][1], x[i][2], 2.0 * atom->radius[i]);
  for (int ic = 0; ic < nc; ic++) {
    const Region::Contact &near = region->contact[ic];
    if (near.iwall != face || near.r <= 0.0) continue;
    double wall_velocity[3] = {0.0, 0.0, 0.0};
    if (region->dynamic_check()) region->velocity_contact(wall_velocity, x[i], ic);
    const double d[3] = {near.delx, near.dely, near.delz};
    double vn = 0.0;
    for (int c = 0; c < 3; c++) vn += d[c] / near.r * (atom->v[i][c] - wall_velocity[c]);
    return vn;
  }
  error->one(FLERR, "Fix wall/gran/region/mn: atom {} left face {} of region {} by more than "
                    "its radius in one step (time step far too large)", atom->tag[i], face,
             region_id);
  return 0.0;
}

int FixWallGranRegionMN::contacts_held(int i) const
{
  if (!observer || !(atom->mask[i] & groupbit)) return 0;
  return static_cast<int>(state[i][0]);
}

// Listed here as well as at each build: a run with `pre no` has no build before its first step.
void FixWallGranRegionMN::setup(int vflag)
{
  list_near_surface();
  post_force(vflag);
}

void FixWallGranRegionMN::pre_neighbor()
{
  list_near_surface();
}

void FixWallGranRegionMN::list_near_surface()
{
  near_surface.clear();
  if (region->dynamic_check() || radii_change) return;
  double **x = atom->x;
  const double *radius = atom->radius;
  const double skin = neighbor->skin;
  const bool planar = domain->dimension == 2;
  // atom i outside the region (a region that is not open lets it in between builds, next
  // to a face), or a face within its skin. In 2D not a face's pure z contact (a slab's faces
  // at z = +-0.5, right above and below every disk: no wall, the disks lie in the plane); a
  // contact with a part in the plane counts (an open region reports only the nearest point
  // to an atom outside it, which can be on a z face's rim: its part in the plane is no more
  // than the distance to the faces in the plane).
  const auto near_a_face = [&](int i) {
    if (!region->match(x[i][0], x[i][1], x[i][2])) return true;
    const int nc = region->surface(x[i][0], x[i][1], x[i][2], radius[i] + skin);
    for (int ic = 0; ic < nc; ic++)
      if (!planar || region->contact[ic].delx != 0.0 || region->contact[ic].dely != 0.0)
        return true;
    return false;
  };
  // every atom, in the group or not: a dynamic group can change between builds
  for (int i = 0; i < atom->nlocal; i++)
    if (state[i][0] > 0.0 || near_a_face(i)) near_surface.push_back(i);
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
// wall's velocity there (a moving or rotating region) subtracted. A face's history follows it
// by its number from step to step; a face no longer touched loses it.
template <int DIM> void FixWallGranRegionMN::post_force_loop()
{
  const double dt_history = granmn::history_dt(update);
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  double **omega = atom->omega;
  double **torque = atom->torque;
  const double *radius = atom->radius;
  const double *rmass = atom->rmass;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const mn::Law contact = law;
  const double to_force = force_per_mass_acceleration;
  const mn::Integrator scheme = integrator;
  const int width = ut_width;
  const int nslots = max_contacts;
  granmn::ContactObserver *const events = observer;
  const bool moving = region->dynamic_check();
  double on_walls[3] = {0.0, 0.0, 0.0};
  // the slots of one atom as they were, to carry each face's history to its new slot
  std::vector<double> before(ncols);

  if (moving) {
    region->prematch();
    track_motion();
  }
  // a region at rest: only the atoms near its surface (near_surface); a moving one, or radii
  // that change: every atom
  const bool every = moving || radii_change;
  const int visited = every ? nlocal : static_cast<int>(near_surface.size());
  for (int n = 0; n < visited; n++) {
    const int i = every ? n : near_surface[n];
    if (!(mask[i] & groupbit)) continue;
    double *row = state[i];
    const int touching_before = static_cast<int>(row[0]);
    int nc = 0;
    // most atoms are far from the surface: no contact now or before, nothing to carry
    if (region->match(x[i][0], x[i][1], x[i][2])) {
      nc = region->surface(x[i][0], x[i][1], x[i][2], radius[i]);
    } else if (touching_before > 0 && !region->openflag) {
      error->one(FLERR, "Fix wall/gran/region/mn: atom {} has passed through the surface of "
                        "region {} (time step too large for the contact stiffness?)",
                 atom->tag[i], region_id);
    }
    if (nc > nslots)
      error->one(FLERR, "Fix wall/gran/region/mn: atom {} touches {} faces of region {}, "
                        "more than the {} it can have", atom->tag[i], nc, region_id, nslots);
    if (nc == 0 && touching_before == 0) continue;
    for (int k = 0; k < ncols; k++) before[k] = row[k];
    int kept = 0;
    for (int ic = 0; ic < nc; ic++) {
      const Region::Contact &face = region->contact[ic];
      // in 2D a face normal to z is no wall (the disks lie in the plane)
      if (DIM == 2 && face.delz != 0.0) continue;
      if (face.r <= 0.0)
        error->one(FLERR, "Fix wall/gran/region/mn: atom {} has reached the surface of region "
                          "{} with its centre (time step too large for the contact stiffness?)",
                   atom->tag[i], region_id);
      // the face's slot: its history if it was touched at the last evaluation, else none
      const int slot = kept++;
      double *ut = ut_block >= 0 ? row + ut_block + slot * width : nullptr;
      double *vt_previous = vt_block >= 0 ? row + vt_block + slot * width : nullptr;
      double *record = record_block >= 0 ? row + record_block + slot * granmn::RECORD_SIZE
                                         : nullptr;
      int old = 0;
      while (old < touching_before && static_cast<int>(before[1 + old]) != face.iwall) old++;
      const bool began = old == touching_before;
      if (!began) before[1 + old] = -1.0;    // matched: not among the faces that ended
      row[1 + slot] = face.iwall;
      for (int c = 0; c < width; c++) {
        if (ut) ut[c] = began ? 0.0 : before[ut_block + old * width + c];
        if (vt_previous) vt_previous[c] = began ? 0.0 : before[vt_block + old * width + c];
      }
      if (record && !began)
        for (int k = 0; k < granmn::RECORD_SIZE; k++)
          record[k] = before[record_block + old * granmn::RECORD_SIZE + k];
      double wall_velocity[3] = {0.0, 0.0, 0.0};
      if (moving) region->velocity_contact(wall_velocity, x[i], ic);
      const double d[3] = {face.delx, face.dely, face.delz};
      const double dv[3] = {v[i][0] - wall_velocity[0], v[i][1] - wall_velocity[1],
                            v[i][2] - wall_velocity[2]};
      const auto kin = mn::wall_kinematics<DIM>(d, face.r, radius[i], dv, omega[i]);
      if (events) {
        events->update_record(record, began, kin.delta, kin.vn);
        if (began || events->reports_every_contact()) events->boundary_touching(i, began);
      }
      mn::add_wall_contact<DIM>(contact, mn::boundary_mass_scale(rmass[i]) * to_force, kin, ut,
                                dt_history, scheme, vt_previous, radius[i], f[i], torque[i],
                                on_walls);
    }
    row[0] = kept;
    // the faces touched at the last evaluation and not at this one: their contacts ended
    for (int old = 0; events && old < touching_before; old++)
      if (before[1 + old] >= 0.0)
        events->boundary_ended(i, &before[record_block + old * granmn::RECORD_SIZE],
                               ended_normal_velocity(i, static_cast<int>(before[1 + old])));
    // slots beyond the faces touched hold no history (a face touched again starts afresh)
    for (int slot = kept; slot < touching_before && slot < nslots; slot++) {
      row[1 + slot] = 0.0;
      for (int c = 0; c < width; c++) {
        if (ut_block >= 0) row[ut_block + slot * width + c] = 0.0;
        if (vt_block >= 0) row[vt_block + slot * width + c] = 0.0;
      }
    }
  }
  for (int c = 0; c < DIM; c++) wall_force[c] = on_walls[c];
  force_reduced = false;
}

// The region's velocity at this step. Region::set_velocity differences its displacement and
// angle from the step before; Region::init, at every run, forgets that step, so the first force
// evaluation of each run saw the region at rest: a sphere rolling on a moving floor got a kick
// of mu m g for a step (LAMMPS's fix wall/gran/region has it so). The fix keeps the velocity
// of the last step it evaluated, also in restart files, and gives it back at a run's first
// evaluation of that same step, differencing from the displacement found then.
void FixWallGranRegionMN::track_motion()
{
  const bigint step = update->ntimestep;
  if (update->setupflag && step == motion.step) {
    for (int c = 0; c < 3; c++) {
      region->v[c] = motion.v[c];
      region->omega[c] = motion.omega[c];
      region->rpoint[c] = motion.rpoint[c];
    }
    region->prev[0] = region->dx;
    region->prev[1] = region->dy;
    region->prev[2] = region->dz;
    region->prev[3] = region->theta;
    region->vel_timestep = static_cast<int>(step);
  } else {
    region->set_velocity();
  }
  motion.step = step;
  for (int c = 0; c < 3; c++) {
    motion.v[c] = region->v[c];
    motion.omega[c] = region->omega[c];
    motion.rpoint[c] = region->rpoint[c];
  }
  for (int k = 0; k < 4; k++) motion.prev[k] = region->prev[k];
}

void FixWallGranRegionMN::write_restart(FILE *fp)
{
  if (comm->me) return;
  const double values[Motion::SIZE] = {
      static_cast<double>(motion.step), motion.v[0],      motion.v[1],      motion.v[2],
      motion.omega[0],                  motion.omega[1],  motion.omega[2],  motion.rpoint[0],
      motion.rpoint[1],                 motion.rpoint[2], motion.prev[0],   motion.prev[1],
      motion.prev[2],                   motion.prev[3]};
  const int size = Motion::SIZE * sizeof(double);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(values, sizeof(double), Motion::SIZE, fp);
}

void FixWallGranRegionMN::restart(char *buf)
{
  double values[Motion::SIZE];
  memcpy(values, buf, sizeof(values));
  motion.step = static_cast<bigint>(values[0]);
  for (int c = 0; c < 3; c++) {
    motion.v[c] = values[1 + c];
    motion.omega[c] = values[4 + c];
    motion.rpoint[c] = values[7 + c];
  }
  // the region of the restart is taken for the one the fix saw (init compares these)
  for (int k = 0; k < 4; k++) region->prev[k] = motion.prev[k] = values[10 + k];
}

double FixWallGranRegionMN::compute_vector(int n)
{
  if (!force_reduced) {
    MPI_Allreduce(wall_force, wall_force_all, size_vector, MPI_DOUBLE, MPI_SUM, world);
    force_reduced = true;
  }
  return wall_force_all[n];
}
