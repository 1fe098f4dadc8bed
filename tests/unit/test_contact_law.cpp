// Unit tests of mn_contact.h: the mapping (k_n, e, beta) -> coefficients, and one contact
// integrated far more finely than any production run (RK4, dt = tau/2e4), so that the measured
// restitution and duration must equal the analytic ones to within the integration error.
#include "mn_contact.h"
#include "mn_integration.h"
#include "rk4_contact.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

// A disk in the plane with I = m sigma^2 / 8.
struct Disk {
  double x, y, vx, vy, w;
  double m, r;
  double inertia() const { return 0.5 * m * r * r; }
};

// Two disks (or one disk and the wall y = 0 when `wall` is set) in contact; u_t is part of the
// state so that RK4 integrates it like the positions.
struct Scene {
  Disk a, b;
  double ut = 0.0;
  bool wall = false;
};

// Time derivatives of a Scene.
struct Rates {
  double vx[2], vy[2], ax[2], ay[2], alpha[2], dut;
};

// The contact's kinematics and mass scale.
mn::Kinematics contact_kinematics(const Scene &s, double &mass_scale)
{
  if (s.wall) {
    mass_scale = s.a.m;
    return mn::kinematics(0.0, s.a.y, s.a.y, s.a.r, s.a.vx, s.a.vy, s.a.r * s.a.w);
  }
  const double dx = s.a.x - s.b.x, dy = s.a.y - s.b.y;
  mass_scale = 2.0 * s.a.m * s.b.m / (s.a.m + s.b.m);
  return mn::kinematics(dx, dy, std::hypot(dx, dy), s.a.r + s.b.r, s.a.vx - s.b.vx,
                        s.a.vy - s.b.vy, s.a.r * s.a.w + s.b.r * s.b.w);
}

// The accelerations (ax, ay, alpha per disk) that the contact force f gives.
void accelerations(const Scene &s, const mn::Kinematics &k, const mn::Force &f, Rates &d)
{
  const double fx = f.fn * k.nx - f.ft * k.ny, fy = f.fn * k.ny + f.ft * k.nx;
  d.ax[0] = fx / s.a.m;
  d.ay[0] = fy / s.a.m;
  d.alpha[0] = -s.a.r * f.ft / s.a.inertia();
  if (!s.wall) {
    d.ax[1] = -fx / s.b.m;
    d.ay[1] = -fy / s.b.m;
    d.alpha[1] = -s.b.r * f.ft / s.b.inertia();
  }
}

Rates rates(const mn::Law &law, const Scene &s)
{
  Rates d{{s.a.vx, s.b.vx}, {s.a.vy, s.b.vy}, {0, 0}, {0, 0}, {0, 0}, 0};
  double mass_scale;
  const mn::Kinematics k = contact_kinematics(s, mass_scale);
  if (k.delta <= 0.0) return d;
  double ut = s.ut;
  const mn::Force f = mn::contact_force(law, mass_scale, k, law.material.mu > 0 ? &ut : nullptr, 0.0);
  accelerations(s, k, f, d);
  d.dut = k.vt;
  return d;
}

Scene advance(const Scene &s, const Rates &d, double h)
{
  Scene n = s;
  Disk *disk[2] = {&n.a, &n.b};
  for (int i = 0; i < 2; i++) {
    disk[i]->x += h * d.vx[i];
    disk[i]->y += h * d.vy[i];
    disk[i]->vx += h * d.ax[i];
    disk[i]->vy += h * d.ay[i];
    disk[i]->w += h * d.alpha[i];
  }
  n.ut += h * d.dut;
  return n;
}

double overlap(const Scene &q)
{
  if (q.wall) return q.a.r - q.a.y;
  return q.a.r + q.b.r - std::hypot(q.a.x - q.b.x, q.a.y - q.b.y);
}

// RK4 over the whole contact, with steps of tau/resolution; returns its duration and leaves the
// scene after separation.
double collide(const mn::Law &law, Scene &s, double tau, double resolution = 2e4)
{
  auto rk4 = [&law](const Scene &q, double h) {
    return rk4_step(q, h, [&law](const Scene &r) { return rates(law, r); }, advance);
  };
  return contact_duration(s, tau / resolution, rk4, overlap);
}

