// What LIGGGHTS's normal model `mn` and tangential model `mn` share (docs/liggghts.md): the law
// per pair of atom types from LIGGGHTS's property/global values, a contact's mass scale and
// kinematics from LIGGGHTS's contact data, and the check that the two models go together. The
// law itself (mapping and force) is mn_contact.h's, the same header the LAMMPS styles use.
#ifndef GRANMN_LIGGGHTS_LAW_H
#define GRANMN_LIGGGHTS_LAW_H

#include <climits>
#include <cstdio>
#include <cstring>
#include <mpi.h>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "atom.h"
#include "contact_interface.h"
#include "domain.h"
#include "error.h"
#include "fix_wall_gran.h"
#include "force.h"
#include "global_properties.h"
#include "input.h"
#include "mn_contact.h"
#include "mn_integration.h"
#include "mn_contact_events.h"
#include "mn_output_schema.h"
#include "modify.h"
#include "pair_gran.h"
#include "property_registry.h"
#include "update.h"
#include "variable.h"

// A model's work of a contact is one function, the law's functions it calls inlined into it
// (GCC left the kinematics and the tangential force calls, their results passed through
// memory), and without GCC's straight-line vectorisation (on by default at -O2 from GCC 12),
// which paired a contact's lever arms and velocities into vectors through the stack and loaded
// them back across two stores, a stall at every contact: 2/3 of the normal model's time in the
// 3D chute (perf). Neither changes a result: the same operations on the same numbers. What a
// run may not need (a deep overlap at setup, the counters) stays a call.
#if defined(__GNUC__) && !defined(__clang__)
#define GRANMN_CONTACT_WORK __attribute__((flatten, optimize("no-tree-slp-vectorize")))
#define GRANMN_CALLED __attribute__((noinline))
#elif defined(__GNUC__)
#define GRANMN_CONTACT_WORK __attribute__((flatten))
#define GRANMN_CALLED __attribute__((noinline))
#else
#define GRANMN_CONTACT_WORK
#define GRANMN_CALLED
#endif

namespace granmn_liggghts {

// The property/global (peratomtypepair) names of the law's four parameters. e and mu are
// LIGGGHTS's own names for them; k_n (per unit mass scale, not LIGGGHTS's absolute kn) and beta
// have names of their own.
constexpr const char *NORMAL_STIFFNESS = "normalStiffnessPerMass";
constexpr const char *RESTITUTION = "coefficientRestitution";
constexpr const char *TANGENTIAL_RESTITUTION = "coefficientTangentialRestitution";
constexpr const char *FRICTION = "coefficientFriction";

// The values as given: the law checks them itself (mn::material_error), for e over all of
// (0,1] where LIGGGHTS's own reader of coefficientRestitution refuses e <= 0.05.
template <const char *const *NAME>
MatrixProperty *create_parameter(PropertyRegistry &registry, const char *caller, bool)
{
  return MODEL_PARAMS::createPerTypePairProperty(registry, *NAME, caller);
}

// The laws of all pairs of atom types (1..max_type, walls' types included), derived from the
// property/global values at each run's init, for the particles' shape of inertia: LIGGGHTS's
// nve/sphere integrates solid spheres in 3D and discs in 2D (its I = m r^2/2 there).
class LawTable {
 public:
  void derive(LAMMPS_NS::LAMMPS *lmp, PropertyRegistry &registry, const mn::Options &options,
              const char *caller)
  {
    registry.registerProperty(NORMAL_STIFFNESS, &create_parameter<&NORMAL_STIFFNESS>);
    registry.registerProperty(RESTITUTION, &create_parameter<&RESTITUTION>);
    registry.registerProperty(TANGENTIAL_RESTITUTION, &create_parameter<&TANGENTIAL_RESTITUTION>);
    registry.registerProperty(FRICTION, &create_parameter<&FRICTION>);
    double **kn = nullptr, **e = nullptr, **beta = nullptr, **mu = nullptr;
    registry.connect(NORMAL_STIFFNESS, kn, caller);
    registry.connect(RESTITUTION, e, caller);
    registry.connect(TANGENTIAL_RESTITUTION, beta, caller);
    registry.connect(FRICTION, mu, caller);

    const double q = lmp->domain->dimension == 2 ? mn::DISC_Q : mn::SOLID_SPHERE_Q;
    stride = registry.max_type() + 1;
    laws.assign(stride * stride, mn::Law());
    // (fix property/global has made sure that each matrix is symmetric)
    for (int i = 1; i < stride; i++)
      for (int j = 1; j < stride; j++) {
        const mn::Material material{kn[i][j], e[i][j], beta[i][j], mu[i][j]};
        const char *wrong = mn::material_error(material);
        const mn::Law law = mn::derive(material, options, q);
        if (!wrong) wrong = mn::law_error(law);
        if (wrong) {
          const std::string message = std::string(caller) + ": for atom types " +
              std::to_string(i) + " and " + std::to_string(j) + ": " + wrong + " (kn: " +
              NORMAL_STIFFNESS + ", e: " + RESTITUTION + ", beta: " + TANGENTIAL_RESTITUTION +
              ", mu: " + FRICTION + ")";
          lmp->error->all(FLERR, message.c_str());
        }
        laws[i * stride + j] = law;
        check_timestep(lmp, caller, i, j);
      }
    force_per_mass_acceleration = 1.0 / lmp->force->ftm2v;
    publish(lmp, (*this)(1, 1));
  }

