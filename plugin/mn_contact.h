// The Mitarai-Nakanishi 2D linear spring-dashpot contact law (PRE 67, 021301 (2003)),
// free of LAMMPS so that the pair style, the wall fix and the unit tests share one copy.
//
// Conventions (docs/model.md sections 2-3): for a contact of disk i with partner j, n points from j
// to i, t = (-n_y, n_x), delta > 0 is the overlap, v_n = n.v_ij and v_t = t.v_ij with the full
// radii as lever arms. The force on i is fn*n + ft*t and the torque on i is -radius_i*ft.
// "mass_scale" is 2M = 2 m_i m_j/(m_i+m_j) for two mobile disks and m_i against the boundary.
#ifndef MN_CONTACT_H
#define MN_CONTACT_H

#include <algorithm>
#include <cmath>
#include <complex>

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

// The coefficients derived from a Material (docs/model.md section 3).
struct Law {
  double kn, eta_n, kt, eta_t, mu;
  double tau_c;   // duration of a binary normal collision
  double tau_w;   // duration of a normal collision with the boundary (mass scale m_i)
  double e_w;     // restitution of a normal collision with the boundary
  Options options;
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

inline Law derive(const Material &m, const Options &options = Options())
{
  Law law;
  const double ln_e = std::log(m.e);
  law.kn = m.kn;
  law.mu = m.mu;
  law.options = options;
  // eta_n = sqrt(2 kn / ((pi/ln e)^2 + 1)), written so that e = 1 gives 0 without 0/0.
  law.eta_n = std::sqrt(2.0 * m.kn * ln_e * ln_e / (PI * PI + ln_e * ln_e));
  law.tau_c = std::sqrt((PI * PI + ln_e * ln_e) / (2.0 * m.kn));
  law.eta_t = -std::log(m.beta) / (3.0 * law.tau_c);
  // Tangential oscillation of a sticking contact has the normal one's frequency.
  law.kt = (2.0 * m.kn - law.eta_n * law.eta_n + 9.0 * law.eta_t * law.eta_t) / 6.0;
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

// Relative motion at one contact.
struct Kinematics {
  double nx, ny;   // unit normal, from partner to i
  double delta;    // overlap
  double vn, vt;   // normal and tangential relative velocity
};

// Disk i against disk j (or a flat wall: radius_j = 0, omega_j = 0, v_j = wall velocity).
// dx, dy = r_i - r_j for a disk, or the wall-to-centre vector along the wall normal;
// dist = |(dx, dy)| > 0; contact_distance = radius_i + radius_j.
inline Kinematics kinematics(double dx, double dy, double dist, double contact_distance,
                             double dvx, double dvy, double lever_spin)
{
  Kinematics k;
  const double inv = 1.0 / dist;
  k.nx = dx * inv;
  k.ny = dy * inv;
  k.delta = contact_distance - dist;
  k.vn = k.nx * dvx + k.ny * dvy;
  // v_ij = dv + n x (r_i w_i + r_j w_j) z; its t component is t.dv - lever_spin.
  k.vt = -k.ny * dvx + k.nx * dvy - lever_spin;
  return k;
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

// Force of one contact. ut is the tangential displacement of this contact (nullptr when
// mu = 0: no friction, no history). It is advanced first over dt_history (0 when forces are only
// re-evaluated, as in LAMMPS's setup) by the integrator's rule; Adams-Bashforth 2 needs
// vt_previous (see advance_tangential_displacement), velocity Verlet none.
inline Force contact_force(const Law &law, double mass_scale, const Kinematics &k, double *ut,
                           double dt_history,
                           Integrator integrator = Integrator::VelocityVerlet,
                           double *vt_previous = nullptr)
{
  Force f;
  f.fn = mass_scale * (law.kn * k.delta - law.eta_n * k.vn);
  if (law.options.limit_damping && f.fn < 0.0) f.fn = 0.0;
  f.ft = 0.0;
  f.sliding = false;
  if (!ut) return f;

  advance_tangential_displacement(integrator, k.vt, dt_history, ut, vt_previous);
  const double trial = -mass_scale * (law.kt * (*ut) + law.eta_t * k.vt);
  const double cap = law.mu * std::fabs(f.fn);
  if (std::fabs(trial) > cap) {
    f.sliding = true;
    f.ft = std::copysign(cap, trial);
    if (law.options.coulomb_cutback && law.kt > 0.0)
      *ut = -(f.ft / mass_scale + law.eta_t * k.vt) / law.kt;
  } else {
    f.ft = trial;
  }
  return f;
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

// ---------------------------------------------------------------------------------------
// Numerical stability of a contact under a time integrator.
//
// Each contact mode is a damped oscillator x'' = -w2 x - g x'. The integrators are linear on
// it, so one step is a 3x3 matrix on the integrator's state; the step is stable while that
// matrix's spectral radius is at most 1.

// The paper's scheme for one coordinate (docs/model.md section 4), used by fix nve/ab2 and by
// the stability analysis alike: the new velocity by Adams-Bashforth 2 from this step's and
// the previous step's accelerations, the new position by the trapezoidal rule.
inline double ab2_velocity(double v, double a, double a_previous, double dt)
{
  return v + dt * (1.5 * a - 0.5 * a_previous);
}

inline double trapezoidal_position(double x, double v, double v_new, double dt)
{
  return x + 0.5 * dt * (v + v_new);
}

namespace detail {

// One step of the integrator on the oscillator, state s.
inline void step(Integrator integrator, double w2, double g, double dt, const double s[3],
                 double out[3])
{
  if (integrator == Integrator::VelocityVerlet) {
    // s = (x, v, a): a is the acceleration computed at the end of the previous step.
    const double vh = s[1] + 0.5 * dt * s[2];
    const double x = s[0] + dt * vh;
    const double a = -w2 * x - g * vh;
    out[0] = x;
    out[1] = vh + 0.5 * dt * a;
    out[2] = a;
  } else {
    // s = (x, v, a_prev); the acceleration at this step follows from (x, v).
    const double a = -w2 * s[0] - g * s[1];
    const double v = ab2_velocity(s[1], a, s[2], dt);
    out[0] = trapezoidal_position(s[0], s[1], v, dt);
    out[1] = v;
    out[2] = a;
  }
}

inline double spectral_radius(Integrator integrator, double w2, double g, double dt)
{
  double m[3][3];
  for (int c = 0; c < 3; c++) {
    double unit[3] = {0.0, 0.0, 0.0}, col[3];
    unit[c] = 1.0;
    step(integrator, w2, g, dt, unit, col);
    for (int r = 0; r < 3; r++) m[r][c] = col[r];
  }
  // Characteristic polynomial z^3 + a z^2 + b z + c, roots by Durand-Kerner.
  const double a = -(m[0][0] + m[1][1] + m[2][2]);
  const double b = m[0][0] * m[1][1] - m[0][1] * m[1][0] + m[0][0] * m[2][2] -
      m[0][2] * m[2][0] + m[1][1] * m[2][2] - m[1][2] * m[2][1];
  const double c = -(m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]));
  using cplx = std::complex<double>;
  auto p = [&](cplx z) { return ((z + a) * z + b) * z + c; };
  cplx root[3] = {cplx(1.0, 0.0), cplx(0.4, 0.9), cplx(-0.65, 0.72)};
  for (int iter = 0; iter < 500; iter++)
    for (int i = 0; i < 3; i++) {
      cplx denom(1.0, 0.0);
      for (int j = 0; j < 3; j++)
        if (j != i) denom *= root[i] - root[j];
      if (std::abs(denom) > 0.0) root[i] -= p(root[i]) / denom;
    }
  return std::max({std::abs(root[0]), std::abs(root[1]), std::abs(root[2])});
}

}    // namespace detail

// Largest growth of an undamped mode's amplitude over one contact (half an oscillation) that
// the step limit accepts; see max_stable_dt.
constexpr double UNDAMPED_GROWTH_PER_CONTACT = 1e-3;

// Largest dt for which the integrator is stable on x'' = -w2 x - g x' (0 if none).
// A damped mode (g > 0) has a strict limit: the spectral radius of the step reaches 1. An
// undamped mode (g = 0: e = 1 or beta = 1) sits on the unit circle under velocity Verlet, but
// Adams-Bashforth 2 amplifies it a little at every step (by about (w dt)^4/4), so it has no
// strict limit at all: there the limit is the step at which a contact (pi/w long) grows by
// UNDAMPED_GROWTH_PER_CONTACT, and lasting contacts still gain energy (the styles warn).
inline double max_stable_dt(Integrator integrator, double w2, double g)
{
  const double tolerance = 1e-9;    // rounding of the eigenvalues
  const bool weakly_unstable = g == 0.0 && integrator == Integrator::AdamsBashforth2;
  auto stable = [&](double dt) {
    const double radius = detail::spectral_radius(integrator, w2, g, dt);
    if (!weakly_unstable) return radius <= 1.0 + tolerance;
    const double steps = std::max(1.0, PI / (std::sqrt(w2) * dt));
    return std::pow(radius, steps) <= 1.0 + UNDAMPED_GROWTH_PER_CONTACT;
  };
  double lo = 0.0, hi = 1.0 / std::sqrt(w2);
  while (stable(hi) && hi < 1e6 / std::sqrt(w2)) {
    lo = hi;
    hi *= 2.0;
  }
  if (lo == 0.0 && !stable(1e-6 * hi)) return 0.0;
  for (int iter = 0; iter < 60; iter++) {
    const double mid = 0.5 * (lo + hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

// True if the integrator slowly amplifies one of the law's modes (AB2 with e = 1, or with
// beta = 1 and friction): fine for collisions, not for contacts that last.
inline bool amplifies_undamped_mode(const Law &law, Integrator integrator)
{
  return integrator == Integrator::AdamsBashforth2 &&
      (law.eta_n == 0.0 || (law.mu > 0.0 && law.eta_t == 0.0));
}

// The modes of a contact whose stability bounds the step: normal and (if mu > 0) sticking
// tangential motion, for a pair of mobile disks (mass scale 2M) and against the boundary (mass
// scale m_i). Uses I = m sigma^2/8 (disks), for which the tangential equation does not depend
// on masses.
enum class Mode { NormalPair, NormalBoundary, TangentialPair, TangentialBoundary };

inline const char *mode_name(Mode mode)
{
  switch (mode) {
    case Mode::NormalPair: return "the normal mode of two disks";
    case Mode::NormalBoundary: return "the normal mode against the boundary";
    case Mode::TangentialPair: return "the tangential (sticking) mode of two disks";
    case Mode::TangentialBoundary: return "the tangential (sticking) mode against the boundary";
  }
  return "";
}

// The largest stable step and the mode that sets it (the stiffest one under the integrator).
struct StabilityLimit {
  double dt;
  Mode mode;
};

inline StabilityLimit stability_limit(const Law &law, Integrator integrator)
{
  StabilityLimit limit{max_stable_dt(integrator, 2.0 * law.kn, 2.0 * law.eta_n),
                       Mode::NormalPair};
  auto consider = [&](double w2, double g, Mode mode) {
    const double dt = max_stable_dt(integrator, w2, g);
    if (dt < limit.dt) limit = {dt, mode};
  };
  consider(law.kn, law.eta_n, Mode::NormalBoundary);
  if (law.mu > 0.0) {
    consider(6.0 * law.kt, 6.0 * law.eta_t, Mode::TangentialPair);
    consider(3.0 * law.kt, 3.0 * law.eta_t, Mode::TangentialBoundary);
  }
  return limit;
}

inline double max_stable_dt(const Law &law, Integrator integrator)
{
  return stability_limit(law, integrator).dt;
}

}    // namespace mn

#endif
