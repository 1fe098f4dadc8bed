// Instantaneous (hard) binary collisions of disks, for the event-driven engine
// (plugin/event_driven) and the tests: the paper's rule and the soft law's own hard limit.
// Free of LAMMPS, like the law (mn_contact.h), whose conventions and coefficients it uses:
// n points from the partner to disk i, t = (-n_y, n_x), v_n = n.v_ij and v_t = t.v_ij with the
// full radii as lever arms (mn::kinematics); a collision's impulse on i is J_n n + J_t t, on the
// partner -J_n n - J_t t; a tangential impulse turns both disks the same way, as the law's torque
// does (mn::torque: d omega = -radius J_t / I).
//
// Two rules (docs/model.md section 8):
// (a) the paper's (section II.A, eqs. (2)-(5)): v_n' = -e v_n; a sticking collision has
//     v_t' = -beta v_t; the tangential impulse is capped at mu |J_n|.
// (b) the soft law's binary collision with the normal held fixed and no gravity, integrated with
//     the law's own forces (literal or cut-back u_t, as the law's options say). With e and beta
//     fixed all the law's rates scale with sqrt(k_n): the outcome is the limit k_n -> infinity of
//     an isolated soft collision, a function of the impact's v_t/v_n alone (and e, beta, mu, the
//     u_t reading).
// Against the boundary (a bump, a flat wall: a partner that does not move) the reduced mass M is
// the disk's own mass m_i and q its own boundary_q; under rule (b) the law's boundary mass scale
// gives e_w, not e.
#ifndef MN_COLLISION_H
#define MN_COLLISION_H

#include "mn_contact.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mn {

// The relative velocity of the contact point (v_n < 0: approaching).
struct ContactVelocity {
  double vn, vt;
};

// The impulse on disk i along n and t.
struct Impulse {
  double jn, jt;
};

// The parameters of rule (a) for one kind of collision.
struct PaperRule {
  double e;      // normal restitution, in (0,1]
  double beta;   // tangential restitution of a sticking collision, in [-1,1]
  double mu;     // Coulomb friction coefficient, >= 0
};

// nullptr if the rule is valid, else what is wrong with it (which value: the caller names the
// input it came from).
inline const char *paper_rule_error(const PaperRule &rule)
{
  if (!(rule.e > 0.0 && rule.e <= 1.0)) return "e must lie in (0,1]";
  if (!(rule.beta >= -1.0 && rule.beta <= 1.0)) return "beta must lie in [-1,1]";
  if (!(rule.mu >= 0.0) || !std::isfinite(rule.mu)) return "mu must be a finite number >= 0";
  return nullptr;
}

// Rule (a): the impulse on i for an impact `in` (v_n < 0) of a contact of reduced mass
// `reduced_mass` (M = m_i m_j/(m_i + m_j), or m_i against the boundary) and inertia shape q
// (pair_q or boundary_q; 3 for disks). A sticking collision's J_t* = -(1 + beta) M v_t / q gives
// v_t' = -beta v_t; the Coulomb cap keeps J_t*'s sign.
inline Impulse paper_impulse(const PaperRule &rule, double reduced_mass, double q,
                             ContactVelocity in)
{
  const double jn = -(1.0 + rule.e) * reduced_mass * in.vn;
  const double sticking = -(1.0 + rule.beta) * reduced_mass * in.vt / q;
  const double cap = rule.mu * std::fabs(jn);
  return {jn, std::fabs(sticking) <= cap ? sticking : std::copysign(cap, sticking)};
}

// The contact velocity after an impulse, and the impulse that takes `in` to `out`:
// dv_n = J_n / M, dv_t = q J_t / M (docs/model.md section 3.1: the tangential effective mass is
// M/q).
inline ContactVelocity after_impulse(ContactVelocity in, Impulse j, double reduced_mass, double q)
{
  return {in.vn + j.jn / reduced_mass, in.vt + q * j.jt / reduced_mass};
}

inline Impulse impulse_between(ContactVelocity in, ContactVelocity out, double reduced_mass,
                               double q)
{
  return {reduced_mass * (out.vn - in.vn), reduced_mass * (out.vt - in.vt) / q};
}

// A disk's motion and inertia, as a collision sees it.
struct DiskMotion {
  double vx, vy, omega;
  double mass, radius, inertia;
};