  const mn::Law &operator()(int itype, int jtype) const { return laws[itype * stride + jtype]; }

  // Turns the law's mass x acceleration into LIGGGHTS's force units (as the LAMMPS styles do).
  double force_per_mass_acceleration = 1.0;

 private:
  // velocity Verlet (LIGGGHTS's nve/sphere) is stable on the law's stiffest contact mode (a run
  // of no steps takes none)
  void check_timestep(LAMMPS_NS::LAMMPS *lmp, const char *caller, int i, int j) const
  {
    const mn::StabilityLimit limit =
        mn::stability_limit((*this)(i, j), mn::Integrator::VelocityVerlet);
    if (lmp->update->nsteps == 0 || !(lmp->update->dt > limit.dt)) return;
    // the modes are named for disks; in 3D they are those of spheres
    std::string mode = mn::mode_name(limit.mode);
    const std::size_t disks = mode.find("disks");
    if (lmp->domain->dimension == 3 && disks != std::string::npos) mode.replace(disks, 5, "spheres");
    char message[512];
    snprintf(message, sizeof(message),
             "%s: for atom types %d and %d: timestep %g exceeds the stability limit %.6g of "
             "velocity Verlet for %s (the paper uses tau_c/100 = %.6g)",
             caller, i, j, lmp->update->dt, limit.dt, mode.c_str(), 0.01 * (*this)(i, j).tau_c);
    lmp->error->all(FLERR, message);
  }

  // The law of atom types 1 and 1 as equal-style variables, under the names the LAMMPS pair
  // style publishes them (mn_output_schema.h): a deck's time step or output can read them after
  // a run (LIGGGHTS derives the law at a run's init; a deck runs `run 0` first).
  static void publish(LAMMPS_NS::LAMMPS *lmp, const mn::Law &law)
  {
    granmn::output::for_each_published(law, [lmp](const char *name, double number) {
      char value[32];
      snprintf(value, sizeof(value), "%.17g", number);
      char *args[3] = {const_cast<char *>(name), const_cast<char *>("equal"), value};
      lmp->input->variable->set(3, args);
    });
  }

