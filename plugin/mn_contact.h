// The Mitarai-Nakanishi 2D linear spring-dashpot contact law (PRE 67, 021301 (2003)), and its 3D
// form for spheres (at the end: a vector u_t kept in the tangent plane),
// free of LAMMPS so that the pair style, the wall fix and the unit tests share one copy. The
// integrators' steps and their stability on a contact are in mn_integration.h.
//
// Conventions (docs/model.md sections 2-3): for a contact of disk i with partner j, n points from j
// to i, t = (-n_y, n_x), delta > 0 is the overlap, v_n = n.v_ij and v_t = t.v_ij with the full
// radii as lever arms. The force on i is fn*n + ft*t and the torque on i is -radius_i*ft.
// A contact's mass scale is 2M = 2 m_i m_j/(m_i+m_j) for two mobile disks and m_i against the
// boundary; the force is the mass scale times an acceleration. The mapping from (k_n, e, beta) to
// the coefficients holds for any shape of inertia, through q = 1 + m r^2/I (docs/model.md
// section 3.1): 3 for the paper's discs, 7/2 for solid spheres.
#ifndef MN_CONTACT_H
#define MN_CONTACT_H

#include <cmath>
#include <limits>
#include <type_traits>

namespace mn {

constexpr double PI = 3.14159265358979323846;

// What a user specifies.
struct Material {
  double kn;     // normal stiffness per unit mass scale
  double e;      // normal restitution of a binary collision, in (0,1]
  double beta;   // tangential restitution of a sticking binary collision, in (0,1]
  double mu;     // Coulomb friction coefficient, >= 0
};

// Optional departures from the paper's law, both off by default.
struct Options {
  bool limit_damping = false;     // clamp fn at zero: no attraction at the end of a contact
  bool coulomb_cutback = false;   // Cundall-Strack: cut u_t back to the Coulomb limit while sliding
};

// The shape of the particles' inertia, q = 1 + m r^2/I with r the contact's lever arm (the
// radius): a sticking contact's tangential motion obeys the normal one's equation with 2 k_n,
// 2 eta_n replaced by 2q k_t, 2q eta_t (docs/model.md section 3.1).
constexpr double DISC_Q = 3.0;            // I = m r^2/2: the paper's 2D discs
constexpr double SOLID_SPHERE_Q = 3.5;    // I = 2 m r^2/5

// The q of a contact of particles i and j (mass m, lever arm r, moment of inertia I):
// 1 + M (r_i^2/I_i + r_j^2/I_j) with M = m_i m_j/(m_i + m_j), the ratio of the reduced mass to
// the tangential effective mass. Two particles of the same q have that q whatever their sizes
// and masses.
inline double pair_q(double mi, double ri, double inertia_i, double mj, double rj,
                     double inertia_j)
{
  return 1.0 + mi * mj / (mi + mj) * (ri * ri / inertia_i + rj * rj / inertia_j);
}

// Against the boundary (mass scale m_i, a partner that does not move): the mobile particle's own
// q, pair_q's limit for m_j, I_j -> infinity.
inline double boundary_q(double mi, double ri, double inertia_i)
{
  return 1.0 + mi * ri * ri / inertia_i;
}

// A material, its options and the coefficients derived from them (docs/model.md section 3).
struct Law {
  Material material;
  Options options;
  double q;   // the shape of inertia the tangential coefficients are derived for
  double eta_n, kt, eta_t;
  double tau_c;   // duration of a binary normal collision
  double tau_w;   // duration of a normal collision with the boundary (mass scale m_i)
  double e_w;     // restitution of a normal collision with the boundary
};

// nullptr if the material is valid, else what is wrong with it.
inline const char *material_error(const Material &m)
{
  if (!(m.kn > 0.0) || !std::isfinite(m.kn)) return "kn must be a finite number > 0";
  if (!(m.e > 0.0 && m.e <= 1.0)) return "e must lie in (0,1]";
  if (!(m.beta > 0.0 && m.beta <= 1.0)) return "beta must lie in (0,1]";
  if (!(m.mu >= 0.0) || !std::isfinite(m.mu)) return "mu must be a finite number >= 0";
  return nullptr;
}

// nullptr if the coefficients derived from a valid material are usable, else why not (a kn so
// large that they overflow).
inline const char *law_error(const Law &law)
{
  if (!(law.tau_c > 0.0) || !std::isfinite(law.eta_n) || !std::isfinite(law.kt) ||
      !std::isfinite(law.tau_w))
    return "kn is too large: the derived coefficients (tau_c, eta_n, kt) overflow";
  return nullptr;
}

// The coefficients for particles of shape q (DISC_Q: the paper's law, which the 2D styles use).
inline Law derive(const Material &m, const Options &options = Options(), double q = DISC_Q)
{
  Law law;
  const double ln_e = std::log(m.e);
  law.material = m;
  law.options = options;
  law.q = q;
  // eta_n = sqrt(2 kn / ((pi/ln e)^2 + 1)), written so that e = 1 gives 0 without 0/0.
  law.eta_n = std::sqrt(2.0 * m.kn * ln_e * ln_e / (PI * PI + ln_e * ln_e));
  law.tau_c = std::sqrt((PI * PI + ln_e * ln_e) / (2.0 * m.kn));
  // beta = exp(-q eta_t tau_c): the sticking tangential mode decays at rate q eta_t.
  law.eta_t = -std::log(m.beta) / (q * law.tau_c);
  // Tangential oscillation of a sticking contact has the normal one's frequency:
  // 2q kt - q^2 eta_t^2 = 2 kn - eta_n^2.
  law.kt = (2.0 * m.kn - law.eta_n * law.eta_n + q * q * law.eta_t * law.eta_t) / (2.0 * q);
  law.tau_w = PI / std::sqrt(m.kn - 0.25 * law.eta_n * law.eta_n);
  law.e_w = std::exp(-0.5 * law.eta_n * law.tau_w);
  return law;
}

// The mass scale of a contact (docs/model.md section 2): 2M = 2 m_i m_j/(m_i + m_j) for two
// mobile disks; against the boundary (a bump or a wall), the mobile disk's own mass.
inline double pair_mass_scale(double mi, double mj)
{
  return 2.0 * mi * mj / (mi + mj);
}

inline double boundary_mass_scale(double mi)
{
  return mi;
}

// A run that starts with a pair overlapping by more than this fraction of the smaller radius
// was, most likely, placed so (a lattice finer than the diameters, atoms created on others):
// the hosts say so at a run's setup. Released, the spring drives the pair apart at up to
// release_speed: at k_n = 2e5 an overlap of 0.06 gives 38, where a flow of unit spheres under
// unit gravity moves at about 1.
constexpr double DEEP_OVERLAP_FRACTION = 0.1;

inline bool deep_overlap(double delta, double radius_i, double radius_j)
{
  return delta > DEEP_OVERLAP_FRACTION * (radius_i < radius_j ? radius_i : radius_j);
}

// The speed at which an overlap delta, released, drives its contact apart (undamped): delta
// times the normal frequency, sqrt(2 k_n) between two particles (the relative motion feels 2M
// (1/m_i + 1/m_j) = 2 of the spring), sqrt(k_n) against the boundary.
inline double release_speed(const Law &law, double delta, bool boundary)
{
  return delta * std::sqrt((boundary ? 1.0 : 2.0) * law.material.kn);
}

// Relative motion at one contact.
struct Kinematics {
  double nx, ny;   // unit normal, from partner to i
  double delta;    // overlap
  double vn, vt;   // normal and tangential relative velocity
};

// Disk i against disk j (or a flat wall: radius_j = 0, omega_j = 0, v_j = wall velocity).
// dx, dy = r_i - r_j for a disk, or the wall-to-centre vector along the wall normal;
// dist = |(dx, dy)| > 0; inv_dist = 1.0 / dist, the quotient as rounded (a host that has it
// already, as LIGGGHTS, saves a division); contact_distance = radius_i + radius_j.
inline Kinematics kinematics(double dx, double dy, double dist, double inv_dist,
                             double contact_distance, double dvx, double dvy, double lever_spin)
{
  Kinematics k;
  k.nx = dx * inv_dist;
  k.ny = dy * inv_dist;
  k.delta = contact_distance - dist;
  k.vn = k.nx * dvx + k.ny * dvy;
  // v_ij = dv + n x (r_i w_i + r_j w_j) z; its t component is t.dv - lever_spin.
  k.vt = -k.ny * dvx + k.nx * dvy - lever_spin;
  return k;
}

inline Kinematics kinematics(double dx, double dy, double dist, double contact_distance,
                             double dvx, double dvy, double lever_spin)
{
  return kinematics(dx, dy, dist, 1.0 / dist, contact_distance, dvx, dvy, lever_spin);
}

struct Force {
  double fn;      // along n, positive = repulsive
  double ft;      // along t
  bool sliding;   // the Coulomb cap was active
};

enum class Integrator {
  VelocityVerlet,   // LAMMPS's: the force at a step sees the half-step velocity
  AdamsBashforth2   // the paper's: AB2 for velocities, trapezoidal rule for positions
};

// Advances a contact's tangential displacement u_t (the integral of v_t over the contact) by one
// step of dt, with the rule the integrator uses for positions, so that u_t is as accurate as they
// are (docs/model.md section 4):
// - velocity Verlet evaluates forces with the half-step velocity: u_t += v_t dt is the midpoint
//   rule;
// - Adams-Bashforth 2 evaluates them with the step's own velocity and moves positions by the
//   trapezoidal rule: u_t += dt/2 (v_t(t - dt) + v_t(t)). v_t(t - dt) is the contact's v_t at its
//   previous force evaluation, kept in *vt_previous. A new contact's slot holds 0: v_t counts as
//   zero before the contact, so its first step adds v_t dt/2, v_t times the mean time that a
//   contact begun within the step has been on (v_t dt would count the whole step: a bias of
//   first order in dt).
// *vt_previous, where given, is set to v_t under either integrator (also when dt = 0), so that
// it is current when a later run switches to Adams-Bashforth 2.
inline void advance_tangential_displacement(Integrator integrator, double vt, double dt,
                                            double *ut, double *vt_previous)
{
  if (integrator == Integrator::AdamsBashforth2)
    *ut += 0.5 * dt * (*vt_previous + vt);
  else
    *ut += vt * dt;
  if (vt_previous) *vt_previous = vt;
}

// The normal force of a contact in either dimension (Kinematics or Kinematics3): spring and
// dashpot on the overlap, along n, positive = repulsive; force_scale as in contact_force.
template <class ContactKinematics>
inline double normal_force(const Law &law, double force_scale, const ContactKinematics &k)
{
  const double fn = force_scale * (law.material.kn * k.delta - law.eta_n * k.vn);
  return law.options.limit_damping && fn < 0.0 ? 0.0 : fn;
}

// The tangential part of contact_force for a contact whose normal force is fn (it sets the
// Coulomb cap): ut advanced, then the force capped. For a host that computes the two parts in
// separate places (LIGGGHTS's normal and tangential models); the result's fn is fn.
inline Force tangential_force(const Law &law, double force_scale, const Kinematics &k, double fn,
                              double *ut, double dt_history, Integrator integrator,
                              double *vt_previous)
{
  Force f;
  f.fn = fn;
  f.sliding = false;
  advance_tangential_displacement(integrator, k.vt, dt_history, ut, vt_previous);
  const double trial = -force_scale * (law.kt * (*ut) + law.eta_t * k.vt);
  const double cap = law.material.mu * std::fabs(f.fn);
  if (std::fabs(trial) > cap) {
    f.sliding = true;
    f.ft = std::copysign(cap, trial);
    if (law.options.coulomb_cutback && law.kt > 0.0)
      *ut = -(f.ft / force_scale + law.eta_t * k.vt) / law.kt;
  } else {
    f.ft = trial;
  }
  return f;
}

// Force of one contact. force_scale turns the law's accelerations into forces: the contact's
// mass scale, in units where force = mass x acceleration (in LAMMPS's, divided by ftm2v).
// ut is the tangential displacement of this contact (nullptr when mu = 0: no friction, no
// history). It is advanced first over dt_history (0 when forces are only re-evaluated, as in
// LAMMPS's setup) by the integrator's rule; Adams-Bashforth 2 needs vt_previous (see
// advance_tangential_displacement), velocity Verlet none.
inline Force contact_force(const Law &law, double force_scale, const Kinematics &k, double *ut,
                           double dt_history,
                           Integrator integrator = Integrator::VelocityVerlet,
                           double *vt_previous = nullptr)
{
  const double fn = normal_force(law, force_scale, k);
  if (!ut) return {fn, 0.0, false};
  return tangential_force(law, force_scale, k, fn, ut, dt_history, integrator, vt_previous);
}

// The contact's force on i in Cartesian components (fn along n, ft along t), and the torque
// about i's centre for a lever arm `radius` (the partner's torque uses its own radius: both
// turn the same way, docs/model.md section 2).
struct Cartesian {
  double fx, fy;
};

inline Cartesian cartesian(const Kinematics &k, const Force &f)
{
  return {f.fn * k.nx - f.ft * k.ny, f.fn * k.ny + f.ft * k.nx};
}

inline double torque(const Force &f, double radius)
{
  return -radius * f.ft;
}

// ---------------------------------------------------------------------------------------------
// The law in 3D (spheres; docs/model.md section 3.2). The same conventions with vectors: n from
// j to i, v_ij = dv + n x (r_i w_i + r_j w_j) (the full radii as lever arms), v_n = n.v_ij, the
// vector v_t = v_ij - v_n n, and u_t a vector in the tangent plane. The force on i is
// fn n + F_t, the torque on i is (-r_i n) x F_t and on j (-r_j n) x F_t (the 2D torque -r ft
// about z is this with F_t = ft t, t = z x n). The 2D functions above are not used here.

// Relative motion at one contact in 3D.
struct Kinematics3 {
  double n[3];     // unit normal, from partner to i
  double delta;    // overlap
  double vn;       // normal relative velocity
  double vt[3];    // tangential relative velocity (in the plane normal to n)
};

// Sphere i against sphere j (or a flat wall: radius_j = 0, omega_j = 0, v_j = wall velocity).
// d = r_i - r_j for a sphere, or the wall-to-centre vector along the wall normal; dist = |d| > 0;
// inv_dist = 1.0 / dist, as in 2D; contact_distance = radius_i + radius_j; dv = v_i - v_j;
// lever = radius_i w_i + radius_j w_j.
inline Kinematics3 kinematics3(const double d[3], double dist, double inv_dist,
                               double contact_distance, const double dv[3], const double lever[3])
{
  Kinematics3 k;
  for (int c = 0; c < 3; c++) k.n[c] = d[c] * inv_dist;
  k.delta = contact_distance - dist;
  const double vij[3] = {dv[0] + k.n[1] * lever[2] - k.n[2] * lever[1],
                         dv[1] + k.n[2] * lever[0] - k.n[0] * lever[2],
                         dv[2] + k.n[0] * lever[1] - k.n[1] * lever[0]};
  k.vn = k.n[0] * vij[0] + k.n[1] * vij[1] + k.n[2] * vij[2];
  for (int c = 0; c < 3; c++) k.vt[c] = vij[c] - k.vn * k.n[c];
  return k;
}

inline Kinematics3 kinematics3(const double d[3], double dist, double contact_distance,
                               const double dv[3], const double lever[3])
{
  return kinematics3(d, dist, 1.0 / dist, contact_distance, dv, lever);
}

// Keeps a contact's u_t in the tangent plane as the contact turns (Luding, Granular Matter 10,
// 235 (2008), eq. 17; LAMMPS GRANULAR's tangential linear_history): the part along the current
// normal is taken out and what is left rescaled to the old magnitude. A u_t along n (no part
// left in the plane) becomes zero.
inline void rotate_into_tangent_plane(const double n[3], double ut[3])
{
  const double before = ut[0] * ut[0] + ut[1] * ut[1] + ut[2] * ut[2];
  if (before == 0.0) return;
  const double along = ut[0] * n[0] + ut[1] * n[1] + ut[2] * n[2];
  for (int c = 0; c < 3; c++) ut[c] -= along * n[c];
  const double after = ut[0] * ut[0] + ut[1] * ut[1] + ut[2] * ut[2];
  const double rescale = after > 0.0 ? std::sqrt(before / after) : 0.0;
  for (int c = 0; c < 3; c++) ut[c] *= rescale;
}

// Whether sqrt(square) <= cap (a cap >= 0), without the square root (whose latency a sticking
// contact's force waited for): square <= cap^2, the product rounded. Exact wherever cap^2 is a normal
// number: the rounded square root of the rounded cap^2 is cap again (cap^2's relative error
// of at most u = 2^-53 moves its root by at most u/2, less than half of cap's ulp), and
// rounding and the square root keep order. false where cap^2 underflows or overflows, or is
// NaN: the caller then compares sqrt(square) with cap, so the outcome is that comparison's in
// every case, to the bit.
inline bool certainly_within(double square, double cap)
{
  const double cap_squared = cap * cap;
  return cap_squared >= std::numeric_limits<double>::min() &&
         cap_squared <= std::numeric_limits<double>::max() && square <= cap_squared;
}

struct Force3 {
  double fn;      // along n, positive = repulsive
  double ft[3];   // tangential force on i
  bool sliding;   // the Coulomb cap was active
};

// The tangential part of contact_force3 for a contact whose normal force is fn, as
// tangential_force in 2D; the result's fn is fn.
inline Force3 tangential_force3(const Law &law, double force_scale, const Kinematics3 &k,
                                double fn, double *ut, double dt_history)
{
  Force3 f;
  f.fn = fn;
  f.sliding = false;
  if (dt_history > 0.0) {
    rotate_into_tangent_plane(k.n, ut);
    for (int c = 0; c < 3; c++) ut[c] += k.vt[c] * dt_history;
  }
  double trial[3];
  for (int c = 0; c < 3; c++) trial[c] = -force_scale * (law.kt * ut[c] + law.eta_t * k.vt[c]);
  const double square = trial[0] * trial[0] + trial[1] * trial[1] + trial[2] * trial[2];
  const double cap = law.material.mu * std::fabs(f.fn);
  if (!certainly_within(square, cap)) {
    const double magnitude = std::sqrt(square);
    if (magnitude > cap) {
      f.sliding = true;
      const double shrink = cap / magnitude;
      for (int c = 0; c < 3; c++) f.ft[c] = shrink * trial[c];
      if (law.options.coulomb_cutback && law.kt > 0.0)
        for (int c = 0; c < 3; c++)
          ut[c] = -(f.ft[c] / force_scale + law.eta_t * k.vt[c]) / law.kt;
      return f;
    }
  }
  for (int c = 0; c < 3; c++) f.ft[c] = trial[c];
  return f;
}

// Force of one contact in 3D, as contact_force in 2D: ut (3 values; nullptr when mu = 0) is
// first turned into the current tangent plane and advanced by u_t += v_t dt (velocity Verlet's
// midpoint rule; Adams-Bashforth 2 is a 2D integrator here), both only when dt_history > 0 (a
// re-evaluation, as in LAMMPS's setup, leaves u_t as it is, so that it gives the last step's
// force again). The trial force -scale (k_t u_t + eta_t v_t) is capped at mu |fn| in
// magnitude; with coulomb_cutback u_t is then set so that the trial force is the capped one.
inline Force3 contact_force3(const Law &law, double force_scale, const Kinematics3 &k, double *ut,
                             double dt_history)
{
  const double fn = normal_force(law, force_scale, k);
  if (!ut) return {fn, {0.0, 0.0, 0.0}, false};
  return tangential_force3(law, force_scale, k, fn, ut, dt_history);
}

// The contact's force on i in Cartesian components.
inline void cartesian3(const Kinematics3 &k, const Force3 &f, double out[3])
{
  for (int c = 0; c < 3; c++) out[c] = f.fn * k.n[c] + f.ft[c];
}

// The torque (-radius n) x F_t about the centre of i (radius_i) or of j (radius_j): both turn
// the same way, as in 2D.
inline void torque3(const Kinematics3 &k, const Force3 &f, double radius, double out[3])
{
  out[0] = -radius * (k.n[1] * f.ft[2] - k.n[2] * f.ft[1]);
  out[1] = -radius * (k.n[2] * f.ft[0] - k.n[0] * f.ft[2]);
  out[2] = -radius * (k.n[0] * f.ft[1] - k.n[1] * f.ft[0]);
}

// ---------------------------------------------------------------------------------------------
// Either dimension, for the loops written once for both (Dim<2> or Dim<3> chooses): the functions
// above, from the same 3-vectors, and one contact's force and torques.
template <int DIM> using Dim = std::integral_constant<int, DIM>;

// kinematics from 3-vectors: in 2D only the x and y of d and dv and the z of lever are read.
inline Kinematics kinematics(Dim<2>, const double d[3], double dist, double contact_distance,
                             const double dv[3], const double lever[3])
{
  return kinematics(d[0], d[1], dist, contact_distance, dv[0], dv[1], lever[2]);
}

inline Kinematics3 kinematics(Dim<3>, const double d[3], double dist, double contact_distance,
                              const double dv[3], const double lever[3])
{
  return kinematics3(d, dist, contact_distance, dv, lever);
}

// The same from 1.0 / dist where the host has it (inv_dist).
inline Kinematics kinematics(Dim<2>, const double d[3], double dist, double inv_dist,
                             double contact_distance, const double dv[3], const double lever[3])
{
  return kinematics(d[0], d[1], dist, inv_dist, contact_distance, dv[0], dv[1], lever[2]);
}

inline Kinematics3 kinematics(Dim<3>, const double d[3], double dist, double inv_dist,
                              double contact_distance, const double dv[3], const double lever[3])
{
  return kinematics3(d, dist, inv_dist, contact_distance, dv, lever);
}

// contact_force of the 3D kinematics: contact_force3.
inline Force3 contact_force(const Law &law, double force_scale, const Kinematics3 &k, double *ut,
                            double dt_history)
{
  return contact_force3(law, force_scale, k, ut, dt_history);
}

// force_and_torques is called once a contact from the hosts' loops, and is inlined there: GCC 12
// left the 3D one a call once the pair style's work of a contact became a function of its own
// (9 % more instructions in its loop on LAMMPS's bench/in.chute).
#if defined(__GNUC__)
#define MN_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define MN_ALWAYS_INLINE inline
#endif

// A contact's force f on i into force (Cartesian; 0 along z in 2D), and its torque added to
// torque_i (lever arm radius_i) and, where torque_j is given, to torque_j (radius_j).
MN_ALWAYS_INLINE void apply_force(const Kinematics &k, const Force &f, double force[3],
                                  double radius_i, double *torque_i, double radius_j,
                                  double *torque_j)
{
  const Cartesian fxy = cartesian(k, f);
  force[0] = fxy.fx;
  force[1] = fxy.fy;
  force[2] = 0.0;
  torque_i[2] += torque(f, radius_i);
  if (torque_j) torque_j[2] += torque(f, radius_j);
}

MN_ALWAYS_INLINE void apply_force(const Kinematics3 &k, const Force3 &f, double force[3],
                                  double radius_i, double *torque_i, double radius_j,
                                  double *torque_j)
{
  cartesian3(k, f, force);
  double t[3];
  torque3(k, f, radius_i, t);
  for (int c = 0; c < 3; c++) torque_i[c] += t[c];
  if (!torque_j) return;
  torque3(k, f, radius_j, t);
  for (int c = 0; c < 3; c++) torque_j[c] += t[c];
}

// The contact's force (contact_force), applied so.
MN_ALWAYS_INLINE void force_and_torques(const Law &law, double force_scale, const Kinematics &k, double *ut,
                              double dt_history, Integrator integrator, double *vt_previous,
                              double force[3], double radius_i, double *torque_i,
                              double radius_j, double *torque_j)
{
  const Force f = contact_force(law, force_scale, k, ut, dt_history, integrator, vt_previous);
  apply_force(k, f, force, radius_i, torque_i, radius_j, torque_j);
}

// The same in 3D, where the integrator is velocity Verlet (Adams-Bashforth 2 is a 2D integrator:
// vt_previous is nullptr).
MN_ALWAYS_INLINE void force_and_torques(const Law &law, double force_scale, const Kinematics3 &k, double *ut,
                              double dt_history, Integrator, double *, double force[3],
                              double radius_i, double *torque_i, double radius_j,
                              double *torque_j)
{
  const Force3 f = contact_force3(law, force_scale, k, ut, dt_history);
  apply_force(k, f, force, radius_i, torque_i, radius_j, torque_j);
}

// A particle of the given radius against a wall, whose own radius and spin are 0 (a plane, a
// region's face): the contact's kinematics in dimension DIM from d (wall to centre, along the
// wall's normal), dist = |d|, dv = v_i - the wall's velocity and the particle's spin omega.
template <int DIM>
inline typename std::conditional<DIM == 3, Kinematics3, Kinematics>::type
wall_kinematics(const double d[3], double dist, double radius, const double dv[3],
                const double omega[3])
{
  const double lever[3] = {radius * omega[0], radius * omega[1], radius * omega[2]};
  return kinematics(Dim<DIM>(), d, dist, radius, dv, lever);
}

// That contact's force added to the particle's force and, with the opposite sign, to on_wall
// (DIM components each), its torque to the particle's torque; scale as for force_and_torques.
template <int DIM, class K>
inline void add_wall_contact(const Law &law, double scale, const K &kin, double *ut,
                             double dt_history, Integrator integrator, double *vt_previous,
                             double radius, double *force, double *torque, double *on_wall)
{
  double f[3];
  force_and_torques(law, scale, kin, ut, dt_history, integrator, vt_previous, f, radius, torque,
                    0.0, nullptr);
  for (int c = 0; c < DIM; c++) {
    force[c] += f[c];
    on_wall[c] -= f[c];
  }
}

}    // namespace mn

#endif