// The contact as LAMMPS integrates it: fix nve/sphere disc (velocity Verlet) or fix nve/ab2 moves
// the disks by steps of dt, and each force evaluation advances u_t as pair_style gran/mn and fix
// wall/gran/mn do (mn::contact_force with the integrator; the history is cleared when the contact
// has ended). Stops two steps after the contact's end (AB2 still uses the contact's last
// acceleration in the step after it); returns the contact's duration, from the overlap
// interpolated linearly between steps as the LAMMPS tests measure it.
double integrate(const mn::Law &law, Scene &s, double dt, mn::Integrator integrator)
{
  const bool ab2 = integrator == mn::Integrator::AdamsBashforth2;
  double vt_previous = 0.0;
  auto evaluate = [&](double dt_history) {
    Rates d{{0, 0}, {0, 0}, {0, 0}, {0, 0}, {0, 0}, 0};
    double mass_scale;
    const mn::Kinematics k = contact_kinematics(s, mass_scale);
    if (k.delta <= 0.0) {
      s.ut = vt_previous = 0.0;
      return d;
    }
    const mn::Force f = mn::contact_force(law, mass_scale, k, law.material.mu > 0 ? &s.ut : nullptr,
                                          dt_history, integrator, ab2 ? &vt_previous : nullptr);
    accelerations(s, k, f, d);
    return d;
  };
  Disk *disk[2] = {&s.a, &s.b};
  const int mobile = s.wall ? 1 : 2;
  Rates a = evaluate(0.0), a_previous = a;    // nve/ab2's first step: a(t - dt) = a(t)
  double t = 0.0, t_start = -1.0, duration = -1.0;
  for (int step = 0, after_end = -1; step < 1000000 && after_end < 2; step++) {
    const double before = overlap(s);
    if (ab2) {
      for (int i = 0; i < mobile; i++) {
        Disk &q = *disk[i];
        const double vx = mn::ab2_velocity(q.vx, a.ax[i], a_previous.ax[i], dt);
        const double vy = mn::ab2_velocity(q.vy, a.ay[i], a_previous.ay[i], dt);
        q.x = mn::trapezoidal_position(q.x, q.vx, vx, dt);
        q.y = mn::trapezoidal_position(q.y, q.vy, vy, dt);
        q.vx = vx;
        q.vy = vy;
        q.w = mn::ab2_velocity(q.w, a.alpha[i], a_previous.alpha[i], dt);
      }
      a_previous = a;
      a = evaluate(dt);
    } else {
      for (int i = 0; i < mobile; i++) {
        Disk &q = *disk[i];
        q.vx += 0.5 * dt * a.ax[i];
        q.vy += 0.5 * dt * a.ay[i];
        q.w += 0.5 * dt * a.alpha[i];
        q.x += dt * q.vx;
        q.y += dt * q.vy;
      }
      a = evaluate(dt);
      for (int i = 0; i < mobile; i++) {
        Disk &q = *disk[i];
        q.vx += 0.5 * dt * a.ax[i];
        q.vy += 0.5 * dt * a.ay[i];
        q.w += 0.5 * dt * a.alpha[i];
      }
    }
    const double after = overlap(s);
    if (before <= 0 && after > 0) t_start = t + dt * (-before) / (after - before);
    t += dt;
    if (after_end >= 0) after_end++;
    if (t_start >= 0 && duration < 0 && before > 0 && after <= 0) {
      duration = t - dt + dt * before / (before - after) - t_start;
      after_end = 0;
    }
  }
  if (duration < 0) ADD_FAILURE() << "contact never ended";
  return duration;
}

// Restitutions -v_n'/v_n, -v_t'/v_t and duration of a contact between two states of a Scene.
struct Outcome {
  double e, beta, duration;
};

Outcome outcome(const Scene &before, const Scene &after, double duration)
{
  double mass_scale;
  const mn::Kinematics k0 = contact_kinematics(before, mass_scale);
  const mn::Kinematics k1 = contact_kinematics(after, mass_scale);
  return {-k1.vn / k0.vn, -k1.vt / k0.vt, duration};
}

