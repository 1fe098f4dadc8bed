/* ----------------------------------------------------------------------
   pair_style gran/mn: the law of mn_contact.h between disks and bumps.
   Structure follows LAMMPS's pair gran/hooke/history (neighbor history through
   FixNeighHistory, created in init_style in place of a placeholder fix). Here the force loop
   and its history; the bump types, the checks, the overlap reports, the published law, the
   cut-offs' radii and the restart settings are in the granmn_*.h units included below.
------------------------------------------------------------------------- */

#include "pair_gran_mn.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_dummy.h"
#include "fix_neigh_history.h"
#include "force.h"
#include "granmn_compat.h"
#include "granmn_flat_arrays.h"
#include "granmn_insertion_radii.h"
#include "granmn_law_arguments.h"
#include "granmn_overlap_reports.h"
#include "granmn_pair_checks.h"
#include "granmn_pair_restart.h"
#include "granmn_published_law.h"
#include "granmn_run_checks.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

PairGranMN::PairGranMN(LAMMPS *lmp) :
    Pair(lmp), restart_history_size(-1),
    observer(nullptr),
    law_reported(false), force_per_mass_acceleration(1.0), max_radius(nullptr),
    fix_history(nullptr)
{
  single_enable = 1;
  no_virial_fdotr_compute = 1;
  centroidstressflag = CENTROID_NOTAVAIL;
  finitecutflag = 1;
  restartinfo = 1;
  // u_t and the counters' state are symmetric under i <-> j (t and v_ij both flip), so the history is copied,
  // not negated as LAMMPS's default transfer does for shear vectors.
  nondefault_history_transfer = 1;

  single_extra = 5;
  svector = new double[single_extra];

  // Placeholder so that the history fix, created in init_style, keeps this position among fixes.
  fix_dummy = (FixDummy *) modify->add_fix("NEIGH_HISTORY_GRANMN_DUMMY" +
                                           std::to_string(instance_me) + " all DUMMY");
}

PairGranMN::~PairGranMN()
{
  if (granmn::fix_by_id(modify, "GRANMN_ATOM_IDS" + std::to_string(instance_me)))
    modify->delete_fix("GRANMN_ATOM_IDS" + std::to_string(instance_me));
  // replaced by another pair style: the former wall types interact again (at exit the
  // neighbor class is already gone)
  if (neighbor) bumps.release_exclusions(lmp);
  delete[] svector;
  if (!fix_history)
    modify->delete_fix("NEIGH_HISTORY_GRANMN_DUMMY" + std::to_string(instance_me));
  else
    modify->delete_fix("NEIGH_HISTORY_GRANMN" + std::to_string(instance_me));
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    delete[] max_radius;
  }
}

/* ---------------------------------------------------------------------- */

// The law's mass scale of a contact (before conversion to force units): a bump is boundary.
static inline double contact_mass_scale(bool i_wall, bool j_wall, double mi, double mj)
{
  return j_wall ? mn::boundary_mass_scale(mi)
      : i_wall  ? mn::boundary_mass_scale(mj)
                : mn::pair_mass_scale(mi, mj);
}

// d[0] * e[0] + ... over the dimension's components, in this order.
template <int DIM> static inline double dot(const double *d, const double *e)
{
  return DIM == 3 ? d[0] * e[0] + d[1] * e[1] + d[2] * e[2] : d[0] * e[0] + d[1] * e[1];
}