// The contact velocity of disk i against disk j (j == nullptr: a boundary element at rest with
// radius `partner_radius`, whose spin is 0) for the unit normal n = (nx, ny) from the partner
// to i: the law's kinematics at contact (overlap 0).
inline ContactVelocity contact_velocity(double nx, double ny, const DiskMotion &i,
                                        const DiskMotion *j)
{
  const double dvx = j ? i.vx - j->vx : i.vx, dvy = j ? i.vy - j->vy : i.vy;
  const double lever_spin = i.radius * i.omega + (j ? j->radius * j->omega : 0.0);
  const Kinematics k = kinematics(nx, ny, 1.0, 1.0, dvx, dvy, lever_spin);
  return {k.vn, k.vt};
}

// The reduced mass and q of a collision of i with j (nullptr: the boundary).
inline double collision_reduced_mass(const DiskMotion &i, const DiskMotion *j)
{
  return j ? i.mass * j->mass / (i.mass + j->mass) : i.mass;
}

inline double collision_q(const DiskMotion &i, const DiskMotion *j)
{
  return j ? pair_q(i.mass, i.radius, i.inertia, j->mass, j->radius, j->inertia)
           : boundary_q(i.mass, i.radius, i.inertia);
}

// Applies the impulse on i (and its opposite on j, where j is a disk) along n = (nx, ny).
// The spins change as the law's torque turns them: both by -radius J_t / I.
inline void apply_impulse(double nx, double ny, Impulse j_imp, DiskMotion &i, DiskMotion *j)
{
  const Force as_force{j_imp.jn, j_imp.jt, false};
  const Kinematics frame{nx, ny, 0.0, 0.0, 0.0};
  const Cartesian p = cartesian(frame, as_force);
  i.vx += p.fx / i.mass;
  i.vy += p.fy / i.mass;
  i.omega += torque(as_force, i.radius) / i.inertia;
  if (!j) return;
  j->vx -= p.fx / j->mass;
  j->vy -= p.fy / j->mass;
  j->omega += torque(as_force, j->radius) / j->inertia;
}

// ---------------------------------------------------------------------------------------------
// Rule (b): the soft law's binary collision with the normal held fixed and no gravity.

enum class Partner { Disk, Boundary };

// What one integrated collision gives: the contact velocity at its end (when the overlap is back
// to 0) and its duration.
struct SoftCollision {
  ContactVelocity out;
  double duration;
};

namespace detail {

// The contact's state: overlap, normal velocity, tangential displacement and velocity.
struct ContactState {
  double delta, vn, ut, vt;
};

// The law's accelerations in a frame where the reduced mass is 1: dv_n/dt = F_n / M and
// dv_t/dt = q F_t / M, with the law's mass scale 2M = 2 for two disks and m_i = M = 1 against
// the boundary.
struct SoftContactOde {
  const Law &law;
  double mass_scale;

  // The law's force at s; where `ut` is given, the law keeps u_t there as it does after a step
  // (unchanged for the literal reading, cut back while sliding for the cut-back one).
  Force force(const ContactState &s, double *ut) const
  {
    const Kinematics k{1.0, 0.0, s.delta, s.vn, s.vt};
    double unchanged = s.ut;
    return contact_force(law, mass_scale, k, law.material.mu > 0.0 ? (ut ? ut : &unchanged) : nullptr,
                         0.0);
  }

  ContactState rates(const ContactState &s) const
  {
    const Force f = force(s, nullptr);
    return {-s.vn, f.fn, s.vt, law.q * f.ft};
  }

  // One RK4 step of h from s; *slides is whether the law's Coulomb cap acts at its end.
  ContactState step(const ContactState &s, double h, bool *slides) const
  {
    auto add = [](const ContactState &a, const ContactState &d, double f) {
      return ContactState{a.delta + f * d.delta, a.vn + f * d.vn, a.ut + f * d.ut,
                          a.vt + f * d.vt};
    };
    const ContactState k1 = rates(s);
    const ContactState k2 = rates(add(s, k1, 0.5 * h));
    const ContactState k3 = rates(add(s, k2, 0.5 * h));
    const ContactState k4 = rates(add(s, k3, h));
    ContactState next{s.delta + h / 6 * (k1.delta + 2 * k2.delta + 2 * k3.delta + k4.delta),
                      s.vn + h / 6 * (k1.vn + 2 * k2.vn + 2 * k3.vn + k4.vn),
                      s.ut + h / 6 * (k1.ut + 2 * k2.ut + 2 * k3.ut + k4.ut),
                      s.vt + h / 6 * (k1.vt + 2 * k2.vt + 2 * k3.vt + k4.vt)};
    *slides = force(next, &next.ut).sliding;
    return next;
  }
};

}    // namespace detail