Disk disk(double diameter, double x, double y, double vx, double vy)
{
  // mass proportional to area, 1 for the unit disk (LAMMPS: set density/disc 4/pi)
  return Disk{x, y, vx, vy, 0.0, diameter * diameter, 0.5 * diameter};
}

// Relative normal and tangential velocity of a with respect to b, in the frame of their
// current line of centres (docs/model.md conventions: n from b to a, t = (-n_y, n_x)).
mn::Kinematics relative_motion(const Scene &s)
{
  const double dx = s.a.x - s.b.x, dy = s.a.y - s.b.y;
  return mn::kinematics(dx, dy, std::hypot(dx, dy), s.a.r + s.b.r, s.a.vx - s.b.vx,
                        s.a.vy - s.b.vy, s.a.r * s.a.w + s.b.r * s.b.w);
}

}    // namespace

TEST(Mapping, DerivedCoefficientsSatisfyTheirDefinitions)
{
  for (double e : {0.3, 0.7, 1.0})
    for (double kn : {1e3, 2e5, 1e10}) {
      const mn::Law law = mn::derive({kn, e, 0.7, 0.5});
      const double ln_e = std::log(e);
      // tau_c is the half period of delta'' + 2 eta_n delta' + 2 kn delta = 0
      EXPECT_NEAR(law.tau_c, mn::PI / std::sqrt(2 * kn - law.eta_n * law.eta_n), 1e-12 * law.tau_c);
      EXPECT_NEAR(std::exp(-law.eta_n * law.tau_c), e, 1e-12);
      EXPECT_NEAR(law.eta_t * 3 * law.tau_c, -std::log(0.7), 1e-12);
      EXPECT_NEAR(6 * law.kt - 9 * law.eta_t * law.eta_t, 2 * kn - law.eta_n * law.eta_n,
                  1e-12 * kn);
      EXPECT_NEAR(law.tau_w, mn::PI / std::sqrt(kn - law.eta_n * law.eta_n / 4), 1e-12 * law.tau_w);
      (void) ln_e;
    }
  // docs/model.md section 3: e = 0.7 gives e_w ~ 0.778
  EXPECT_NEAR(mn::derive({1e5, 0.7, 0.7, 0.5}).e_w, 0.778, 5e-4);
}

TEST(Mapping, RejectsOutOfRangeMaterial)
{
  EXPECT_NE(mn::material_error({0.0, 0.7, 0.7, 0.5}), nullptr);
  EXPECT_NE(mn::material_error({-1.0, 0.7, 0.7, 0.5}), nullptr);
  EXPECT_NE(mn::material_error({1e5, 0.0, 0.7, 0.5}), nullptr);
  EXPECT_NE(mn::material_error({1e5, 1.01, 0.7, 0.5}), nullptr);
  EXPECT_NE(mn::material_error({1e5, 0.7, 0.0, 0.5}), nullptr);
  EXPECT_NE(mn::material_error({1e5, 0.7, 1.5, 0.5}), nullptr);
  EXPECT_NE(mn::material_error({1e5, 0.7, 0.7, -0.1}), nullptr);
  EXPECT_NE(mn::material_error({NAN, 0.7, 0.7, 0.5}), nullptr);
  EXPECT_EQ(mn::material_error({1e5, 1.0, 1.0, 0.0}), nullptr);
}

// Head-on: e and tau_c for equal and unequal disks (the 2M scaling makes both mass-free).
TEST(Collision, HeadOnRestitutionAndDuration)
{
  for (double e : {0.5, 0.7, 0.9, 1.0})
    for (double kn : {0.5e5, 256e5})
      for (double d2 : {1.0, 0.8}) {
        const mn::Law law = mn::derive({kn, e, 0.7, 0.0});
        const double gap = 1e-3;
        Scene s;
        s.a = disk(1.0, -0.5 - gap, 0, 1.0, 0);
        s.b = disk(d2, 0.5 * d2 + gap, 0, -1.0, 0);
        const double duration = collide(law, s, law.tau_c);
        const double e_measured = -(s.a.vx - s.b.vx) / 2.0;
        // RK4 error is negligible; the step that straddles the contact's end misplaces at
        // most eta_n * h of relative velocity: bound 1e-4.
        EXPECT_NEAR(e_measured, e, 1e-4) << "e=" << e << " kn=" << kn << " d2=" << d2;
        EXPECT_NEAR(duration / law.tau_c, 1.0, 1e-4) << "e=" << e << " kn=" << kn;
      }
}

