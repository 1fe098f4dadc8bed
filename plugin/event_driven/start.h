// A run's start: the box (periodic in x), the flat floor if any, the disks (mobile) and the
// bumps (disks fixed on the slope), as the event-driven engine reads them, with where each came
// from so that a refusal can name it.
#ifndef MN_EVENT_DRIVEN_START_H
#define MN_EVENT_DRIVEN_START_H

#include <stdexcept>
#include <string>
#include <vector>

namespace mn {
namespace ed {

// A refused input: the message names the input (a file and line, or a parameter) and says what
// is wrong with it and what is accepted.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string &what) : std::runtime_error(what) {}
};

struct StartDisk {
  double x, y, vx, vy, omega, diameter;
  std::string origin;    // where it was read: "FILE line N"
};

struct Bump {
  double x, y, diameter;
  std::string origin;
};

struct Start {
  double xlo = 0.0, xhi = 0.0;    // the periodic box along the slope
  bool has_floor = false;
  double floor_y = 0.0;           // the flat wall (a disk touches it when y - radius = floor_y)
  std::vector<StartDisk> disks;
  std::vector<Bump> bumps;
  std::string origin;             // the file, or what built the start
};

// Reads a start file of lines (blank lines and # comments ignored):
//   box XLO XHI                    the periodic box along the slope (once, required)
//   floor Y                        a flat wall at y = Y (at most once)
//   disk X Y VX VY OMEGA DIAMETER  a mobile disk
//   bump X Y DIAMETER              a fixed disk of the slope
// Throws InputError naming the file and line for an unknown line, a missing or extra value,
// a value that is not a finite number, or a diameter that is not > 0.
Start read_start(const std::string &path);

}    // namespace ed
}    // namespace mn

#endif
