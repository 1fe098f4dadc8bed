// The event-driven engine of hard disks (docs/model.md section 8): disks of any sizes with
// rotation under gravity at the slope's inclination, periodic along the slope (x), on a flat
// floor and/or fixed bumps, colliding instantaneously by rule (a) or (b) of mn_collision.h.
//
// Between events every disk flies on its parabola. The engine keeps each disk's state at the
// time of its own last event (Lubachevsky's delayed states: an event touches only the disks it
// involves) and one predicted event per disk (the earliest of: a collision with a disk, the
// floor or a bump in its own or a neighbouring cell, or leaving its cell), in a tournament tree
// (event_tree.h), so that an event costs O(log N) plus the disks of 9 cells. A predicted
// collision with disk j is valid while j has had no collision since (its collision count then
// is still the one recorded); an invalid one makes the disk predict again. A collision with a
// disk is the root of a quadratic (their relative motion is free flight), with the floor of a
// quadratic, with a bump (fixed, while the disk falls) of a quartic, all found by entry_time.h,
// which takes only a gap that is closing: so a pair that has just collided is never found
// touching again, and a pair left overlapping by rounding while it approaches collides at once.
#ifndef MN_EVENT_DRIVEN_ENGINE_H
#define MN_EVENT_DRIVEN_ENGINE_H

#include "event_tree.h"
#include "settings.h"
#include "start.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace mn {
namespace ed {

// Partners of a collision: a disk's index (>= 0), the floor, or bump b as bump_partner(b).
constexpr int FLOOR = -1;
inline int bump_partner(int b) { return -2 - b; }
inline bool is_bump(int partner) { return partner <= -2; }
inline int bump_index(int partner) { return -2 - partner; }

// One collision, as an observer sees it: the contact velocity (mn_collision.h's conventions,
// n from the partner to disk i) before and after.
struct CollisionRecord {
  double time;
  int i, partner;
  ContactVelocity in, out;
  bool tc;    // made elastic by the TC model
};

// A detected inelastic collapse: a disk with more than collapse_count collisions within
// collapse_time.
struct CollapseReport {
  double time;             // of the collision that made the count
  int disk;
  int collisions;          // within the window that ends at `time`
  int grazing;             // of those, contacts closed without normal velocity (Totals::grazing)
  double first;            // the time of the window's first collision
  struct Partner {
    int partner;           // as in CollisionRecord
    int collisions;        // with the disk, within the window
  };
  std::vector<Partner> partners;
  std::string describe() const;
};

// What the run has done so far.
struct Totals {
  std::uint64_t events = 0;               // collisions, cell crossings and grazing contacts
  std::uint64_t disk_collisions = 0;      // each counted once (it involves two disks)
  std::uint64_t boundary_collisions = 0;  // with the floor or a bump
  std::uint64_t tc_collisions = 0;        // of those, made elastic by the TC model
  std::uint64_t cell_crossings = 0;
  std::uint64_t invalid_predictions = 0;  // events found stale and predicted again
  std::uint64_t grazing = 0;              // predicted contacts found not approaching (rounding):
                                          // disks then fly apart; with the boundary they
                                          // count towards a collapse
  double largest_overlap = 0.0;           // the largest overlap at a collision, / contact distance
};

// A disk's motion at a time.
struct DiskState {
  double x, y, vx, vy, omega;    // x unwrapped (periodic images counted)
};

class Engine {
 public:
  // Checks the start against the settings and builds the engine at time 0. Throws InputError
  // for a start the engine refuses (naming the disk or bump and its origin): a disk outside the
  // box or below the floor, two disks overlapping, a disk inside a bump, no disks, a box too
  // short for the cells (3 contact distances).
  Engine(const Start &start, const Settings &settings);
  ~Engine();

  enum class Stop { Time, Events, Collapse };
  // Processes events up to time t_end (the disks are then at t_end: state() gives them) or
  // until `max_events` more events (0: no limit), or a detected collapse.
  Stop run(double t_end, std::uint64_t max_events = 0);

  double time() const { return epoch_ + now_; }
  double box_length() const { return length_; }
  int disks() const { return static_cast<int>(disk_.size()); }
  DiskState state(int i) const;    // at time()
  double radius(int i) const { return disk_[i].radius; }
  double mass(int i) const { return disk_[i].mass; }
  double inertia(int i) const { return disk_[i].inertia; }
  const Totals &totals() const { return totals_; }
  const CollapseReport *collapse() const { return collapse_.get(); }
  // per disk: collisions with disks, with the boundary, and of those made elastic by TC
  std::uint64_t disk_collisions_of(int i) const { return disk_[i].disk_collisions; }
  std::uint64_t boundary_collisions_of(int i) const { return disk_[i].boundary_collisions; }

  // Called after every collision.
  void set_observer(std::function<void(const CollisionRecord &)> observer) { observer_ = observer; }

  // The largest overlap between any two disks or a disk and the boundary at time(), over the
  // contact distance (0 if none): an O(N) check through the cells, for tests.
  double largest_overlap_now() const;

  // The kinetic energy (translational, rotational) summed over the disks at time().
  void kinetic_energy(double *translational, double *rotational) const;

 private:
  enum class Kind : unsigned char { None, Disk, Floor, Bump, Cross };
  struct Event {
    double time;
    Kind kind;
    int partner;                    // disk, bump, or the crossing's direction
    std::uint64_t partner_collisions;
  };
  struct Disk {
    double x, y, vx, vy, omega;     // at time t; x in [0, L) to rounding (the box from xlo)
    double t;
    double radius, mass, inertia;
    int cell, slot;
    long long image;                // periodic images crossed
    std::uint64_t collisions;       // changes of trajectory
    int last_partner;               // of the last collision (none: a value no partner has)
    long long last_encounter;       // with a disk: which periodic image of it (image difference)
    double last_collision;
    std::uint64_t disk_collisions, boundary_collisions;
  };
  struct FixedDisk {
    double x, y, radius;
    int cell;
  };
  struct Flight {
    double x, y, vx, vy;
  };

  Flight flight(const Disk &d, double t) const;
  void advance(Disk &d, double t) const;
  int cell_of(double x, double y) const;
  void add_rows_to(int row);
  void place(int i, int cell);
  void unplace(int i);
  void predict(int i);
  void collide_disks(int i, int j);
  void collide_boundary(int i, int partner);
  void cross(int i, int direction);
  void rebase();
  Impulse impulse(const ContactVelocity &in, double reduced_mass, double q, bool boundary,
                  bool elastic) const;

  Settings settings_;
  double xlo_, length_;
  double gx_, gy_;
  bool has_floor_;
  double floor_y_;
  int nx_, rows_;
  double cell_width_, cell_height_, y0_;
  std::vector<Disk> disk_;
  std::vector<FixedDisk> bump_;
  std::vector<std::vector<int>> cell_disks_, cell_bumps_;
  std::vector<Event> event_;
  EventTree tree_;
  // Times are kept from an epoch that moves up with the run (rebase()), so that a time's
  // rounding stays that of a number of order 1, not of the run's length: a disk's place at an
  // event is then off by ~1e-16 of its speed times a time unit, at t = 1e4 as at t = 1.
  double epoch_ = 0.0;
  double now_ = 0.0;    // from epoch_
  Totals totals_;
  std::shared_ptr<const SoftLimitTable> disk_table_, boundary_table_;
  std::function<void(const CollisionRecord &)> observer_;
  class CollapseDetector;
  std::unique_ptr<CollapseDetector> detector_;
  std::unique_ptr<CollapseReport> collapse_;
};

}    // namespace ed
}    // namespace mn

#endif