// Sticking oblique impact: the tangential oscillation has the normal one's half period, so the
// contact ends after half an oscillation damped by beta. The tangential motion is given as spin
// and the contact is stiff (tau_c ~ 2e-4), so that the line of centres turns by ~1e-4 rad during
// the contact: the frame's rotation then changes the measured ratio by ~1e-4, inside 1e-3.
TEST(Collision, StickingObliqueImpactHasTangentialRestitutionBeta)
{
  for (double beta : {0.3, 0.7, 1.0}) {
    const mn::Law law = mn::derive({1e8, 0.7, beta, 1e6});
    Scene s;
    s.a = disk(1.0, -0.5001, 0, 1.0, 0);
    s.b = disk(1.0, 0.5001, 0, -1.0, 0);
    s.a.w = s.b.w = 0.6;
    const double vt_before = relative_motion(s).vt;
    collide(law, s, law.tau_c);
    EXPECT_NEAR(-relative_motion(s).vt / vt_before, beta, 1e-3) << "beta=" << beta;
  }
}

// Sliding throughout (small mu): the tangential impulse is mu times the normal one. With the
// normal force clamped at zero, the tangential impulse, read exactly from the change of spin
// (J_t = -I dw / r), is mu M (1 + e') |v_n|. Stiff contact and spin-only slip as above.
TEST(Collision, SlidingImpactTransfersMuTimesNormalImpulse)
{
  mn::Options clamp;
  clamp.limit_damping = true;
  const double mu = 0.01;
  const mn::Law law = mn::derive({1e8, 0.7, 0.7, mu}, clamp);
  Scene s;
  s.a = disk(1.0, -0.5001, 0, 1.0, 0);
  s.b = disk(1.0, 0.5001, 0, -1.0, 0);
  s.a.w = s.b.w = 2.0;
  const double w_before = s.a.w;
  collide(law, s, law.tau_c);
  const double e_clamped = relative_motion(s).vn / 2.0;    // v_n went from -2 to 2 e'
  EXPECT_GT(e_clamped, 0.7);    // no attraction at the end: less is dissipated
  const double tangential_impulse = -s.a.inertia() * (s.a.w - w_before) / s.a.r;
  const double reduced_mass = 0.5;
  EXPECT_NEAR(std::fabs(tangential_impulse), mu * reduced_mass * (1 + e_clamped) * 2.0, 1e-6);
}

TEST(Collision, BoundaryContactHasDurationTauWAndRestitutionEW)
{
  for (double e : {0.5, 0.7, 0.9}) {
    const mn::Law law = mn::derive({2e5, e, 0.7, 0.0});
    Scene s;
    s.wall = true;
    s.a = disk(1.0, 0, 0.501, 0, -1.0);
    const double duration = collide(law, s, law.tau_w);
    EXPECT_NEAR(s.a.vy, law.e_w, 1e-4) << "e=" << e;
    EXPECT_NEAR(duration / law.tau_w, 1.0, 1e-4) << "e=" << e;
  }
}

TEST(Force, NoFrictionNeedsNoHistory)
{
  const mn::Law law = mn::derive({1e5, 0.7, 0.7, 0.0});
  const mn::Kinematics k = mn::kinematics(1.0, 0.0, 1.0, 1.01, -0.5, 0.3, 0.1);
  const mn::Force f = mn::contact_force(law, 1.0, k, nullptr, 1e-4);
  EXPECT_EQ(f.ft, 0.0);
  EXPECT_NEAR(f.fn, law.material.kn * 0.01 + law.eta_n * 0.5, 1e-9);
}