// |u_t|^2 of a contact's history (0 where the law keeps no u_t).
template <int DIM> static inline double ut_squared(const double *ut)
{
  return !ut ? 0.0 : DIM == 3 ? ut[0] * ut[0] + ut[1] * ut[1] + ut[2] * ut[2] : ut[0] * ut[0];
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

// The share of a contact's energies booked to atom i (its partner has the rest): half to each
// of two disks, all of it to the disk against a bump.
static inline double energy_share(bool i_wall, bool j_wall)
{
  return i_wall ? 0.0 : j_wall ? 1.0 : 0.5;
}

// A contact just ended: its atoms have one contact less; its row goes to the observer, once even
// if both processes hold the pair. d = x_i - x_j; energy: what it dissipated (nullptr where
// energies are not booked).
template <int DIM>
void PairGranMN::report_end(int i, int j, const double *d, double rsq, const double *state,
                            const tagint *tag, const mn::ContactEnergy *energy)
{
  double **v = atom->v;
  const double dv[3] = {v[i][0] - v[j][0], v[i][1] - v[j][1], v[i][2] - v[j][2]};
  const double vn = dot<DIM>(d, dv) / sqrt(rsq);
  const bool tally_j = force->newton_pair || j < atom->nlocal;
  const bool record = tally_j || tag[i] < tag[j];
  observer->pair_ended(i, j, bumps.is_bump(atom->type[j]), bumps.is_bump(atom->type[i]), state,
                       vn, record, tally_j, energy);
}

void PairGranMN::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  if (domain->dimension == 2 && neighbor->ago == 0) granmn::check_in_plane(lmp);
  const bool friction = layout.ut >= 0, observed = observer != nullptr;
  const bool energy = layout.energy >= 0;
  if (sends_ghost_velocity) granmn::forward_comm(comm, this);
  if (domain->dimension == 3)
    compute_for<3>(friction, observed, energy);
  else
    compute_for<2>(friction, observed, energy);
}

// The loop compiled for what the run needs: a law without friction keeps no u_t, a run
// without fix contacts/mn reports no contacts, one that does not ask for energies books none,
// and none pays a test per contact for it. Energies are booked for the observer.
template <int DIM> void PairGranMN::compute_for(bool friction, bool observed, bool energy)
{
  if (friction) {
    if (energy)
      compute_loop<DIM, true, true, true>();
    else
      observed ? compute_loop<DIM, true, true, false>() : compute_loop<DIM, true, false, false>();
  } else {
    if (energy)
      compute_loop<DIM, false, true, true>();
    else
      observed ? compute_loop<DIM, false, true, false>()
               : compute_loop<DIM, false, false, false>();
  }
}

// What the force loop reads, gathered once per force evaluation: the neighbour scan keeps
// only its own few values in registers, and a contact's work reads the rest from here.
struct PairGranMN::LoopData {
  const double *x, *v, *omega, *radius, *rmass;    // x, v, omega as flat arrays
  double *f, *torque;
  const int *type;
  const tagint *tag;
  int nlocal, newton_pair;
  mn::Law contact;
  const char *is_wall;
  double to_force, dt_history;
  granmn::ContactObserver *events;    // read only where OBSERVED
  int ut_slot, record_slot, vt_previous_slot, energy_slot;
  mn::Integrator scheme;
  const granmn::EnergyTallies *energies;    // read only where ENERGY
};

