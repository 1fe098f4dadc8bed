// One soft collision of two free disks (or a disk and a flat wall y = 0) integrated in full 2D
// with the law of mn_contact.h (the line of centres turns, no gravity), by RK4 with steps of
// duration/resolution, the contact's end located within its last step by bisection on the
// step's length (the force continued across the end within that step, so that the step stays
// smooth), and steps cut where F_n changes sign; u_t is kept as the law keeps it after each step (cut back while sliding under
// the cut-back reading). The reference the hard limit (rule (b)) is approached by.
#ifndef MN_TESTS_EVENT_DRIVEN_SOFT_COLLISION_H
#define MN_TESTS_EVENT_DRIVEN_SOFT_COLLISION_H

#include "mn_collision.h"

#include <cmath>

namespace soft {

struct Disk {
  double x, y, vx, vy, w;
  double m, r;
  double inertia() const { return 0.5 * m * r * r; }
};

// disk a against disk b, a bump (b fixed: a disk of the slope) or the wall (b unused); ut is
// the contact's u_t
struct Scene {
  Disk a, b;
  bool wall = false;
  bool bump = false;
  double ut = 0.0;
};

inline mn::Kinematics kinematics(const Scene &s, double *mass_scale)
{
  if (s.wall) {
    *mass_scale = mn::boundary_mass_scale(s.a.m);
    return mn::kinematics(0.0, s.a.y, s.a.y, s.a.r, s.a.vx, s.a.vy, s.a.r * s.a.w);
  }
  const double dx = s.a.x - s.b.x, dy = s.a.y - s.b.y;
  *mass_scale = s.bump ? mn::boundary_mass_scale(s.a.m) : mn::pair_mass_scale(s.a.m, s.b.m);
  return mn::kinematics(dx, dy, std::hypot(dx, dy), s.a.r + s.b.r, s.a.vx - s.b.vx,
                        s.a.vy - s.b.vy, s.a.r * s.a.w + s.b.r * s.b.w);
}

// the contact velocity (n from b, or the wall, to a)
inline mn::ContactVelocity contact_velocity(const Scene &s)
{
  double scale;
  const mn::Kinematics k = kinematics(s, &scale);
  return {k.vn, k.vt};
}

struct Rates {
  double vx[2], vy[2], ax[2], ay[2], alpha[2], dut;
};

inline Rates rates(const mn::Law &law, const Scene &s)
{
  Rates d{{s.a.vx, s.b.vx}, {s.a.vy, s.b.vy}, {0, 0}, {0, 0}, {0, 0}, 0};
  double scale;
  // in contact throughout: the force from the touching start (where the dashpot already acts)
  // to the end, continued across it within the last step so that the step stays smooth
  const mn::Kinematics k = kinematics(s, &scale);
  double ut = s.ut;
  const mn::Force f = mn::contact_force(law, scale, k, law.material.mu > 0 ? &ut : nullptr, 0.0);
  const mn::Cartesian c = mn::cartesian(k, f);
  d.ax[0] = c.fx / s.a.m;
  d.ay[0] = c.fy / s.a.m;
  d.alpha[0] = mn::torque(f, s.a.r) / s.a.inertia();
  if (!s.wall && !s.bump) {
    d.ax[1] = -c.fx / s.b.m;
    d.ay[1] = -c.fy / s.b.m;
    d.alpha[1] = mn::torque(f, s.b.r) / s.b.inertia();
  }
  d.dut = k.vt;
  return d;
}

inline Scene advance(const Scene &s, const Rates &d, double h)
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

inline Scene step(const mn::Law &law, const Scene &s, double h)
{
  auto r = [&](const Scene &q) { return rates(law, q); };
  const Rates k1 = r(s), k2 = r(advance(s, k1, h / 2)), k3 = r(advance(s, k2, h / 2)),
              k4 = r(advance(s, k3, h));
  Scene n = advance(s, k1, h / 6);
  n = advance(n, k2, h / 3);
  n = advance(n, k3, h / 3);
  n = advance(n, k4, h / 6);
  double scale;
  const mn::Kinematics k = kinematics(n, &scale);
  if (law.material.mu > 0) mn::contact_force(law, scale, k, &n.ut, 0.0);
  return n;
}

inline double overlap(const Scene &s)
{
  double scale;
  return kinematics(s, &scale).delta;
}

inline double normal_force(const mn::Law &law, const Scene &s)
{
  double scale;
  const mn::Kinematics k = kinematics(s, &scale);
  return mn::normal_force(law, scale, k);
}

// Integrates from a touching start (overlap 0, approaching) to the contact's end; returns the
// scene at the end. A step in which F_n changes sign is cut there (bisection on its length):
// the cut-back cap closes to 0 at that instant, which a step across it would smear.
inline Scene collide(const mn::Law &law, Scene s, double duration, double resolution)
{
  const double h = duration / resolution;
  auto sign = [](double x) { return (x > 0.0) - (x < 0.0); };
  int fn_sign = 0;
  for (long n = 0; n < 10 * static_cast<long>(resolution); n++) {
    auto passed = [&](const Scene &e) {
      const int now = sign(normal_force(law, e));
      return !(overlap(e) > 0.0) || (fn_sign != 0 && now != 0 && now != fn_sign);
    };
    Scene next = step(law, s, h);
    if (passed(next)) {
      double lo = 0.0, hi = h;
      for (int iter = 0; iter < 80; iter++) {
        const double mid = 0.5 * (lo + hi);
        if (!(mid > lo && mid < hi)) break;
        const Scene m = step(law, s, mid);
        if (passed(m)) {
          hi = mid;
          next = m;
        } else {
          lo = mid;
        }
      }
    }
    if (!(overlap(next) > 0.0)) return next;
    s = next;
    const int now = sign(normal_force(law, s));
    if (now != 0) fn_sign = now;
  }
  return s;
}

inline Disk disk(double diameter, double x, double y, double vx, double vy, double w = 0.0)
{
  return Disk{x, y, vx, vy, w, diameter * diameter, 0.5 * diameter};
}

}    // namespace soft

#endif