TEST(Force, LiteralHistoryKeepsGrowingWhileSlidingCutbackDoesNot)
{
  const mn::Law literal = mn::derive({1e5, 0.7, 0.7, 0.1});
  mn::Options cut;
  cut.coulomb_cutback = true;
  const mn::Law cutback = mn::derive({1e5, 0.7, 0.7, 0.1}, cut);
  const mn::Kinematics k = mn::kinematics(1.0, 0.0, 1.0, 1.001, 0.0, 1.0, 0.0);
  double ut_literal = 0.0, ut_cutback = 0.0;
  for (int step = 0; step < 100; step++) {
    const mn::Force a = mn::contact_force(literal, 1.0, k, &ut_literal, 1e-4);
    const mn::Force b = mn::contact_force(cutback, 1.0, k, &ut_cutback, 1e-4);
    EXPECT_TRUE(a.sliding);
    EXPECT_NEAR(std::fabs(a.ft), 0.1 * std::fabs(a.fn), 1e-12);
    EXPECT_NEAR(b.ft, a.ft, 1e-12);
    // after a cut-back the elastic-plus-viscous trial force sits exactly on the cone
    EXPECT_NEAR(std::fabs(cutback.kt * ut_cutback + cutback.eta_t * k.vt), 0.1 * std::fabs(b.fn),
                1e-9 * std::fabs(b.fn));
  }
  EXPECT_NEAR(ut_literal, 100 * 1e-4 * 1.0, 1e-12);    // the literal integral of v_t
}

// Under Adams-Bashforth 2, u_t is the trapezoidal sum of the v_t seen at the force evaluations,
// exact for a v_t linear in time; a re-evaluation (dt = 0, LAMMPS's setup) records v_t without
// advancing u_t; a new contact (slot 0) counts v_t = 0 before it, adding v_t dt/2 on its first
// step. Velocity Verlet's rule is the plain sum v_t dt (its v_t is the half-step one). Rules out
// AB2 summing v_t(t + dt) dt (off by (v_t(end) - v_t(start)) dt/2 here) and a new contact
// taking a whole step of v_t.
TEST(Force, AdamsBashforthAdvancesUtByTheTrapezoidalRule)
{
  const mn::Law law = mn::derive({1e5, 0.7, 0.7, 1e6});
  const double dt = 1e-4;
  auto vt_at = [](int step) { return 0.3 + 0.1 * step; };
  auto at = [&](int step) { return mn::kinematics(1.0, 0.0, 1.0, 1.001, 0.0, vt_at(step), 0.0); };
  double ut = 0.0, vt_previous = 0.0, ut_verlet = 0.0;
  mn::contact_force(law, 1.0, at(0), &ut, 0.0, mn::Integrator::AdamsBashforth2, &vt_previous);
  EXPECT_EQ(ut, 0.0);
  EXPECT_EQ(vt_previous, vt_at(0));
  for (int step = 1; step <= 10; step++) {
    mn::contact_force(law, 1.0, at(step), &ut, dt, mn::Integrator::AdamsBashforth2, &vt_previous);
    mn::contact_force(law, 1.0, at(step), &ut_verlet, dt);
  }
  const double integral = 10 * dt * 0.5 * (vt_at(0) + vt_at(10));    // linear in time
  EXPECT_NEAR(ut, integral, 1e-15);
  EXPECT_NEAR(ut_verlet, integral + 0.5 * dt * (vt_at(10) - vt_at(0)), 1e-15);

  double fresh_ut = 0.0, fresh_vt = 0.0;    // as a new contact's slots are
  mn::contact_force(law, 1.0, at(3), &fresh_ut, dt, mn::Integrator::AdamsBashforth2, &fresh_vt);
  EXPECT_NEAR(fresh_ut, 0.5 * dt * vt_at(3), 1e-18);
}

// Velocity Verlet on an undamped oscillator is stable up to dt = 2/omega exactly.
TEST(Stability, VelocityVerletUndampedLimitIsTwoOverOmega)
{
  for (double w2 : {1.0, 2e5, 3e10})
    EXPECT_NEAR(mn::max_stable_dt(mn::Integrator::VelocityVerlet, w2, 0.0) * std::sqrt(w2), 2.0,
                1e-6);
}