// The force loop in dimension DIM: 2, disks (u_t a scalar; torques about z); 3, spheres (u_t a
// vector; forces and torques in three components). The overloads of mn::kinematics and
// mn::force_and_torques (mn_contact.h) take each contact through the dimension's law.
// FRICTION: the law keeps u_t (mu > 0); OBSERVED: a contact observer (fix contacts/mn) is
// told of contacts. A pair keeps history if either holds.
// Most neighbours do not touch (in a dense 2D flow four in five): the scan over them is kept
// small, and a contact's work is a call (touching_pair, ended_pair). With that work inlined the
// scan had the registers of both and reloaded its own values from the stack at every
// neighbour, the many that do not touch included.
template <int DIM, bool FRICTION, bool OBSERVED, bool ENERGY> void PairGranMN::compute_loop()
{
  // The per-atom vectors as flat arrays (granmn_flat_arrays.h): atom j's position is at
  // x + 3 j, found without loading the row pointer x[j] first, for each neighbour and each
  // vector of a contact.
  const auto row = [](int k) { return granmn::row_start(k, 3); };
  LoopData data;
  data.x = granmn::rows(atom->x);
  data.v = granmn::rows(atom->v);
  data.f = granmn::rows(atom->f);
  data.omega = granmn::rows(atom->omega);
  data.torque = granmn::rows(atom->torque);
  data.radius = atom->radius;
  data.rmass = atom->rmass;
  data.type = atom->type;
  data.tag = atom->tag;
  data.nlocal = atom->nlocal;
  data.newton_pair = force->newton_pair;
  data.contact = law;
  data.is_wall = bumps.by_type();
  data.to_force = force_per_mass_acceleration;
  data.dt_history = granmn::history_dt(update);
  data.events = observer;
  data.ut_slot = layout.ut;
  data.record_slot = layout.record;
  data.vt_previous_slot = layout.vt_previous;
  data.energy_slot = layout.energy;
  data.scheme = integrator;
  data.energies = ENERGY ? observer->energy_tallies() : nullptr;

  // Locals, not members: a member would be loaded again after every call of a contact's work,
  // which may have changed it for all the compiler knows.
  const double *x = data.x;
  const double *radius = data.radius;
  const int stride = layout.size;
  const int inum = list->inum;
  const int *ilist = list->ilist;
  const int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  constexpr bool history = FRICTION || OBSERVED;
  int **firsttouch = history ? fix_history->firstflag : nullptr;
  double **firstslots = history ? fix_history->firstvalue : nullptr;

  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const int jnum = numneigh[i];
    // an atom without neighbours (most of a dilute flow's) has nothing to do; marked unlikely,
    // so that a dense flow, where every atom has some, keeps its loop as it was
    if (__builtin_expect(jnum == 0, 0)) continue;
    const double xi[3] = {x[row(i)], x[row(i) + 1], DIM == 3 ? x[row(i) + 2] : 0.0};
    const double radi = radius[i];
    const int *jlist = firstneigh[i];
    int *touch = history ? firsttouch[i] : nullptr;
    double *slots_all = history ? firstslots[i] : nullptr;

    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const double *xj = x + row(j);
      const double d[3] = {xi[0] - xj[0], xi[1] - xj[1], DIM == 3 ? xi[2] - xj[2] : 0.0};
      const double rsq = dot<DIM>(d, d);
      const double radsum = radi + radius[j];
      double *slots = history ? slots_all + stride * jj : nullptr;
      if (rsq >= radsum * radsum) {
        // a pair that is not touching already has zero history (FixNeighHistory hands new
        // pairs zeros): only a contact that just ended has any to clear
        if (history && __builtin_expect(touch[jj] != 0, 0))
          ended_pair<DIM, OBSERVED, ENERGY>(data, i, j, d[0], d[1], d[2], rsq, touch + jj,
                                            slots, stride, data.record_slot);
      } else {
        touching_pair<DIM, FRICTION, OBSERVED, ENERGY>(data, i, j, d[0], d[1], d[2], rsq,
                                                       radsum, history ? touch + jj : nullptr,
                                                       slots);
      }
    }
  }
}

// A contact that has just ended: its last force's second half booked (ENERGY), the observer's
// row, and its history cleared.
template <int DIM, bool OBSERVED, bool ENERGY>
void PairGranMN::ended_pair(const LoopData &data, int i, int j, double dx, double dy, double dz,
                            double rsq, int *touch, double *slots, int stride, int record_slot)
{
  const double d[3] = {dx, dy, dz};
  if (ENERGY) {
    const mn::ContactEnergy energy = book_ended<DIM>(data, i, j, d, rsq, slots);
    report_end<DIM>(i, j, d, rsq, slots + record_slot, atom->tag, &energy);
  } else if (OBSERVED) {
    report_end<DIM>(i, j, d, rsq, slots + record_slot, atom->tag, nullptr);
  }
  *touch = 0;
  for (int k = 0; k < stride; k++) slots[k] = 0.0;
}