  int stride = 0;
  std::vector<mn::Law> laws;
};

// The boundary (docs/model.md section 2): walls, and particles in fix freeze's group, which
// LIGGGHTS tells by meff: pair_gran_base.h sets it to the other particle's mass when one is
// frozen, a value it never has otherwise (m_i m_j/(m_i + m_j) < min(m_i, m_j)).
inline bool partner_is_boundary(const LIGGGHTS::ContactModels::SurfacesIntersectData &contact)
{
  return contact.is_wall || contact.meff == contact.mi;
}

// ... and, for two particles, whether i is the frozen one (j's partner is the boundary).
inline bool i_is_boundary(const LIGGGHTS::ContactModels::SurfacesIntersectData &contact)
{
  return !contact.is_wall && contact.meff == contact.mj;
}

// A contact's mass scale: against the boundary the mobile particle's own mass (LIGGGHTS's meff
// there), else 2M of the two masses, mn::pair_mass_scale's 2 m_i m_j/(m_i + m_j): twice
// LIGGGHTS's meff = m_i m_j/(m_i + m_j) to the bit (a factor 2 is exact in each rounding),
// without a division of its own.
inline double mass_scale(const LIGGGHTS::ContactModels::SurfacesIntersectData &contact)
{
  if (partner_is_boundary(contact) || i_is_boundary(contact))
    return mn::boundary_mass_scale(contact.meff);
  return 2.0 * contact.meff;
}

// The contact's kinematics as the LAMMPS styles compute them: n from the partner to i, the
// full radii as lever arms (LIGGGHTS's own models use the radii less half the overlap), from the
// same centre distance LIGGGHTS found (delta = x_i - x_j, or from the wall's contact point to
// the centre; r its length and rinv = 1.0 / r; radsum = r_i + r_j, or r_i against a wall).
template <int DIM>
using Kinematics = typename std::conditional<DIM == 2, mn::Kinematics, mn::Kinematics3>::type;

template <int DIM>
inline Kinematics<DIM> kinematics(const LIGGGHTS::ContactModels::SurfacesIntersectData &contact)
{
  const double *vi = contact.v_i, *vj = contact.v_j, *wi = contact.omega_i;
  const double dv[3] = {vi[0] - vj[0], vi[1] - vj[1], vi[2] - vj[2]};
  double lever[3];
  if (contact.is_wall) {
    for (int c = 0; c < 3; c++) lever[c] = contact.radi * wi[c];
  } else {
    const double *wj = contact.omega_j;
    for (int c = 0; c < 3; c++) lever[c] = contact.radi * wi[c] + contact.radj * wj[c];
  }
  return mn::kinematics(mn::Dim<DIM>(), contact.delta, contact.r, contact.rinv, contact.radsum, dv,
                        lever);
}

// The normal model computes a contact's kinematics once and leaves them in LIGGGHTS's contact
// data, where the tangential model (evaluated after it: the two go together) takes them: the
// normal in en, the overlap in deltan, v_n in vn, and the law's tangential velocity in
// vtr1..3 (its v_t, with the full radii as lever arms, in place of LIGGGHTS's; in 2D the
// scalar v_t along t in vtr1).
inline void keep(LIGGGHTS::ContactModels::SurfacesIntersectData &contact,
                 const mn::Kinematics3 &k)
{
  for (int c = 0; c < 3; c++) contact.en[c] = k.n[c];
  contact.deltan = k.delta;
  contact.vn = k.vn;
  contact.vtr1 = k.vt[0];
  contact.vtr2 = k.vt[1];
  contact.vtr3 = k.vt[2];
}

inline void keep(LIGGGHTS::ContactModels::SurfacesIntersectData &contact,
                 const mn::Kinematics &k)
{
  contact.en[0] = k.nx;
  contact.en[1] = k.ny;
  contact.en[2] = 0.0;
  contact.deltan = k.delta;
  contact.vn = k.vn;
  contact.vtr1 = k.vt;
}

inline mn::Kinematics3 kept3(const LIGGGHTS::ContactModels::SurfacesIntersectData &contact)
{
  mn::Kinematics3 k;
  for (int c = 0; c < 3; c++) k.n[c] = contact.en[c];
  k.delta = contact.deltan;
  k.vn = contact.vn;
  k.vt[0] = contact.vtr1;
  k.vt[1] = contact.vtr2;
  k.vt[2] = contact.vtr3;
  return k;
}

inline mn::Kinematics kept2(const LIGGGHTS::ContactModels::SurfacesIntersectData &contact)
{
  return {contact.en[0], contact.en[1], contact.deltan, contact.vn, contact.vtr1};
}

// `model mn` and `tangential mn` are one law: every pair style or wall that names one must name
// the other, with neither cohesion nor rolling friction (their forces would change the
// restitution and contact time the law is derived to keep).
template <class Owner> void check_combination(LAMMPS_NS::LAMMPS *lmp, const std::string &owner,
                                              Owner *models)
{
  const bool normal = models->contact_match("normal", "mn");
  const bool tangential = models->contact_match("tangential", "mn");
  std::string wrong;
  if (normal && !tangential)
    wrong = "model mn needs tangential mn";
  else if (tangential && !normal)
    wrong = "tangential mn needs model mn";
  else if (normal && !models->contact_match("cohesion", "off"))
    wrong = "model mn takes no cohesion model";
  else if (normal && !models->contact_match("rolling_friction", "off"))
    wrong = "model mn takes no rolling_friction model";
  if (!wrong.empty()) lmp->error->all(FLERR, (owner + ": " + wrong).c_str());
}

inline void check_combination(LAMMPS_NS::LAMMPS *lmp)
{
  LAMMPS_NS::Pair *pair = lmp->force->pair_match("gran", 0);
  if (auto *gran = dynamic_cast<LAMMPS_NS::PairGran *>(pair))
    check_combination(lmp, "pair_style gran", gran);
  for (int f = 0; f < lmp->modify->nfix; f++)
    if (auto *wall = dynamic_cast<LAMMPS_NS::FixWallGran *>(lmp->modify->fix[f]))
      check_combination(lmp, std::string("fix ") + wall->id + " wall/gran", wall);
}

// Pairs of particles that overlap deeply (mn::deep_overlap) at a run's setup, said in one
// warning after the setup's force evaluation of the pair style, with the deepest of them.
class DeepOverlaps {
 public:
  // whether the pass beginning is a run's setup (LIGGGHTS evaluates forces there with
  // shearupdate 0; compute pair/gran/local's passes have computeflag 0)
  void begin(LAMMPS_NS::LAMMPS *lmp, const LIGGGHTS::ContactModels::SurfacesIntersectData &pass)
  {
    watching = pass.computeflag && lmp->update->setupflag;
    count = 0;
    deepest = Deepest();
  }