// The limit is computed once per (integrator, w2, g) and kept: asked again, each mode gets the
// number its own bisection gives, with other modes asked in between (a store keyed on less,
// say without g or the integrator, would hand one mode another's limit).
TEST(Stability, KeptLimitIsEachModesOwn)
{
  const auto vv = mn::Integrator::VelocityVerlet, ab2 = mn::Integrator::AdamsBashforth2;
  const double modes[][2] = {{4e5, 10.0}, {4e5, 400.0}, {1e3, 10.0}};
  for (int round = 0; round < 2; round++)
    for (const auto integrator : {vv, ab2})
      for (const auto &mode : modes)
        EXPECT_EQ(mn::max_stable_dt(integrator, mode[0], mode[1]),
                  mn::detail::bisect_stable_dt(integrator, mode[0], mode[1]));
  EXPECT_NE(mn::max_stable_dt(vv, 4e5, 10.0), mn::max_stable_dt(vv, 4e5, 400.0));
  EXPECT_NE(mn::max_stable_dt(vv, 4e5, 10.0), mn::max_stable_dt(ab2, 4e5, 10.0));
}

// Independent of the eigenvalue computation: iterate the integrators on the oscillator just
// below and just above the reported limit.
TEST(Stability, ReportedLimitSeparatesDecayFromGrowth)
{
  for (mn::Integrator integrator :
       {mn::Integrator::VelocityVerlet, mn::Integrator::AdamsBashforth2}) {
    const mn::Law law = mn::derive({1e5, 0.7, 0.7, 0.5});
    const double cases[][2] = {{2 * law.material.kn, 2 * law.eta_n}, {6 * law.kt, 6 * law.eta_t}};
    for (const auto &mode : cases) {
      const double dt_max = mn::max_stable_dt(integrator, mode[0], mode[1]);
      ASSERT_GT(dt_max, 0.0);
      auto amplitude_after = [&](double dt) {
        double s[3] = {1.0, 0.0, -mode[0]}, next[3];
        double amplitude = 1.0;
        for (int n = 0; n < 20000 && amplitude < 1e6; n++) {
          mn::detail::step(integrator, mode[0], mode[1], dt, s, next);
          for (int c = 0; c < 3; c++) s[c] = next[c];
          amplitude = std::fabs(s[0]) + std::fabs(s[1]) / std::sqrt(mode[0]);
        }
        return amplitude;
      };
      EXPECT_LT(amplitude_after(0.98 * dt_max), 1.0);
      EXPECT_GT(amplitude_after(1.02 * dt_max), 1e3);
    }
  }
}

TEST(Stability, LawLimitIsTheStiffestModeAndAboveTheRecommendedStep)
{
  const mn::Law law = mn::derive({2e5, 0.7, 0.7, 0.5});
  const double dt_max = mn::max_stable_dt(law, mn::Integrator::VelocityVerlet);
  EXPECT_LE(dt_max, mn::max_stable_dt(mn::Integrator::VelocityVerlet, 2 * law.material.kn, 2 * law.eta_n));
  EXPECT_GT(dt_max, law.tau_c / 10);    // the paper's tau_c/100 is far inside
  EXPECT_LT(dt_max, law.tau_c);
}

// The limit names the mode that sets it. With usual e and beta that is the normal mode of two
// disks (the stiffest, w^2 = 2 kn); beta -> 0 damps the sticking tangential mode (rate 6 eta_t
// for two disks) so hard that it sets a limit below tau_c/100, and e -> 0 does the same to the
// normal mode (tau_c grows with |ln e|).
TEST(Stability, LimitNamesTheModeThatSetsIt)
{
  for (const auto integrator : {mn::Integrator::VelocityVerlet, mn::Integrator::AdamsBashforth2}) {
    const mn::Law usual = mn::derive({2e5, 0.7, 0.7, 0.5});
    EXPECT_EQ(mn::stability_limit(usual, integrator).mode, mn::Mode::NormalPair);
    const mn::Law sticky = mn::derive({2e5, 0.7, 1e-40, 0.5});
    const mn::StabilityLimit tangential = mn::stability_limit(sticky, integrator);
    EXPECT_EQ(tangential.mode, mn::Mode::TangentialPair);
    EXPECT_EQ(tangential.dt, mn::max_stable_dt(integrator, 6 * sticky.kt, 6 * sticky.eta_t));
    EXPECT_LT(tangential.dt, sticky.tau_c / 100);
    // without friction the tangential mode does not exist
    EXPECT_EQ(mn::stability_limit(mn::derive({2e5, 0.7, 1e-40, 0.0}), integrator).mode,
              mn::Mode::NormalPair);
    const mn::Law dead = mn::derive({2e5, 1e-40, 0.7, 0.5});
    const mn::StabilityLimit normal = mn::stability_limit(dead, integrator);
    EXPECT_EQ(normal.mode, mn::Mode::NormalPair);
    EXPECT_LT(normal.dt, dead.tau_c / 100);
  }
}