// One pair in contact (rsq < radsum^2; (dx, dy, dz) = x_i - x_j): the law's force and torques,
// tallied to i and, where this process tallies it, to j. touch and slots: the pair's flag and
// history (nullptr where the run keeps none). The components come by value: an array's address
// would have the scan store it for every neighbour.
template <int DIM, bool FRICTION, bool OBSERVED, bool ENERGY>
void PairGranMN::touching_pair(const LoopData &data, int i, int j, double dx, double dy,
                               double dz, double rsq, double radsum, int *touch, double *slots)
{
  const double d[3] = {dx, dy, dz};
  const auto row = [](int k) { return granmn::row_start(k, 3); };
  const double *radius = data.radius;
  const double radi = radius[i], radj = radius[j];
  const double r = sqrt(rsq);
  // the centre of one inside the other: as the wall fix's centre that reached its wall
  if (r <= MAX(radi, radj)) granmn::report_passed_through(lmp, law, bumps, cutsq, i, j, r);
  const double *vi = data.v + row(i), *vj = data.v + row(j);
  const double *wi = data.omega + row(i), *wj = data.omega + row(j);
  const double dv[3] = {vi[0] - vj[0], vi[1] - vj[1], vi[2] - vj[2]};
  const double lever[3] = {radi * wi[0] + radj * wj[0], radi * wi[1] + radj * wj[1],
                           radi * wi[2] + radj * wj[2]};
  const auto kin = mn::kinematics(mn::Dim<DIM>(), d, r, radsum, dv, lever);
  // looked up per contact, not per atom: most atoms of a dilute flow touch nothing
  const bool i_wall = data.is_wall[data.type[i]], j_wall = data.is_wall[data.type[j]];
  const bool tally_j = data.newton_pair || j < data.nlocal;
  const bool began = OBSERVED && !*touch;
  if (OBSERVED) {
    granmn::ContactObserver *const events = data.events;
    events->update_record(slots + data.record_slot, began, kin.delta, kin.vn);
    if (const granmn::ContactTallies *step = events->pair_tallies()) {
      step->add(i, j_wall, began);
      if (tally_j) step->add(j, i_wall, began);
    } else if (began || events->reports_every_contact()) {
      events->pair_touching(i, j, j_wall, i_wall, began, tally_j);
    }
  }
  if (FRICTION || OBSERVED) *touch = 1;
  double *ut = FRICTION ? slots + data.ut_slot : nullptr;
  // the law gives mass x acceleration; LAMMPS turns force back into it with ftm2v
  const double scale =
      contact_mass_scale(i_wall, j_wall, data.rmass[i], data.rmass[j]) * data.to_force;

  double fc_xyz[3];
  double *vt_previous =
      FRICTION && data.vt_previous_slot >= 0 ? slots + data.vt_previous_slot : nullptr;
  double *torque = data.torque;
  if (ENERGY) {
    const mn::EnergyStep booked = mn::force_and_torques_with_energy(
        data.contact, scale, kin, lever, ut, data.dt_history, data.scheme, vt_previous,
        slots + data.energy_slot, fc_xyz, radi, torque + row(i), radj,
        tally_j ? torque + row(j) : nullptr);
    const mn::StoredEnergy stored =
        mn::stored_energy(data.contact, scale, kin.delta, ut_squared<DIM>(ut));
    const double share_i = energy_share(i_wall, j_wall);
    data.energies->add(i, share_i, booked, stored);
    if (tally_j) data.energies->add(j, 1.0 - share_i, booked, stored);
    if (began && data.dt_history == 0.0) {
      const mn::EnergyStep opened = mn::open_energy_account(
          data.contact, scale, kin.delta, ut_squared<DIM>(ut), slots + data.energy_slot);
      data.energies->add(i, share_i, opened, {0.0, 0.0});
      if (tally_j) data.energies->add(j, 1.0 - share_i, opened, {0.0, 0.0});
    }
  } else {
    mn::force_and_torques(data.contact, scale, kin, ut, data.dt_history, data.scheme,
                          vt_previous, fc_xyz, radi, torque + row(i), radj,
                          tally_j ? torque + row(j) : nullptr);
  }
  double *f = data.f;
  for (int c = 0; c < DIM; c++) f[row(i) + c] += fc_xyz[c];
  if (tally_j)
    for (int c = 0; c < DIM; c++) f[row(j) + c] -= fc_xyz[c];
  if (evflag)
    ev_tally_xyz(i, j, data.nlocal, data.newton_pair, 0.0, 0.0, fc_xyz[0], fc_xyz[1], fc_xyz[2],
                 d[0], d[1], d[2]);
}

