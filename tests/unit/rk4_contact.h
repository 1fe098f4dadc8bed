// RK4 through one contact, for the unit tests' reference integrations (disks in 2D, spheres in
// 3D), of a scene type S with
//   rates(s)          its time derivatives
//   advance(s, d, h)  s + h d (linear in d)
//   overlap(s)        the contact's overlap (> 0 while in contact)
#ifndef GRANMN_TESTS_RK4_CONTACT_H
#define GRANMN_TESTS_RK4_CONTACT_H

#include <gtest/gtest.h>

// One classical Runge-Kutta step written with advance alone: since advance is linear in d,
// stepping by h/6 k1, h/3 k2, h/3 k3, h/6 k4 in turn is RK4's weighted sum.
template <class S, class Rates, class Advance>
S rk4_step(const S &s, double h, Rates rates, Advance advance)
{
  const auto k1 = rates(s);
  const auto k2 = rates(advance(s, k1, 0.5 * h));
  const auto k3 = rates(advance(s, k2, 0.5 * h));
  const auto k4 = rates(advance(s, k3, h));
  S next = advance(s, k1, h / 6);
  next = advance(next, k2, h / 3);
  next = advance(next, k3, h / 3);
  return advance(next, k4, h / 6);
}

// Steps of h through the whole contact (step(s, h): the scene a step later, e.g. rk4_step);
// returns the contact's duration (the overlap's zeros, interpolated linearly within a step) and
// leaves s after separation.
template <class S, class Step, class Overlap>
double contact_duration(S &s, double h, Step step, Overlap overlap)
{
  double t = 0.0, t_start = -1.0;
  for (int n = 0; n < 4000000; n++) {
    const double before = overlap(s);
    s = step(s, h);
    const double after = overlap(s);
    if (before <= 0 && after > 0) t_start = t + h * (-before) / (after - before);
    t += h;
    if (t_start >= 0 && before > 0 && after <= 0)
      return t - h + h * before / (before - after) - t_start;
  }
  ADD_FAILURE() << "contact never ended";
  return 0.0;
}

#endif