// Adams-Bashforth 2 amplifies an undamped mode (e = 1) at every step, so it has no strict
// limit: the reported one is where a contact (pi/w) grows by UNDAMPED_GROWTH_PER_CONTACT. The
// paper's tau_c/100 is well inside it; iterating the step over one contact shows the growth.
TEST(Stability, AdamsBashforthOnAnUndampedModeIsLimitedByTheGrowthOverAContact)
{
  const mn::Law law = mn::derive({2e5, 1.0, 0.7, 0.0});
  ASSERT_EQ(law.eta_n, 0.0);
  EXPECT_TRUE(mn::amplifies_undamped_mode(law, mn::Integrator::AdamsBashforth2));
  EXPECT_FALSE(mn::amplifies_undamped_mode(law, mn::Integrator::VelocityVerlet));
  const double dt_max = mn::max_stable_dt(law, mn::Integrator::AdamsBashforth2);
  EXPECT_GT(dt_max, law.tau_c / 100);
  const double w2 = 2 * law.material.kn;
  auto growth_over_a_contact = [&](double dt) {
    double s[3] = {1.0, 0.0, -w2}, next[3];
    const int steps = (int) std::ceil(mn::PI / std::sqrt(w2) / dt);
    double energy0 = 0.5 * w2, energy = energy0;
    for (int n = 0; n < 4 * steps; n++) {    // two oscillations: the growth of four contacts
      mn::detail::step(mn::Integrator::AdamsBashforth2, w2, 0.0, dt, s, next);
      for (int c = 0; c < 3; c++) s[c] = next[c];
      energy = 0.5 * (w2 * s[0] * s[0] + s[1] * s[1]);
    }
    return std::pow(std::sqrt(energy / energy0), 0.25) - 1.0;
  };
  EXPECT_LT(growth_over_a_contact(law.tau_c / 100), 1e-4);
  EXPECT_NEAR(growth_over_a_contact(dt_max), mn::UNDAMPED_GROWTH_PER_CONTACT,
              0.5 * mn::UNDAMPED_GROWTH_PER_CONTACT);
}

// ---------------------------------------------------------------------------------------
// The integrators' order of convergence on single collisions (as LAMMPS runs them), against
// RK4 at tau/2e5.

namespace {

// Sticking oblique impacts: two unit disks (spin-only slip, stiff as above) and a unit disk
// falling obliquely on the wall y = 0, `gap` of free flight before the contact (closing speed 1).
Scene oblique_pair(double gap)
{
  Scene s;
  s.a = disk(1.0, -0.5 - 0.5 * gap, 0, 0.5, 0);
  s.b = disk(1.0, 0.5 + 0.5 * gap, 0, -0.5, 0);
  s.a.w = s.b.w = 0.6;
  return s;
}

Scene oblique_wall(double gap)
{
  Scene s;
  s.wall = true;
  s.a = disk(1.0, 0, 0.5 + gap, 0.5, -1.0);
  return s;
}

struct Convergence {
  Outcome reference;
  std::vector<Outcome> errors;    // measured - reference, at dt = tau/50, /100, /200
};

// The contact begins half-way through a step (after 3.5 steps of free flight), as in the LAMMPS
// decks: there a contact that switches on between steps costs no first-order error.
Convergence convergence(const mn::Law &law, Scene (*scene)(double), double tau,
                        mn::Integrator integrator)
{
  Convergence c;
  Scene s = scene(0.2 * tau), start = s;
  c.reference = outcome(start, s, collide(law, s, tau, 2e5));
  for (double steps : {50.0, 100.0, 200.0}) {
    const double dt = tau / steps;
    s = start = scene(3.5 * dt);
    const Outcome o = outcome(start, s, integrate(law, s, dt, integrator));
    c.errors.push_back({o.e - c.reference.e, o.beta - c.reference.beta,
                        o.duration - c.reference.duration});
    std::printf("%s dt = tau/%g: e %+.3e beta %+.3e duration/tau %+.3e\n",
                integrator == mn::Integrator::AdamsBashforth2 ? "AB2   " : "Verlet", steps,
                c.errors.back().e, c.errors.back().beta, c.errors.back().duration / tau);
  }
  return c;
}

}    // namespace