// A contact found ended (d = x_i - x_j, its history not yet cleared): its last force's second
// half and its springs' release booked to its atoms; what it dissipated in all.
template <int DIM>
mn::ContactEnergy PairGranMN::book_ended(const LoopData &data, int i, int j, const double *d,
                                         double rsq, double *slots)
{
  const auto row = [](int k) { return granmn::row_start(k, 3); };
  const double radi = data.radius[i], radj = data.radius[j];
  const double *vi = data.v + row(i), *vj = data.v + row(j);
  const double *wi = data.omega + row(i), *wj = data.omega + row(j);
  const double dv[3] = {vi[0] - vj[0], vi[1] - vj[1], vi[2] - vj[2]};
  const double lever[3] = {radi * wi[0] + radj * wj[0], radi * wi[1] + radj * wj[1],
                           radi * wi[2] + radj * wj[2]};
  const auto kin = mn::kinematics(mn::Dim<DIM>(), d, sqrt(rsq), radi + radj, dv, lever);
  const bool i_wall = data.is_wall[data.type[i]], j_wall = data.is_wall[data.type[j]];
  const double scale =
      contact_mass_scale(i_wall, j_wall, data.rmass[i], data.rmass[j]) * data.to_force;
  const double *ut = data.ut_slot >= 0 ? slots + data.ut_slot : nullptr;
  double *energy = slots + data.energy_slot;
  const mn::EnergyStep booked =
      book_ended_energy(data.contact, scale, kin, lever, ut_squared<DIM>(ut), data.dt_history,
                        data.scheme, energy);
  const double share_i = energy_share(i_wall, j_wall);
  data.energies->add(i, share_i, booked, {0.0, 0.0});
  if (data.newton_pair || j < data.nlocal) data.energies->add(j, 1.0 - share_i, booked, {0.0, 0.0});
  return mn::contact_energy(data.contact, scale, 0.0, 0.0, energy);
}

/* ---------------------------------------------------------------------- */

void PairGranMN::allocate()
{
  allocated = 1;
  const int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) setflag[i][j] = 0;
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  max_radius = new double[n + 1];
}

// A new law: reported at the next init_style, its derived values published now.
void PairGranMN::publish_law()
{
  law_reported = false;
  granmn::publish_law_variables(lmp, law);
}

// What is known only at a run's setup, after the domain's and the neighbor's init.
void PairGranMN::setup()
{
  granmn::warn_deep_overlaps(lmp, law, bumps, list);
  granmn::check_deform_remap(lmp, sends_ghost_velocity);
  granmn::check_special_bonds(lmp);
}

int PairGranMN::pack_forward_comm(int n, int *list, double *buf, int, int *)
{
  const double *v = granmn::rows(atom->v), *omega = granmn::rows(atom->omega);
  int m = 0;
  for (int k = 0; k < n; k++) {
    const std::ptrdiff_t row = granmn::row_start(list[k], 3);
    buf[m++] = v[row];
    buf[m++] = v[row + 1];
    buf[m++] = omega[row + 2];
  }
  return m;
}

void PairGranMN::unpack_forward_comm(int n, int first, double *buf)
{
  double *v = granmn::rows(atom->v), *omega = granmn::rows(atom->omega);
  int m = 0;
  for (int i = first; i < first + n; i++) {
    const std::ptrdiff_t row = granmn::row_start(i, 3);
    v[row] = buf[m++];
    v[row + 1] = buf[m++];
    omega[row + 2] = buf[m++];
  }
}