// The default resolution of soft_limit_collision: RK4 steps per normal contact duration. The
// force has kinks (the Coulomb cap switching on or off, |F_n| through 0) and, under the cut-back
// reading, a cap that closes to 0 when F_n changes sign; each is located and stepped to, so that
// RK4 keeps its order on the smooth pieces between them (tests/event_driven: the outcome's
// convergence in the number of steps).
constexpr int SOFT_LIMIT_STEPS = 512;

// Rule (b) for one impact (v_n < 0), integrated with RK4 through the contact (steps of
// duration/steps). Within a step where the overlap returns to 0, F_n changes sign, or the law's
// Coulomb cap switches on (and, for the literal u_t, off), the step is cut at that instant,
// found by bisection on the step's length to rounding. Under the cut-back reading u_t is kept
// as the law keeps it (cut back at the end of every step that slides); there the contact leaves
// the cap smoothly (the free trial force turns inside it), which needs no cut. The outcome does
// not depend on law.material.kn (only on e, beta, mu and the law's options).
inline SoftCollision soft_limit_collision(const Law &law, Partner partner, ContactVelocity in,
                                          int steps = SOFT_LIMIT_STEPS)
{
  const double mass_scale =
      partner == Partner::Disk ? pair_mass_scale(2.0, 2.0) : boundary_mass_scale(1.0);
  const detail::SoftContactOde ode{law, mass_scale};
  const bool cutback = law.options.coulomb_cutback;
  const double nominal = partner == Partner::Disk ? law.tau_c : law.tau_w;
  const double h = nominal / steps;
  auto sign = [](double x) { return (x > 0.0) - (x < 0.0); };
  detail::ContactState s{0.0, in.vn, 0.0, in.vt};
  double t = 0.0;
  bool sliding = false;   // the cap acted at the end of the last step
  int fn_sign = 0;        // the sign of F_n, once it has one
  // Whether a step from s to `e` (sliding at its end: `slides`) passed a switch.
  auto passed = [&](const detail::ContactState &e, bool slides) {
    if (!(e.delta > 0.0)) return true;
    const int fn = sign(ode.force(e, nullptr).fn);
    if (fn_sign != 0 && fn != 0 && fn != fn_sign) return true;
    return cutback ? !sliding && slides : slides != sliding;
  };
  // the normal motion is the linear oscillator's: it ends near `nominal` (later where the
  // normal force is clamped at 0); 8 durations bound it
  for (int n = 0; n < 8 * steps; n++) {
    bool slides = false;
    double x = h;
    detail::ContactState next = ode.step(s, h, &slides);
    if (passed(next, slides)) {
      double lo = 0.0;
      for (int iter = 0; iter < 80; iter++) {
        const double mid = 0.5 * (lo + x);
        if (!(mid > lo && mid < x)) break;
        bool mid_slides = false;
        const detail::ContactState m = ode.step(s, mid, &mid_slides);
        if (passed(m, mid_slides)) {
          x = mid;
          next = m;
          slides = mid_slides;
        } else {
          lo = mid;
        }
      }
    }
    t += x;
    if (!(next.delta > 0.0)) return {{next.vn, next.vt}, t};
    s = next;
    sliding = slides;
    const int fn = sign(ode.force(s, nullptr).fn);
    if (fn != 0) fn_sign = fn;
  }
  return {{s.vn, s.vt}, t};    // not reached for a valid law
}

// Rule (b) tabulated: the outcome as a function of the impact angle phi = atan2(|v_t|, |v_n|)
// in [0, pi/2], v_t' = sign(v_t) |v| H(phi) and v_n' = -ratio v_n (ratio = e, or e_w against the
// boundary, for the law's linear normal force), |v| the impact speed; H is interpolated linearly
// between nodes placed adaptively until the interpolation error is at most `tolerance` |v|
// (checked against integrated collisions at the quarter points of every interval: on an
// interval where H is smooth the largest error lies near the middle; where H has a kink the
// error is a tent whose top is at most twice its value at the nearest quarter point, so each is
// required to be within tolerance/2). The symmetry v_t -> -v_t of the law gives the other half.
// H(pi/2) = 1: a grazing impact (v_n -> 0) slides throughout and loses O(|v_n|) of v_t.
class SoftLimitTable {
 public:
  static constexpr double DEFAULT_TOLERANCE = 1e-6;

