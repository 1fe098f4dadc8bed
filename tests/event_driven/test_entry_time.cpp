// The entry times of plugin/event_driven/entry_time.h: the earliest tau >= 0 at which a gap
// function is <= 0 while closing, against brute force (the gap sampled finely in long double):
// never later than the first sample that is closed and closing (no missed or late entry), and
// at a closed gap (no early one). Random gaps of the engine's kinds: a pair (convex quadratic),
// the floor and a cell's side (concave quadratics under gravity), a bump (quartic).
#include "entry_time.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

long double value(const double *c, int deg, long double x)
{
  long double v = c[deg];
  for (int k = deg - 1; k >= 0; k--) v = v * x + c[k];
  return v;
}

long double slope(const double *c, int deg, long double x)
{
  long double v = deg * static_cast<long double>(c[deg]);
  for (int k = deg - 1; k >= 1; k--) v = v * x + k * static_cast<long double>(c[k]);
  return v;
}

// The first of n + 1 samples of [0, horizon] where the gap is closed and closing (or, as the
// definition's infimum, opening no more), or infinity.
double sampled_entry(const double *c, int deg, double horizon, int n)
{
  for (int k = 0; k <= n; k++) {
    const long double t = horizon * static_cast<long double>(k) / n;
    if (value(c, deg, t) <= 0 && slope(c, deg, t) < 0) return static_cast<double>(t);
  }
  return mn::ed::NEVER;
}

// The engine's gap scale: a contact distance ~1, speeds ~1, gravity ~1.
struct Check {
  double horizon;
  int samples;

  // entry found by the solver: `found`; brute force on the same polynomial
  void operator()(const double *c, int deg, double found, const char *what) const
  {
    const double sampled = sampled_entry(c, deg, horizon, samples);
    const double spacing = horizon / samples;
    if (std::isfinite(sampled)) {
      // not later than the first closed sample (a dip between samples may make it earlier)
      ASSERT_LE(found, sampled + 1e-12) << what;
    }
    if (std::isfinite(found) && found <= horizon) {
      // a real entry: the gap at it is closed (to rounding) and it closes there or just after
      const long double scale = std::fabs(c[0]) + std::fabs(c[1]) + std::fabs(c[2]) + 1.0;
      EXPECT_LE(value(c, deg, found), 1e-12 * scale) << what << " at " << found;
      const long double later = found + 1e-9 + 1e-9 * found;
      EXPECT_TRUE(slope(c, deg, found) <= 1e-9 * scale || value(c, deg, later) <= 0)
          << what << " at " << found;
      if (!std::isfinite(sampled)) {
        // brute force saw none: the entry is a dip narrower than a sample (or at the end)
        EXPECT_TRUE(found > horizon - spacing ||
                    value(c, deg, found + spacing) > 0 || value(c, deg, found - spacing) > 0)
            << what << " at " << found;
      }
    }
  }
};

}    // namespace

TEST(EntryTime, QuadraticsOfEveryKind)
{
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Check check{4.0, 20000};
  for (int n = 0; n < 5000; n++) {
    // a pair: |dr + dv t|^2 - d^2
    const double dx = 2 * u(random), dy = 2 * u(random), vx = u(random), vy = u(random);
    const double pair[3] = {dx * dx + dy * dy - 1.0, 2 * (dx * vx + dy * vy), vx * vx + vy * vy};
    check(pair, 2, mn::ed::quadratic_entry(pair[0], pair[1], pair[2]), "pair");
    // the floor or a cell's side under gravity: h + v t - g/2 t^2, and the other sign of g
    const double g = 0.5 + std::fabs(u(random));
    const double fall[3] = {0.3 * u(random), u(random), -0.5 * g};
    check(fall, 2, mn::ed::quadratic_entry(fall[0], fall[1], fall[2]), "fall");
    const double rise[3] = {0.3 * u(random), u(random), 0.5 * g};
    check(rise, 2, mn::ed::quadratic_entry(rise[0], rise[1], rise[2]), "rise");
  }
}

