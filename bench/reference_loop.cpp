// A minimal hand-written loop with the same contact law (mn_contact.h) for the two flowing
// scenes of inputs/: what a step costs without LAMMPS, the yardstick of bench/run_benchmarks.py.
//
//   reference-loop frictional|collisional KN DT_FRACTION WARMUP_TIME MEASURED_STEPS [SEED]
//
// The scenes are built as the decks build them (same sizes, start, slope, wall or bumps); the
// step is velocity Verlet as fix nve/disc/mn does it (forces see the half-step velocity, gravity
// is added to the force sum, the mass factors are computed once);
// the neighbour list is a binned half list with a 0.2 skin, rebuilt when a disk has moved
// half the skin, carrying each contact's u_t over. It keeps no counters and writes no output:
// it prints CPU us/step over MEASURED_STEPS after WARMUP_TIME, with the mean contacts per step
// and the mean kinetic energy per disk over those steps (to show that the scene flows).
#include "mn_contact.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <unordered_map>
#include <utility>
#include <vector>

namespace {

constexpr double SKIN = 0.2;

struct Pair {
  int i, j;
  double shift;    // x image of j seen from i (0 or +-L), fixed between rebuilds
  double ut;       // tangential displacement, 0 while not touching
};

struct Scene {
  double length;                       // periodic in x
  double sin_theta;
  bool flat_wall;                      // frictional: a wall at y = 0; collisional: bumps
  int n, n_mobile;                     // mobile disks first, then fixed bumps
  std::vector<double> x, y, vx, vy, w, radius, mass;
  std::vector<double> fx, fy, torque, wall_ut;
};

double hash(long a, long b)
{
  return double((a + b) % 10007) / 10007.0;
}

// inputs/frictional_flow.lmp: ten rows of ten, rows 4 apart, the top row raised by up to 2.
Scene frictional(long seed)
{
  Scene s;
  s.length = 10.02;
  s.sin_theta = 0.20;
  s.flat_wall = true;
  for (int id = 1; id <= 100; id++) {
    const int col = (id - 1) % 10, row = (id - 1) / 10;
    const double d = 0.8 + 0.2 * hash(id * 7919L, seed * 104729L);
    double y = 4.0 * (row + 0.5);
    if (id > 90) y += 2.0 * hash(id * 104729L, seed * 7919L);
    s.x.push_back(1.002 * (col + 0.5));
    s.y.push_back(y);
    s.radius.push_back(0.5 * d);
    s.mass.push_back(d * d);    // density 4/pi per unit area
  }
  s.n = s.n_mobile = 100;
  return s;
}

// inputs/collisional_flow.lmp: 50 unit disks above the valleys of 50 fixed unit bumps.
Scene collisional(long seed)
{
  Scene s;
  s.length = 50.1;
  s.sin_theta = 0.45;
  s.flat_wall = false;
  for (int k = 0; k < 50; k++) {
    const long id = 51 + k;    // the deck creates the bumps first
    s.x.push_back(1.002 * (k + 0.5));
    s.y.push_back(2.0 + 4.0 * hash(id * 7919L, seed * 104729L));
  }
  for (int k = 0; k < 50; k++) {
    s.x.push_back(1.002 * k);
    s.y.push_back(0.0);
  }
  s.n = 100;
  s.n_mobile = 50;
  s.radius.assign(s.n, 0.5);
  s.mass.assign(s.n, 1.0);
  return s;
}

class Loop {
 public:
  Loop(Scene scene, const mn::Law &law, double dt) : s(std::move(scene)), law(law), dt(dt)
  {
    s.vx.assign(s.n, 0.0);
    s.vy.assign(s.n, 0.0);
    s.w.assign(s.n, 0.0);
    s.fx.assign(s.n, 0.0);
    s.fy.assign(s.n, 0.0);
    s.torque.assign(s.n, 0.0);
    s.wall_ut.assign(s.n, 0.0);
    gx = s.sin_theta;
    gy = -std::sqrt(1.0 - s.sin_theta * s.sin_theta);
    // 1/m and r^2/2 once (fix nve/disc/mn keeps its factors too); the same values as
    // computed at every step before, so the same trajectory
    for (int i = 0; i < s.n_mobile; i++) {
      inv_mass.push_back(1.0 / s.mass[i]);
      half_r2.push_back(0.5 * s.radius[i] * s.radius[i]);
    }
    rebuild();
    forces();
  }