  SoftLimitTable(const Law &law, Partner partner, double tolerance = DEFAULT_TOLERANCE,
                 int steps = SOFT_LIMIT_STEPS)
      : law_(law), partner_(partner), tolerance_(tolerance), steps_(steps)
  {
    // the normal outcome is one number: integrated 16 times finer, to rounding
    normal_ratio_ = soft_limit_collision(law_, partner_, {-1.0, 0.0}, 16 * steps_).out.vn;
    const int initial = 16;
    const double right = 0.5 * PI;
    phi_.push_back(0.0);
    h_.push_back(exact(0.0));
    for (int k = 1; k <= initial; k++) {
      const double a = phi_.back(), b = right * k / initial;
      refine(a, h_.back(), b, exact(b), exact(0.5 * (a + b)), 0);
    }
  }

  // The outgoing contact velocity of an impact `in` (v_n < 0).
  ContactVelocity outgoing(ContactVelocity in) const
  {
    const double speed = std::hypot(in.vn, in.vt);
    const double phi = std::atan2(std::fabs(in.vt), std::fabs(in.vn));
    return {-normal_ratio_ * in.vn, (in.vt < 0.0 ? -speed : speed) * interpolate(phi)};
  }

  // H(phi), interpolated.
  double interpolate(double phi) const
  {
    const std::size_t k = std::min<std::size_t>(
        std::upper_bound(phi_.begin(), phi_.end(), phi) - phi_.begin(), phi_.size() - 1);
    if (k == 0) return h_[0];
    const double w = (phi - phi_[k - 1]) / (phi_[k] - phi_[k - 1]);
    return h_[k - 1] + w * (h_[k] - h_[k - 1]);
  }

  // H(phi) from an integrated collision (phi = pi/2: the grazing limit, 1).
  double exact(double phi) const
  {
    if (phi >= 0.5 * PI) return 1.0;
    const SoftCollision c =
        soft_limit_collision(law_, partner_, {-std::cos(phi), std::sin(phi)}, steps_);
    return c.out.vt;
  }

  double normal_ratio() const { return normal_ratio_; }
  double tolerance() const { return tolerance_; }
  std::size_t nodes() const { return phi_.size(); }

 private:
  // Appends the nodes of (a, b] (H known at a, b and the middle), splitting until the quarter
  // points interpolate within tolerance/2 (or the interval is at rounding's width).
  void refine(double a, double ha, double b, double hb, double hmid, int depth)
  {
    const double q1 = a + 0.25 * (b - a), mid = a + 0.5 * (b - a), q3 = a + 0.75 * (b - a);
    const double h1 = exact(q1), h3 = exact(q3);
    const double limit = 0.5 * tolerance_;
    const bool fine = std::fabs(h1 - (0.75 * ha + 0.25 * hb)) <= limit &&
        std::fabs(hmid - 0.5 * (ha + hb)) <= limit &&
        std::fabs(h3 - (0.25 * ha + 0.75 * hb)) <= limit;
    if (fine || depth >= 40 || !(q1 > a && q3 < b)) {
      phi_.push_back(b);
      h_.push_back(hb);
      return;
    }
    refine(a, ha, mid, hmid, h1, depth + 1);
    refine(mid, hmid, b, hb, h3, depth + 1);
  }

  Law law_;
  Partner partner_;
  double tolerance_;
  int steps_;
  double normal_ratio_;
  std::vector<double> phi_, h_;
};

// The soft law's tangential restitution of a sticking boundary collision (-v_t'/v_t, no
// Coulomb cap): the boundary's tangential oscillator u'' + q eta_t u' + q k_t u = 0 over the
// normal boundary collision's duration tau_w, which is not its half period (docs/model.md
// section 3.1), started at u = 0, u' = v_t. It does not depend on k_n.
inline double boundary_sticking_restitution(const Law &law)
{
  const double rate = 0.5 * law.q * law.eta_t;
  const double omega = std::sqrt(law.q * law.kt - rate * rate);
  const double t = law.tau_w;
  return -std::exp(-rate * t) * (std::cos(omega * t) - rate / omega * std::sin(omega * t));
}

}    // namespace mn

#endif