  GRANMN_CALLED void see(LAMMPS_NS::LAMMPS *lmp,
                         const LIGGGHTS::ContactModels::SurfacesIntersectData &contact,
                         const mn::Law &law)
  {
    if (contact.is_wall || !mn::deep_overlap(contact.deltan, contact.radi, contact.radj)) return;
    // newton off: a pair with a ghost is seen by both of its processes; counted by one
    const int *tag = lmp->atom->tag;
    if (!lmp->force->newton_pair && contact.j >= lmp->atom->nlocal &&
        tag[contact.i] > tag[contact.j])
      return;
    count++;
    const double radius = contact.radi < contact.radj ? contact.radi : contact.radj;
    if (contact.deltan / radius <= deepest.fraction) return;
    const bool boundary = partner_is_boundary(contact) || i_is_boundary(contact);
    deepest.fraction = contact.deltan / radius;
    deepest.tag_i = tag[contact.i] < tag[contact.j] ? tag[contact.i] : tag[contact.j];
    deepest.tag_j = tag[contact.i] < tag[contact.j] ? tag[contact.j] : tag[contact.i];
    deepest.overlap = contact.deltan;
    deepest.radius = radius;
    deepest.speed = mn::release_speed(law, contact.deltan, boundary);
  }

  // after the pass, on every process
  void report(LAMMPS_NS::LAMMPS *lmp, const char *caller)
  {
    if (!watching) return;
    watching = false;
    MPI_Comm world = lmp->world;
    long long all = 0;
    MPI_Allreduce(&count, &all, 1, MPI_LONG_LONG, MPI_SUM, world);
    if (all == 0) return;
    // the deepest from the first process that holds it
    double fraction = 0.0;
    MPI_Allreduce(&deepest.fraction, &fraction, 1, MPI_DOUBLE, MPI_MAX, world);
    int me = 0, holder = 0;
    MPI_Comm_rank(world, &me);
    const int mine = deepest.fraction == fraction ? me : INT_MAX;
    MPI_Allreduce(&mine, &holder, 1, MPI_INT, MPI_MIN, world);
    MPI_Bcast(&deepest, sizeof(Deepest) / sizeof(double), MPI_DOUBLE, holder, world);
    if (me != 0) return;
    char message[512];
    snprintf(message, sizeof(message),
             "%s: %lld pair(s) of particles overlap by more than %g of the smaller radius at "
             "the start of the run; the deepest, atoms %.0f and %.0f, by %.6g (%.3g of radius "
             "%.6g): released, it drives them apart at up to %.3g (placed closer than their "
             "radii's sum?)",
             caller, all, mn::DEEP_OVERLAP_FRACTION, deepest.tag_i, deepest.tag_j,
             deepest.overlap, deepest.fraction, deepest.radius, deepest.speed);
    lmp->error->warning(FLERR, message);
  }

  bool watching = false;    // the pass is a run's setup

 private:
  // (doubles only: sent as one array)
  struct Deepest {
    double fraction, tag_i, tag_j, overlap, radius, speed;    // tag_i < tag_j
  };
  long long count = 0;
  Deepest deepest = Deepest();
};

// What each of the two models holds of the law: the options its settings set, the laws of the
// type pairs, and the dimension, made at each run's init (connectToProperties) after the
// combination of models is checked.
struct ModelLaw {
  mn::Options options;
  LawTable laws;
  bool two_d = false;

  void connect(LAMMPS_NS::LAMMPS *lmp, PropertyRegistry &registry, const char *model)
  {
    check_combination(lmp);
    laws.derive(lmp, registry, options, model);
    two_d = lmp->domain->dimension == 2;
  }
};

// The fix contacts/mn of the run, if one is defined (the counters: fix_contacts_mn.h).
inline const granmn::ContactCounter *find_counter(LAMMPS_NS::LAMMPS *lmp)
{
  LAMMPS_NS::Modify *modify = lmp->modify;
  return granmn::find_observer<granmn::ContactCounter>(
      std::vector<LAMMPS_NS::Fix *>(modify->fix, modify->fix + modify->nfix));
}

}    // namespace granmn_liggghts

#endif