  void step()
  {
    const double half = 0.5 * dt;
    for (int i = 0; i < s.n_mobile; i++) {
      s.vx[i] += half * s.fx[i] * inv_mass[i];
      s.vy[i] += half * s.fy[i] * inv_mass[i];
      s.w[i] += half * s.torque[i] * inv_mass[i] / half_r2[i];
      s.x[i] += dt * s.vx[i];
      s.y[i] += dt * s.vy[i];
    }
    if (moved_half_skin()) rebuild();
    forces();
    for (int i = 0; i < s.n_mobile; i++) {
      s.vx[i] += half * s.fx[i] * inv_mass[i];
      s.vy[i] += half * s.fy[i] * inv_mass[i];
      s.w[i] += half * s.torque[i] * inv_mass[i] / half_r2[i];
    }
  }

  long contacts = 0;    // summed over steps, for the mean
  int rebuilds = 0;

  double kinetic_energy_per_disk() const
  {
    double e = 0.0;
    for (int i = 0; i < s.n_mobile; i++)
      e += 0.5 * s.mass[i] * (s.vx[i] * s.vx[i] + s.vy[i] * s.vy[i]) +
          0.25 * s.mass[i] * s.radius[i] * s.radius[i] * s.w[i] * s.w[i];
    return e / s.n_mobile;
  }

 private:
  Scene s;
  mn::Law law;
  double dt, gx, gy;
  std::vector<double> inv_mass, half_r2;    // per mobile disk
  std::vector<Pair> pairs;
  std::vector<double> x_built, y_built;

  bool moved_half_skin() const
  {
    const double limit = 0.25 * SKIN * SKIN;
    for (int i = 0; i < s.n_mobile; i++) {
      const double dx = s.x[i] - x_built[i], dy = s.y[i] - y_built[i];
      if (dx * dx + dy * dy > limit) return true;
    }
    return false;
  }

  // Wrap x into the box, bin the disks, list every pair within contact distance + skin once;
  // a pair that was touching keeps its u_t.
  void rebuild()
  {
    rebuilds++;
    std::unordered_map<long, double> history;
    for (const Pair &p : pairs)
      if (p.ut != 0.0) history[long(p.i) * s.n + p.j] = p.ut;
    for (int i = 0; i < s.n; i++) s.x[i] -= s.length * std::floor(s.x[i] / s.length);
    x_built = s.x;
    y_built = s.y;

    double max_radius = 0.0, ylo = s.y[0], yhi = s.y[0];
    for (int i = 0; i < s.n; i++) {
      max_radius = std::max(max_radius, s.radius[i]);
      ylo = std::min(ylo, s.y[i]);
      yhi = std::max(yhi, s.y[i]);
    }
    const double cut = 2.0 * max_radius + SKIN;
    const int nbx = std::max(3, int(s.length / cut));
    const int nby = int((yhi - ylo) / cut) + 1;
    const double bx = s.length / nbx;
    std::vector<std::vector<int>> bins(nbx * nby);
    auto bin_x = [&](int i) { return std::min(nbx - 1, int(s.x[i] / bx)); };
    auto bin_y = [&](int i) { return std::min(nby - 1, int((s.y[i] - ylo) / cut)); };
    for (int i = 0; i < s.n; i++) bins[bin_y(i) * nbx + bin_x(i)].push_back(i);

    pairs.clear();
    for (int i = 0; i < s.n; i++) {
      const int cx = bin_x(i), cy = bin_y(i);
      for (int oy = -1; oy <= 1; oy++) {
        if (cy + oy < 0 || cy + oy >= nby) continue;
        for (int ox = -1; ox <= 1; ox++) {
          const int wx = (cx + ox + nbx) % nbx;
          for (int j : bins[(cy + oy) * nbx + wx]) {
            if (j <= i || (i >= s.n_mobile && j >= s.n_mobile)) continue;
            double dx = s.x[i] - s.x[j];
            const double shift = dx > 0.5 * s.length ? s.length : dx < -0.5 * s.length ? -s.length : 0.0;
            dx -= shift;
            const double dy = s.y[i] - s.y[j];
            const double reach = s.radius[i] + s.radius[j] + SKIN;
            if (dx * dx + dy * dy >= reach * reach) continue;
            // nbx = 3 visits a neighbouring bin twice: keep the first
            bool listed = false;
            for (size_t k = pairs.size(); k-- > 0 && pairs[k].i == i;)
              if (pairs[k].j == j) listed = true;
            if (listed) continue;
            const auto kept = history.find(long(i) * s.n + j);
            pairs.push_back({i, j, shift, kept == history.end() ? 0.0 : kept->second});
          }
        }
      }
    }
  }