// Velocity Verlet's damping sees velocities half a step old: its restitutions are first order
// in dt, within 3 (1 + x)|ln x| dt/tau + (dt/tau)^2 of x (tests/lammps/granmn_run.py
// restitution_error_bound argues it). Adams-Bashforth 2 with the trapezoidal rule for positions
// and u_t is second order: over half an oscillation of angular frequency w = pi/tau its error is
// c (w dt)^2 with c of the order of its error constant (5/12; measured 0.2), so
// |error| <= (pi dt/tau)^2. A first-order u_t (u_t += v_t(t) dt under AB2, as before) errs by
// ~0.55 pi dt/tau in beta (0.035 at tau/50, nine times the bound) and halves its error with dt
// (ratio 2, not 4).
void expect_orders(const mn::Law &law, Scene (*scene)(double), double tau, double e, double beta)
{
  const double steps[3] = {50.0, 100.0, 200.0};
  for (auto integrator : {mn::Integrator::VelocityVerlet, mn::Integrator::AdamsBashforth2}) {
    const bool ab2 = integrator == mn::Integrator::AdamsBashforth2;
    const Convergence c = convergence(law, scene, tau, integrator);
    EXPECT_NEAR(c.reference.e, e, 1e-4);
    EXPECT_NEAR(c.reference.beta, beta, 1e-3);    // the line of centres turns by ~1e-4 rad
    EXPECT_NEAR(c.reference.duration / tau, 1.0, 1e-4);
    for (int k = 0; k < 3; k++) {
      const double h = 1.0 / steps[k];    // dt/tau
      const Outcome &error = c.errors[k];
      auto bound = [&](double x) {
        return ab2 ? std::pow(mn::PI * h, 2) : 3 * (1 + x) * std::fabs(std::log(x)) * h + h * h;
      };
      EXPECT_LE(std::fabs(error.e), bound(e)) << "dt = tau/" << steps[k];
      EXPECT_LE(std::fabs(error.beta), bound(beta)) << "dt = tau/" << steps[k];
      // a contact starts and ends between steps: at most a step off; AB2 second order
      EXPECT_LE(std::fabs(error.duration / tau), ab2 ? std::pow(mn::PI * h, 2) : h);
    }
    // halving dt divides the error by 2^order
    for (int k = 0; k < 2; k++) {
      const Outcome &coarse = c.errors[k], &fine = c.errors[k + 1];
      for (double ratio : {coarse.e / fine.e, coarse.beta / fine.beta}) {
        if (ab2)
          EXPECT_GE(ratio, 3.0) << "AB2 is second order; dt = tau/" << steps[k];
        else
          EXPECT_TRUE(ratio >= 1.5 && ratio <= 2.6) << "Verlet: first order, ratio " << ratio;
      }
      if (ab2) EXPECT_GE(coarse.duration / fine.duration, 3.0);
    }
  }
}

TEST(Convergence, StickingObliqueImpactUnderBothIntegrators)
{
  const mn::Law law = mn::derive({1e8, 0.7, 0.7, 1e6});
  expect_orders(law, oblique_pair, law.tau_c, 0.7, 0.7);
}

// With beta = e the wall's sticking tangential mode is its normal one (3 eta_t = eta_n and
// 3 kt = kn, docs/model.md section 3): the tangential restitution against the wall is e_w too.
TEST(Convergence, StickingObliqueWallBounceUnderBothIntegrators)
{
  const mn::Law law = mn::derive({2e5, 0.7, 0.7, 1e6});
  expect_orders(law, oblique_wall, law.tau_w, law.e_w, law.e_w);
}