// pair_style gran/mn kn K e E beta B mu MU [wall_types T ...] [limit_damping] [coulomb_cutback]
void PairGranMN::settings(int narg, char **arg)
{
  granmn::LawArguments parsed;
  bumps.types.clear();
  int iarg = 0;
  while (iarg < narg) {
    int used = granmn::parse_law_keyword(lmp, "pair_style gran/mn", narg, arg, iarg, parsed);
    if (!used) used = bumps.parse(lmp, narg, arg, iarg);
    if (!used)
      error->all(FLERR, "Illegal pair_style gran/mn command: unknown keyword {}", arg[iarg]);
    iarg += used;
  }
  granmn::check_one_gran_mn(lmp, this);
  law = granmn::law_from_arguments(lmp, "pair_style gran/mn", parsed, nullptr);
  publish_law();
  if (domain->box_exist) bumps.check_types(lmp);
}

void PairGranMN::coeff(int narg, char **arg)
{
  if (narg != 2)
    error->all(FLERR, "Incorrect args for pair coefficients: pair_style gran/mn takes "
                      "pair_coeff * * with no further arguments");
  if (!allocated) allocate();

  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  int count = 0;
  for (int i = ilo; i <= ihi; i++)
    for (int j = MAX(jlo, i); j <= jhi; j++) {
      setflag[i][j] = 1;
      count++;
    }
  if (count == 0) error->all(FLERR, "Incorrect args for pair coefficients");
  bumps.check_types(lmp);
}

/* ---------------------------------------------------------------------- */

void PairGranMN::init_style()
{
  follow_dimension();
  granmn::check_sphere_attributes(lmp);
  set_ghost_velocity();
  bumps.check_types(lmp);
  bumps.check_atoms(lmp);
  granmn::check_disc_integration(lmp, "pair_style gran/mn");
  force_per_mass_acceleration = 1.0 / force->ftm2v;
  granmn::warn_builds_once(lmp);
  integrator = granmn::integrator_in_use(modify);
  if (!law_reported && comm->me == 0) {
    granmn::report_law(lmp, law);
    law_reported = true;
  }
  granmn::check_timestep(lmp, "pair_style gran/mn", update->dt, law, integrator);
  set_up_history();
  bumps.exclude_bump_pairs(lmp);
  // cut-offs follow the largest radius of each type, inserted atoms' too
  granmn::largest_radii(lmp, max_radius);
}

// The law was derived for the dimension's shape of inertia when the pair style was given
// (after the box, and so after the dimension command: its constructor adds a fix); kept
// right here should the dimension ever be known only later.
void PairGranMN::follow_dimension()
{
  if (law.q == granmn::dimension_q(lmp)) return;
  law = granmn::checked_law(lmp, "pair_style gran/mn", law.material, law.options,
                            granmn::dimension_q(lmp));
  publish_law();
}

// The law reads the ghosts' v and omega. LAMMPS's own comm_modify vel yes sends them with x,
// 3 values each, in one message through a buffer; without it LAMMPS sends x alone, in place.
// In 3D the style turns LAMMPS's own on (as LAMMPS's granular styles require it): sending
// v and omega in a second message of its own cost more (the 3D chute, docs/performance.md).
// In 2D it sends them itself at compute(), only vx, vy and omega_z: a third of the values
// LAMMPS's own would add. The values are the same, so is every force to the bit. (Comm's
// init, after the pair's, sizes the messages for the setting.)
void PairGranMN::set_ghost_velocity()
{
  if (domain->dimension == 3) comm->ghost_velocity = 1;
  sends_ghost_velocity = comm->ghost_velocity == 0;
  comm_forward = sends_ghost_velocity ? 3 : 0;
}