  void forces()
  {
    for (int i = 0; i < s.n; i++) s.fx[i] = s.fy[i] = s.torque[i] = 0.0;
    int touching = 0;
    for (Pair &p : pairs) {
      const int i = p.i, j = p.j;
      const double dx = s.x[i] - s.x[j] - p.shift, dy = s.y[i] - s.y[j];
      const double rsq = dx * dx + dy * dy;
      const double radsum = s.radius[i] + s.radius[j];
      if (rsq >= radsum * radsum) {
        p.ut = 0.0;
        continue;
      }
      touching++;
      const double r = std::sqrt(rsq);
      const mn::Kinematics kin = mn::kinematics(dx, dy, r, radsum, s.vx[i] - s.vx[j],
                                                s.vy[i] - s.vy[j],
                                                s.radius[i] * s.w[i] + s.radius[j] * s.w[j]);
      // a bump (index >= n_mobile, always j) is boundary: mass scale m_i
      const double scale = j >= s.n_mobile ? mn::boundary_mass_scale(s.mass[i])
                                           : mn::pair_mass_scale(s.mass[i], s.mass[j]);
      const mn::Force fc = mn::contact_force(law, scale, kin, &p.ut, dt);
      const mn::Cartesian f = mn::cartesian(kin, fc);
      s.fx[i] += f.fx;
      s.fy[i] += f.fy;
      s.torque[i] += mn::torque(fc, s.radius[i]);
      s.fx[j] -= f.fx;
      s.fy[j] -= f.fy;
      s.torque[j] += mn::torque(fc, s.radius[j]);
    }
    for (int i = 0; i < s.n_mobile; i++) {
      s.fx[i] += s.mass[i] * gx;
      s.fy[i] += s.mass[i] * gy;
      if (!s.flat_wall) continue;
      if (s.y[i] >= s.radius[i]) {
        s.wall_ut[i] = 0.0;
        continue;
      }
      touching++;
      const mn::Kinematics kin =
          mn::kinematics(0.0, s.y[i], s.y[i], s.radius[i], s.vx[i], s.vy[i], s.radius[i] * s.w[i]);
      const mn::Force fc = mn::contact_force(law, mn::boundary_mass_scale(s.mass[i]), kin,
                                             &s.wall_ut[i], dt);
      const mn::Cartesian f = mn::cartesian(kin, fc);
      s.fx[i] += f.fx;
      s.fy[i] += f.fy;
      s.torque[i] += mn::torque(fc, s.radius[i]);
    }
    contacts += touching;
  }
};

}    // namespace

int main(int argc, char **argv)
{
  if (argc < 6 || (strcmp(argv[1], "frictional") != 0 && strcmp(argv[1], "collisional") != 0)) {
    fprintf(stderr, "usage: %s frictional|collisional KN DT_FRACTION WARMUP_TIME MEASURED_STEPS "
                    "[SEED]\n", argv[0]);
    return 2;
  }
  const bool is_frictional = strcmp(argv[1], "frictional") == 0;
  const double kn = atof(argv[2]), dt_fraction = atof(argv[3]), warmup_time = atof(argv[4]);
  const long measured = atol(argv[5]);
  const long seed = argc > 6 ? atol(argv[6]) : 2003;
  const mn::Law law = mn::derive({kn, 0.7, 0.7, 0.5});
  const double dt = std::min(dt_fraction * law.tau_c, 1e-4);    // as the decks choose it

  Loop loop(is_frictional ? frictional(seed) : collisional(seed), law, dt);
  const long warmup = long(std::ceil(warmup_time / dt));
  for (long k = 0; k < warmup; k++) loop.step();
  loop.contacts = 0;
  double energy = 0.0;
  int samples = 0;
  const std::clock_t start = std::clock();    // CPU time, as bench/run_benchmarks.py takes it
  for (long k = 0; k < measured; k++) {
    loop.step();
    if (k % 1000 == 0) {
      energy += loop.kinetic_energy_per_disk();
      samples++;
    }
  }
  const double seconds = double(std::clock() - start) / CLOCKS_PER_SEC;
  printf("us_per_step %.4f contacts_per_step %.2f energy_per_disk %.4f steps %ld dt %.6g "
         "rebuilds %d\n", 1e6 * seconds / measured, double(loop.contacts) / measured,
         energy / samples, measured, dt, loop.rebuilds);
  return 0;
}