// Touching gaps: just after a collision (0 to rounding, opening) there is no entry at ~0; a
// gap left closed by rounding while closing enters at once; a concave gap closed by rounding
// and opening too little to open enters where it turns (its vertex).
TEST(EntryTime, TouchingGaps)
{
  using mn::ed::quadratic_entry;
  for (double rounding : {-1e-16, 0.0, 1e-16}) {
    EXPECT_EQ(quadratic_entry(rounding, 0.3, 1.0), mn::ed::NEVER);       // a pair flying apart
    if (rounding <= 0.0) {
      EXPECT_EQ(quadratic_entry(rounding, -0.3, 1.0), 0.0);
    }
    // a bounce off the floor: the next landing, not the root at ~0
    EXPECT_NEAR(quadratic_entry(rounding, 0.8, -0.5), 1.6, 1e-14);
  }
  // no normal velocity left: the vertex
  EXPECT_NEAR(quadratic_entry(-1e-16, 1e-9, -0.5), 1e-9, 1e-20);
  EXPECT_EQ(quadratic_entry(-1e-16, -1e-9, -0.5), 0.0);
}

// A disk falling past a bump: |dr + v t + g t^2/2|^2 - d^2, a quartic, over a horizon; random
// starts around the bump, grazing ones (the minimum distance ~ the contact distance, where a
// tangent double root is easy to miss) and starts touching it after a bounce.
TEST(EntryTime, QuarticsOfADiskFallingPastABump)
{
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double horizon = 3.0;
  const Check check{horizon, 30000};
  int entries = 0;
  for (int n = 0; n < 3000; n++) {
    const double gx = 0.45 * std::fabs(u(random)), gy = -1.0;
    double dx = 2.5 * u(random), dy = 0.5 + 2.0 * std::fabs(u(random));
    double vx = 2 * u(random), vy = 2 * u(random);
    if (n % 3 == 1) {    // touching after a bounce: on the surface, moving off it
      const double a = 3.14159265358979 * (0.1 + 0.8 * std::fabs(u(random)));
      dx = std::cos(a);
      dy = std::sin(a);
      const double speed = std::fabs(u(random));
      vx = dx * speed - dy * u(random);
      vy = dy * speed + dx * u(random);
    }
    const double c[5] = {dx * dx + dy * dy - 1.0, 2 * (dx * vx + dy * vy),
                         vx * vx + vy * vy + dx * gx + dy * gy, vx * gx + vy * gy,
                         0.25 * (gx * gx + gy * gy)};
    const double found = mn::ed::quartic_entry(c, horizon);
    entries += std::isfinite(found);
    check(c, 4, found, "bump");
    // the same path shifted so that its closest approach grazes the bump
    double closest = INFINITY, at = 0.0;
    for (int k = 0; k <= 3000; k++) {
      const double t = horizon * k / 3000.0;
      const double px = dx + vx * t + 0.5 * gx * t * t, py = dy + vy * t + 0.5 * gy * t * t;
      if (std::hypot(px, py) < closest) {
        closest = std::hypot(px, py);
        at = t;
      }
    }
    if (at > 0.0 && at < horizon) {
      const double s = 1.0 / closest * (1.0 - 1e-9 * u(random));
      const double gdx = dx * s, gdy = dy * s;    // not exact grazing: a scaled start
      const double g4[5] = {gdx * gdx + gdy * gdy - 1.0, 2 * (gdx * vx + gdy * vy),
                            vx * vx + vy * vy + gdx * gx + gdy * gy, vx * gx + vy * gy,
                            0.25 * (gx * gx + gy * gy)};
      check(g4, 4, mn::ed::quartic_entry(g4, horizon), "grazing");
    }
  }
  EXPECT_GT(entries, 500);
}