// The per-contact history: u_t when there is friction (and under Adams-Bashforth 2 the
// previous v_t its rule for u_t needs), then the contact observer's record if there is one
// (fix contacts/mn), then the energy history if it books energies (energy yes).
void PairGranMN::set_up_history()
{
  observer = granmn::find_observer(granmn::all_fixes(modify));
  const bool energy = observer && observer->energy_tallies();
  const granmn::ContactLayout needed = granmn::pair_history_layout(
      law.material.mu > 0.0, integrator == mn::Integrator::AdamsBashforth2, observer,
      granmn::ut_width(lmp),
      energy ? mn::energy_history_size(integrator, domain->dimension) : 0);
  granmn::check_history_size(lmp, needed.size, fix_history ? layout.size : -1,
                             restart_history_size);
  layout = needed;
  const bool history = layout.size > 0;
  // At a reneighboring, fix neigh/history keeps a pair's history only if the pair overlapped
  // when the list was built, i.e. before this step's force evaluation: a contact that ended in
  // the step's move would lose its record before the counters see it end (found by the
  // cross-check with pair_style tracker). The counters keep every pair's flags; the force
  // evaluation clears them when a contact ends, so forces do not change.
  beyond_contact = observer ? 1 : 0;

  granmn::request_size_list(neighbor, this, instance_me, history);

  // the history is keyed by atom IDs: fix GRANMN/ATOM_IDS says at each init when they have
  // changed under it
  if (history) {
    const std::string ids = "GRANMN_ATOM_IDS" + std::to_string(instance_me);
    if (!granmn::fix_by_id(modify, ids)) modify->add_fix(ids + " all GRANMN/ATOM_IDS");
  }

  if (history && !fix_history) {
    auto cmd = fmt::format("NEIGH_HISTORY_GRANMN{} all NEIGH_HISTORY {}", instance_me,
                           layout.size);
    fix_history = (FixNeighHistory *) modify->replace_fix(
        "NEIGH_HISTORY_GRANMN_DUMMY" + std::to_string(instance_me), cmd, 1);
    fix_history->pair = this;
  }
}

double PairGranMN::init_one(int i, int j)
{
  if (!allocated) allocate();
  if (bumps.is_bump(i) && bumps.is_bump(j)) return 0.0;
  return max_radius[i] + max_radius[j];
}

/* ---------------------------------------------------------------------- */

void PairGranMN::write_restart_settings(FILE *fp)
{
  granmn::write_pair_settings(fp, {law.material, law.options, bumps.types, layout.size});
}

void PairGranMN::read_restart_settings(FILE *fp)
{
  const granmn::PairSettings settings = granmn::read_pair_settings(lmp, fp);
  restart_history_size = settings.history_size;
  bumps.types = settings.bump_types;
  law = granmn::checked_law(lmp, "pair_style gran/mn", settings.material, settings.options,
                            granmn::dimension_q(lmp));
  publish_law();
}

void PairGranMN::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) fwrite(&setflag[i][j], sizeof(int), 1, fp);
}

void PairGranMN::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  bumps.check_types(lmp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      if (comm->me == 0) utils::sfread(FLERR, &setflag[i][j], sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
    }
}

/* ---------------------------------------------------------------------- */

// In 2D u_t is a component along t, which flips with n as v_t does: the pair (j, i) has the
// same u_t. In 3D it is a vector, the integral of i's v_t relative to j: the pair (j, i) has
// -u_t (LAMMPS's default transfer for shear vectors). The counters' record is symmetric.
void PairGranMN::GRANMN_TRANSFER_HISTORY(source, target)
{
  for (int k = 0; k < layout.size; k++) target[k] = source[k];
  if (layout.ut >= 0 && layout.ut_width == 3)
    for (int k = layout.ut; k < layout.ut + 3; k++) target[k] = -source[k];
  // The energy history's last force under velocity Verlet: its normal flips with the pair, its
  // f_n (and in 2D f_t, a component along t, which flips too) does not; in 3D the tangential
  // force on j is minus that on i. Energies and Adams-Bashforth 2's powers are the pair's.
  if (layout.energy >= 0 && integrator == mn::Integrator::VelocityVerlet) {
    const int previous = layout.energy + mn::ENERGY_PREVIOUS_FORCE;
    const int dimension = domain->dimension;
    for (int c = 0; c < dimension; c++) target[previous + c] = -source[previous + c];
    if (dimension == 3)
      for (int c = 4; c < 7; c++) target[previous + c] = -source[previous + c];
  }
}

