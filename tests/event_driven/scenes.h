// Starts for the engine's tests: scenes like the paper's, built here (the runs of the study take
// theirs from the decks).
#ifndef MN_TESTS_EVENT_DRIVEN_SCENES_H
#define MN_TESTS_EVENT_DRIVEN_SCENES_H

#include "start.h"

#include <string>

namespace scenes {

inline mn::ed::StartDisk disk(double x, double y, double vx, double vy, double omega,
                              double diameter)
{
  return {x, y, vx, vy, omega, diameter, "test disk"};
}

// A deterministic number in [0, 1) from two integers (the decks' kind of hash).
inline double hashed(long a, long b)
{
  return static_cast<double>((a * 7919 + b * 104729) % 10007) / 10007.0;
}

// The collisional flow's geometry (50 bumps 1.002 apart on L = 50.1, 50 disks at rest above the
// valleys at heights 2 to 6).
inline mn::ed::Start collisional(int seed)
{
  mn::ed::Start s;
  s.origin = "collisional test scene";
  s.xlo = 0.0;
  s.xhi = 50.1;
  for (int k = 0; k < 50; k++) s.bumps.push_back({k * 1.002, 0.0, 1.0, "test bump"});
  for (int k = 0; k < 50; k++)
    s.disks.push_back(disk(0.501 + k * 1.002, 2.0 + 4.0 * hashed(k + 51, seed), 0, 0, 0, 1.0));
  return s;
}

// The frictional flow's geometry (a flat floor, L = 10.02, 100 disks of diameters in
// [0.8, 1.0] in ten rows of ten, 4 apart, the top row raised at random).
inline mn::ed::Start frictional(int seed)
{
  mn::ed::Start s;
  s.origin = "frictional test scene";
  s.xlo = 0.0;
  s.xhi = 10.02;
  s.has_floor = true;
  s.floor_y = 0.0;
  for (int row = 0; row < 10; row++)
    for (int k = 0; k < 10; k++) {
      const int id = row * 10 + k;
      const double y = 0.6 + 4.0 * row + (row == 9 ? 2.0 * hashed(id, seed) : 0.0);
      s.disks.push_back(disk(0.501 + k * 1.002, y, 0, 0, 0, 0.8 + 0.2 * hashed(id + 1000, seed)));
    }
  return s;
}

}    // namespace scenes

#endif
