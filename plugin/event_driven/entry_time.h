// When a gap closes: the earliest time tau >= 0 at which a polynomial gap function q(tau) is
// <= 0 while decreasing, for the event-driven engine's predictions (a disk meeting a disk, the
// floor, a bump, a cell's side). Taking only a closing gap (q' < 0) is what keeps touching pairs
// apart: just after a collision the gap is 0 to rounding but opening, and its root at ~0 is not
// an entry; a gap that rounding has left slightly negative while it closes is an entry now.
// Precisely, the result is the infimum of {tau >= 0 : q(tau) <= 0 and q'(tau) < 0}, or infinity.
#ifndef MN_EVENT_DRIVEN_ENTRY_TIME_H
#define MN_EVENT_DRIVEN_ENTRY_TIME_H

#include <cmath>
#include <limits>

namespace mn {
namespace ed {

constexpr double NEVER = std::numeric_limits<double>::infinity();

// q(tau) = c0 + c1 tau + c2 tau^2, in closed forms chosen so that no root is a difference of
// nearly equal numbers.
inline double quadratic_entry(double c0, double c1, double c2)
{
  if (c2 > 0.0) {    // convex: decreasing only before its vertex
    if (!(c1 < 0.0)) return NEVER;
    if (c0 <= 0.0) return 0.0;
    const double d = c1 * c1 - 4.0 * c0 * c2;
    if (d < 0.0) return NEVER;    // the gap's minimum stays open
    return 2.0 * c0 / (-c1 + std::sqrt(d));
  }
  if (c2 < 0.0) {    // concave: decreasing after its vertex, and closing in the end
    const double a = -c2;
    const double d = c1 * c1 + 4.0 * c0 * a;
    if (c0 > 0.0) return c1 >= 0.0 ? (c1 + std::sqrt(d)) / (2.0 * a) : 2.0 * c0 / (std::sqrt(d) - c1);
    if (c1 < 0.0) return 0.0;
    // closed (to rounding) but opening: an entry at the vertex if it never opens, else where
    // it closes again
    if (d < 0.0) return c1 / (2.0 * a);
    return (c1 + std::sqrt(d)) / (2.0 * a);
  }
  if (!(c1 < 0.0)) return NEVER;
  return c0 <= 0.0 ? 0.0 : -c0 / c1;
}

namespace detail {

// p(x) = c[0] + c[1] x + ... + c[deg] x^deg
inline double evaluate(const double *c, int deg, double x)
{
  double v = c[deg];
  for (int k = deg - 1; k >= 0; k--) v = v * x + c[k];
  return v;
}

// The root of p in [a, b], where p(a) and p(b) have opposite signs (or one is 0): bisection
// to the last bit.
inline double bisect(const double *c, int deg, double a, double b)
{
  double pa = evaluate(c, deg, a);
  if (pa == 0.0) return a;
  for (int iter = 0; iter < 200; iter++) {
    const double m = 0.5 * (a + b);
    if (!(m > a && m < b)) break;
    const double pm = evaluate(c, deg, m);
    if (pm == 0.0) return m;
    if ((pm < 0.0) == (pa < 0.0)) {
      a = m;
      pa = pm;
    } else {
      b = m;
    }
  }
  return b;
}

// The points in (a, b) where p changes sign, ascending, into out (at most deg); their count.
// Between consecutive roots of p' the polynomial is monotone, so each sign change is bracketed
// by them and none is missed (a root of even multiplicity, p touching 0, is not a sign change).
inline int sign_changes(const double *c, int deg, double a, double b, double *out)
{
  while (deg > 0 && c[deg] == 0.0) deg--;
  if (deg == 0) return 0;
  double breaks[6];
  int n = 0;
  breaks[n++] = a;
  if (deg >= 2) {
    double d[4];
    for (int k = 1; k <= deg; k++) d[k - 1] = k * c[k];
    n += sign_changes(d, deg - 1, a, b, breaks + 1);
  }
  breaks[n++] = b;
  int found = 0;
  for (int k = 0; k + 1 < n; k++) {
    const double lo = breaks[k], hi = breaks[k + 1];
    const double plo = evaluate(c, deg, lo), phi = evaluate(c, deg, hi);
    if ((plo < 0.0 && phi > 0.0) || (plo > 0.0 && phi < 0.0)) {
      const double r = bisect(c, deg, lo, hi);
      if (r > a && r < b) out[found++] = r;
    }
  }
  return found;
}

}    // namespace detail

// The entry time of a quartic gap q (coefficients c[0..4], any of the top ones may be 0)
// within [0, horizon] (finite), or NEVER if it does not close there. The interval is cut at the
// roots of q' (found by the same bracketing one degree down), so that q is monotone on each
// piece: on the first decreasing piece [a, b] with q(b) <= 0 the entry is a if q(a) <= 0, else
// q's root in (a, b], found by bisection.
inline double quartic_entry(const double c[5], double horizon)
{
  double cuts[6];
  int n = 0;
  cuts[n++] = 0.0;
  double d[4];
  for (int k = 1; k <= 4; k++) d[k - 1] = k * c[k];
  n += detail::sign_changes(d, 3, 0.0, horizon, cuts + 1);
  cuts[n++] = horizon;
  for (int k = 0; k + 1 < n; k++) {
    const double a = cuts[k], b = cuts[k + 1];
    const double qa = detail::evaluate(c, 4, a), qb = detail::evaluate(c, 4, b);
    // decreasing on the piece: q' < 0 inside (tested in the middle, away from the cuts)
    if (!(detail::evaluate(d, 3, 0.5 * (a + b)) < 0.0)) continue;
    if (qa <= 0.0) return a;
    if (qb <= 0.0) return detail::bisect(c, 4, a, b);
  }
  return NEVER;
}

}    // namespace ed
}    // namespace mn

#endif