// For compute pair/local: fforce*(dx,dy) is the normal force; svector = ft, delta, vn, vt, ut
// (in 3D the magnitudes |F_t|, |v_t|, |u_t|).
double PairGranMN::single(int i, int j, int, int, double rsq, double, double, double &fforce)
{
  const double radsum = atom->radius[i] + atom->radius[j];
  if (rsq >= radsum * radsum) {
    fforce = 0.0;
    for (int m = 0; m < single_extra; m++) svector[m] = 0.0;
    return 0.0;
  }
  return domain->dimension == 3 ? single_contact<3>(i, j, rsq, fforce)
                                : single_contact<2>(i, j, rsq, fforce);
}

// A 2D component as it is, a 3D vector's magnitude: what single() reports.
static inline double reported(double value)
{
  return value;
}

static inline double reported(const double (&vector)[3])
{
  return sqrt(vector[0] * vector[0] + vector[1] * vector[1] + vector[2] * vector[2]);
}

// single() in dimension DIM for a pair in contact, as compute_loop evaluates it.
template <int DIM> double PairGranMN::single_contact(int i, int j, double rsq, double &fforce)
{
  double **x = atom->x;
  double **v = atom->v;
  double **omega = atom->omega;
  const double ri = atom->radius[i], rj = atom->radius[j];
  const double r = sqrt(rsq);
  const double d[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], DIM == 3 ? x[i][2] - x[j][2] : 0.0};
  const double dv[3] = {v[i][0] - v[j][0], v[i][1] - v[j][1], v[i][2] - v[j][2]};
  const double lever[3] = {ri * omega[i][0] + rj * omega[j][0], ri * omega[i][1] + rj * omega[j][1],
                           ri * omega[i][2] + rj * omega[j][2]};
  const auto kin = mn::kinematics(mn::Dim<DIM>(), d, r, ri + rj, dv, lever);

  double ut[3] = {0.0, 0.0, 0.0};    // a copy: single() must not alter the stored history
  if (layout.ut >= 0) {
    const int jnum = list->numneigh[i];
    const int *jlist = list->firstneigh[i];
    for (int jj = 0; jj < jnum; jj++)
      if ((jlist[jj] & NEIGHMASK) == j) {
        for (int c = 0; c < layout.ut_width; c++)
          ut[c] = fix_history->firstvalue[i][layout.size * jj + layout.ut + c];
        break;
      }
  }
  const double ut_reported = DIM == 3 ? reported(ut) : ut[0];
  const auto fc = mn::contact_force(law,
                                    contact_mass_scale(bumps.is_bump(atom->type[i]),
                                                       bumps.is_bump(atom->type[j]),
                                                       atom->rmass[i], atom->rmass[j]) *
                                        force_per_mass_acceleration,
                                    kin, law.material.mu > 0.0 ? ut : nullptr, 0.0);
  fforce = fc.fn / r;
  svector[0] = reported(fc.ft);
  svector[1] = kin.delta;
  svector[2] = kin.vn;
  svector[3] = reported(kin.vt);
  svector[4] = ut_reported;
  return 0.0;
}

void *PairGranMN::extract(const char *name, int &dim)
{
  if (strcmp(name, granmn::LAW_EXTRACT_NAME) != 0) return nullptr;
  dim = 0;
  return &law;
}

#ifdef GRANMN_PAIR_HAS_ATOM2CUT
double PairGranMN::atom2cut(int i)
{
  return 2.0 * atom->radius[i];
}

double PairGranMN::radii2cut(double r1, double r2)
{
  return r1 + r2;
}
#endif
