// The time integrators on one contact (Mitarai & Nakanishi's law, mn_contact.h): the paper's
// step for one coordinate, and the largest step each integrator takes stably on the law's
// contact modes. Free of LAMMPS, like the law.
//
// Each contact mode is a damped oscillator x'' = -w2 x - g x'. The integrators are linear on
// it, so one step is a 3x3 matrix on the integrator's state; the step is stable while that
// matrix's spectral radius is at most 1.
#ifndef MN_INTEGRATION_H
#define MN_INTEGRATION_H

#include "mn_contact.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <tuple>

namespace mn {

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
namespace detail {

inline double bisect_stable_dt(Integrator integrator, double w2, double g)
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

}    // namespace detail

// ... computed once per process for each (integrator, w2, g) and kept: the styles ask for it at
// every run's init (their step check, the published v_mn_dt_max_*), a deck split into many
// short runs asks again and again, and the bisections (the spectral radii of their steps)
// cost ~21 ms of CPU a run (docs/performance.md).
inline double max_stable_dt(Integrator integrator, double w2, double g)
{
  static std::map<std::tuple<Integrator, double, double>, double> known;
  const auto key = std::make_tuple(integrator, w2, g);
  const auto found = known.find(key);
  if (found != known.end()) return found->second;
  const double dt = detail::bisect_stable_dt(integrator, w2, g);
  known.emplace(key, dt);
  return dt;
}

// True if the integrator slowly amplifies one of the law's modes (AB2 with e = 1, or with
// beta = 1 and friction): fine for collisions, not for contacts that last.
inline bool amplifies_undamped_mode(const Law &law, Integrator integrator)
{
  return integrator == Integrator::AdamsBashforth2 &&
      (law.eta_n == 0.0 || (law.material.mu > 0.0 && law.eta_t == 0.0));
}

// The modes of a contact whose stability bounds the step: normal and (if mu > 0) sticking
// tangential motion, for a pair of mobile disks (mass scale 2M) and against the boundary (mass
// scale m_i), for particles of the law's shape q, for which the tangential equation does not
// depend on masses (docs/model.md section 3.1).
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
  StabilityLimit limit{max_stable_dt(integrator, 2.0 * law.material.kn, 2.0 * law.eta_n),
                       Mode::NormalPair};
  auto consider = [&](double w2, double g, Mode mode) {
    const double dt = max_stable_dt(integrator, w2, g);
    if (dt < limit.dt) limit = {dt, mode};
  };
  consider(law.material.kn, law.eta_n, Mode::NormalBoundary);
  if (law.material.mu > 0.0) {
    consider(2.0 * law.q * law.kt, 2.0 * law.q * law.eta_t, Mode::TangentialPair);
    consider(law.q * law.kt, law.q * law.eta_t, Mode::TangentialBoundary);
  }
  return limit;
}

inline double max_stable_dt(const Law &law, Integrator integrator)
{
  return stability_limit(law, integrator).dt;
}

}    // namespace mn

#endif
