#include "engine.h"

#include "entry_time.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace mn {
namespace ed {

namespace {

// Starts may have disks touching (the file's decimals rounded): an overlap up to this, in
// units of the contact distance, is a touch; more is refused.
constexpr double START_TOUCH = 1e-10;

// Cells are wider than the largest contact distance by this factor, so that positions off
// their cell by rounding still meet only disks of neighbouring cells.
constexpr double CELL_MARGIN = 1.0 + 1e-9;

constexpr int NO_PARTNER = INT_MIN;

// The epoch moves up to the present whenever that is more than this many time units from it.
constexpr double REBASE_AFTER = 1.0;

// Rule (b)'s tables depend on e, beta, mu, the u_t reading and the partner only: built once per
// process for each.
std::shared_ptr<const SoftLimitTable> soft_table(const Law &law, Partner partner)
{
  static std::map<std::tuple<double, double, double, bool, int>, std::shared_ptr<const SoftLimitTable>>
      tables;
  const auto key = std::make_tuple(law.material.e, law.material.beta, law.material.mu,
                                   law.options.coulomb_cutback, static_cast<int>(partner));
  auto found = tables.find(key);
  if (found != tables.end()) return found->second;
  auto table = std::make_shared<const SoftLimitTable>(law, partner);
  tables.emplace(key, table);
  return table;
}

std::string partner_name(int partner)
{
  if (partner == FLOOR) return "the floor";
  if (is_bump(partner)) return "bump " + std::to_string(bump_index(partner));
  return "disk " + std::to_string(partner);
}

}    // namespace

// Per disk, its collisions within the last collapse_time (kept only while they come that
// close: a disk that collides rarely holds one entry).
class Engine::CollapseDetector {
 public:
  CollapseDetector(int disks, int count, double window)
      : recent_(disks), count_(count), window_(window)
  {
  }

  // Records a collision; true when the disk has had more than `count` within the window.
  bool record(int disk, double t, int partner, bool grazing = false)
  {
    Recent &r = recent_[disk];
    if (!r.hits.empty() && t - r.hits.back().time > window_) {
      r.hits.clear();
      r.head = 0;
    }
    r.hits.push_back({t, partner, grazing});
    while (t - r.hits[r.head].time > window_) r.head++;
    if (r.head > 64 && 2 * r.head > r.hits.size()) {
      r.hits.erase(r.hits.begin(), r.hits.begin() + static_cast<long>(r.head));
      r.head = 0;
    }
    return static_cast<long>(r.hits.size() - r.head) > count_;
  }

  // Moves every recorded time back by `shift` (a new epoch).
  void shift(double by)
  {
    for (Recent &r : recent_)
      for (Hit &h : r.hits) h.time -= by;
  }

  // The report of a collapse of `disk` at local time t; epoch: the time local times start from.
  CollapseReport report(int disk, double t, double epoch) const
  {
    const Recent &r = recent_[disk];
    CollapseReport c;
    c.time = epoch + t;
    c.disk = disk;
    c.collisions = static_cast<int>(r.hits.size() - r.head);
    c.first = epoch + r.hits[r.head].time;
    std::map<int, int> partners;
    c.grazing = 0;
    for (std::size_t k = r.head; k < r.hits.size(); k++) {
      partners[r.hits[k].partner]++;
      c.grazing += r.hits[k].grazing;
    }
    for (const auto &p : partners) c.partners.push_back({p.first, p.second});
    return c;
  }

 private:
  struct Hit {
    double time;
    int partner;
    bool grazing;
  };
  struct Recent {
    std::vector<Hit> hits;
    std::size_t head = 0;
  };
  std::vector<Recent> recent_;
  long count_;
  double window_;
};

std::string CollapseReport::describe() const
{
  std::ostringstream out;
  out.precision(17);
  out << "inelastic collapse at t = " << time << ": disk " << disk << " had " << collisions
      << " collisions within " << time - first << " (from t = " << first << ")";
  if (grazing)
    out << ", " << grazing << " of them grazing (a closed gap without normal velocity left to"
        << " rounding: a lasting contact)";
  out << "; partners:";
  for (std::size_t k = 0; k < partners.size(); k++)
    out << (k ? "," : "") << " " << partner_name(partners[k].partner) << " x "
        << partners[k].collisions;
  return out.str();
}

Engine::Engine(const Start &start, const Settings &settings)
    : settings_(settings), tree_(std::max<int>(1, static_cast<int>(start.disks.size())))
{
  if (start.disks.empty()) throw InputError(start.origin + ": the start has no disks");
  xlo_ = start.xlo;
  length_ = start.xhi - start.xlo;
  const double cos_theta = std::sqrt(std::max(0.0, 1.0 - settings.sin_theta * settings.sin_theta));
  gx_ = settings.g * settings.sin_theta;
  gy_ = -settings.g * cos_theta;
  has_floor_ = start.has_floor;
  floor_y_ = start.floor_y;

  double largest_disk = 0.0, largest_bump = 0.0;
  for (const StartDisk &d : start.disks) largest_disk = std::max(largest_disk, 0.5 * d.diameter);
  for (const Bump &b : start.bumps) largest_bump = std::max(largest_bump, 0.5 * b.diameter);
  const double contact = largest_disk + std::max(largest_disk, largest_bump);
  nx_ = static_cast<int>(std::floor(length_ / (contact * CELL_MARGIN)));
  if (nx_ < 3) {
    std::ostringstream m;
    m << start.origin << ": the box is " << length_ << " long; the cells need at least 3 times "
      << "the largest contact distance (" << contact << ") along x";
    throw InputError(m.str());
  }
  cell_width_ = length_ / nx_;
  cell_height_ = cell_width_;

  double lowest = INFINITY, highest = -INFINITY;
  for (const StartDisk &d : start.disks) {
    if (!(d.x >= start.xlo && d.x < start.xhi)) {
      std::ostringstream m;
      m.precision(17);
      m << d.origin << ": the disk at x = " << d.x << " is outside the box [" << start.xlo
        << ", " << start.xhi << ")";
      throw InputError(m.str());
    }
    if (has_floor_ && d.y - 0.5 * d.diameter < floor_y_ - START_TOUCH * 0.5 * d.diameter) {
      std::ostringstream m;
      m.precision(17);
      m << d.origin << ": the disk at y = " << d.y << " (radius " << 0.5 * d.diameter
        << ") reaches below the floor at y = " << floor_y_;
      throw InputError(m.str());
    }
    lowest = std::min(lowest, d.y - 0.5 * d.diameter);
    highest = std::max(highest, d.y + 0.5 * d.diameter);
  }
  for (const Bump &b : start.bumps) {
    if (!(b.x >= start.xlo && b.x < start.xhi)) {
      std::ostringstream m;
      m.precision(17);
      m << b.origin << ": the bump at x = " << b.x << " is outside the box [" << start.xlo
        << ", " << start.xhi << ")";
      throw InputError(m.str());
    }
    lowest = std::min(lowest, b.y - 0.5 * b.diameter);
    highest = std::max(highest, b.y + 0.5 * b.diameter);
  }
  if (has_floor_) lowest = std::min(lowest, floor_y_);
  y0_ = lowest - cell_height_;
  rows_ = 0;
  add_rows_to(static_cast<int>(std::floor((highest - y0_) / cell_height_)) + 1);

  for (const Bump &b : start.bumps) {
    FixedDisk f{b.x - xlo_, b.y, 0.5 * b.diameter, 0};
    f.cell = cell_of(f.x, f.y);
    cell_bumps_[f.cell].push_back(static_cast<int>(bump_.size()));
    bump_.push_back(f);
  }
  for (const StartDisk &s : start.disks) {
    Disk d;
    d.x = s.x - xlo_;
    d.y = s.y;
    d.vx = s.vx;
    d.vy = s.vy;
    d.omega = s.omega;
    d.t = 0.0;
    d.radius = 0.5 * s.diameter;
    // mass proportional to area, 1 for the unit diameter (LAMMPS: density/disc 4/pi); a disc's
    // moment of inertia (docs/model.md section 1)
    d.mass = s.diameter * s.diameter;
    d.inertia = 0.5 * d.mass * d.radius * d.radius;
    d.image = 0;
    d.collisions = 0;
    d.last_partner = NO_PARTNER;
    d.last_encounter = 0;
    d.last_collision = -INFINITY;
    d.disk_collisions = d.boundary_collisions = 0;
    d.cell = d.slot = -1;
    disk_.push_back(d);
    place(static_cast<int>(disk_.size()) - 1, cell_of(d.x, d.y));
  }

  // overlaps at the start, through the cells
  for (int i = 0; i < disks(); i++) {
    const Disk &a = disk_[i];
    const int col = a.cell % nx_, row = a.cell / nx_;
    for (int r = std::max(0, row - 1); r <= std::min(rows_ - 1, row + 1); r++)
      for (int dc = -1; dc <= 1; dc++) {
        const int c = (col + dc + nx_) % nx_;
        auto check = [&](double x, double y, double contact_distance, const std::string &what) {
          double dx = a.x - x;
          dx -= length_ * std::nearbyint(dx / length_);
          const double dist = std::hypot(dx, a.y - y);
          if (dist < contact_distance * (1.0 - START_TOUCH)) {
            std::ostringstream m;
            m.precision(17);
            m << start.disks[i].origin << ": disk " << i << " at (" << a.x + xlo_ << ", " << a.y
              << ") " << what << ": centres " << dist << " apart, contact distance "
              << contact_distance;
            throw InputError(m.str());
          }
        };
        for (int j : cell_disks_[r * nx_ + c])
          if (j > i)
            check(disk_[j].x, disk_[j].y, a.radius + disk_[j].radius,
                  "overlaps disk " + std::to_string(j) + " (" + start.disks[j].origin + ")");
        for (int b : cell_bumps_[r * nx_ + c])
          check(bump_[b].x, bump_[b].y, a.radius + bump_[b].radius,
                "lies inside bump " + std::to_string(b) + " (" + start.bumps[b].origin + ")");
      }
  }

  if (settings_.rule == RuleKind::SoftLimit) {
    const Law law = settings_.soft_law();
    disk_table_ = soft_table(law, Partner::Disk);
    boundary_table_ = soft_table(law, Partner::Boundary);
  }
  detector_.reset(new CollapseDetector(disks(), settings_.collapse_count, settings_.collapse_time));
  event_.assign(disk_.size(), Event{INFINITY, Kind::None, 0, 0});
  for (int i = 0; i < disks(); i++) predict(i);
}

Engine::~Engine() = default;

Engine::Flight Engine::flight(const Disk &d, double t) const
{
  const double tau = t - d.t;
  return {d.x + (d.vx + 0.5 * gx_ * tau) * tau, d.y + (d.vy + 0.5 * gy_ * tau) * tau,
          d.vx + gx_ * tau, d.vy + gy_ * tau};
}

void Engine::advance(Disk &d, double t) const
{
  const Flight f = flight(d, t);
  d.x = f.x;
  d.y = f.y;
  d.vx = f.vx;
  d.vy = f.vy;
  d.t = t;
}

int Engine::cell_of(double x, double y) const
{
  const int col = std::min(nx_ - 1, std::max(0, static_cast<int>(std::floor(x / cell_width_))));
  const int row = std::min(rows_ - 1, std::max(0, static_cast<int>(std::floor((y - y0_) / cell_height_))));
  return row * nx_ + col;
}

void Engine::add_rows_to(int row)
{
  if (row < rows_) return;
  rows_ = row + 1;
  cell_disks_.resize(static_cast<std::size_t>(rows_) * nx_);
  cell_bumps_.resize(static_cast<std::size_t>(rows_) * nx_);
}

void Engine::place(int i, int cell)
{
  Disk &d = disk_[i];
  d.cell = cell;
  d.slot = static_cast<int>(cell_disks_[cell].size());
  cell_disks_[cell].push_back(i);
}

void Engine::unplace(int i)
{
  std::vector<int> &members = cell_disks_[disk_[i].cell];
  const int moved = members.back();
  members[disk_[i].slot] = moved;
  disk_[moved].slot = disk_[i].slot;
  members.pop_back();
}

void Engine::predict(int i)
{
  const Disk &d = disk_[i];
  const Flight f = flight(d, now_);
  Event next{INFINITY, Kind::None, 0, 0};
  double best = NEVER;    // time from now
  auto consider = [&](double tau, Kind kind, int partner, std::uint64_t partner_collisions) {
    if (tau < best) {
      best = tau;
      next = {0.0, kind, partner, partner_collisions};
    }
  };

  // leaving the cell: its four sides (row 0 reaches down without end; a disk rising out of the
  // top row gets a new row)
  const int col = d.cell % nx_, row = d.cell / nx_;
  const double x_lo = col * cell_width_, x_hi = col == nx_ - 1 ? length_ : (col + 1) * cell_width_;
  consider(quadratic_entry(x_hi - f.x, -f.vx, -0.5 * gx_), Kind::Cross, 0, 0);
  consider(quadratic_entry(f.x - x_lo, f.vx, 0.5 * gx_), Kind::Cross, 1, 0);
  consider(quadratic_entry(y0_ + (row + 1) * cell_height_ - f.y, -f.vy, -0.5 * gy_), Kind::Cross, 2, 0);
  if (row > 0) consider(quadratic_entry(f.y - (y0_ + row * cell_height_), f.vy, 0.5 * gy_), Kind::Cross, 3, 0);

  if (has_floor_) consider(quadratic_entry(f.y - d.radius - floor_y_, f.vy, 0.5 * gy_), Kind::Floor, 0, 0);

  const double g2 = gx_ * gx_ + gy_ * gy_;
  const double speed = std::hypot(f.vx, f.vy);
  for (int r = std::max(0, row - 1); r <= std::min(rows_ - 1, row + 1); r++)
    for (int dc = -1; dc <= 1; dc++) {
      int c = col + dc;
      double offset = 0.0;    // the neighbour's image seen from this cell
      if (c < 0) {
        c += nx_;
        offset = -length_;
      } else if (c >= nx_) {
        c -= nx_;
        offset = length_;
      }
      const int cell = r * nx_ + c;
      for (int b : cell_bumps_[cell]) {
        const FixedDisk &bump = bump_[b];
        const double dx = f.x - (bump.x + offset), dy = f.y - bump.y;
        const double contact = d.radius + bump.radius;
        const double r2 = dx * dx + dy * dy;
        // a bump out of reach before the best event so far
        if (std::isfinite(best) &&
            std::sqrt(r2) - contact > best * (speed + 0.5 * std::sqrt(g2) * best))
          continue;
        double tau = NEVER;
        if (g2 == 0.0) {    // straight flight
          tau = quadratic_entry(r2 - contact * contact, 2.0 * (dx * f.vx + dy * f.vy),
                                f.vx * f.vx + f.vy * f.vy);
        } else if (std::isfinite(best)) {
          const double c4[5] = {r2 - contact * contact, 2.0 * (dx * f.vx + dy * f.vy),
                                f.vx * f.vx + f.vy * f.vy + (dx * gx_ + dy * gy_),
                                f.vx * gx_ + f.vy * gy_, 0.25 * g2};
          tau = quartic_entry(c4, best);
        }    // else it never leaves the bottom row, below every bump: it meets none
        consider(tau, Kind::Bump, b, 0);
      }
      for (int j : cell_disks_[cell]) {
        if (j == i) continue;
        const Disk &e = disk_[j];
        // just collided with each other, this image of it, and neither since: flying apart
        // (free relative flight); another periodic image may still come
        const long long encounter = (offset > 0.0) - (offset < 0.0) + d.image - e.image;
        if (d.last_partner == j && e.last_partner == i && d.last_encounter == encounter) continue;
        const Flight g = flight(e, now_);
        const double dx = f.x - (g.x + offset), dy = f.y - g.y;
        const double dvx = f.vx - g.vx, dvy = f.vy - g.vy;
        const double contact = d.radius + e.radius;
        consider(quadratic_entry(dx * dx + dy * dy - contact * contact, 2.0 * (dx * dvx + dy * dvy),
                                 dvx * dvx + dvy * dvy),
                 Kind::Disk, j, e.collisions);
      }
    }
  next.time = now_ + best;
  event_[i] = next;
  tree_.set(i, next.time);
}

Impulse Engine::impulse(const ContactVelocity &in, double reduced_mass, double q, bool boundary,
                        bool elastic) const
{
  if (elastic) return paper_impulse(settings_.tc_rule(), reduced_mass, q, in);
  if (settings_.rule == RuleKind::Paper)
    return paper_impulse(boundary ? settings_.boundary : settings_.disk, reduced_mass, q, in);
  const ContactVelocity out = (boundary ? boundary_table_ : disk_table_)->outgoing(in);
  return impulse_between(in, out, reduced_mass, q);
}

void Engine::collide_disks(int i, int j)
{
  Disk &a = disk_[i], &b = disk_[j];
  advance(a, now_);
  advance(b, now_);
  double dx = a.x - b.x;
  const double images = std::nearbyint(dx / length_);
  dx -= length_ * images;
  const long long encounter = static_cast<long long>(images) + a.image - b.image;
  const double dy = a.y - b.y;
  const double dist = std::hypot(dx, dy), contact = a.radius + b.radius;
  totals_.largest_overlap = std::max(totals_.largest_overlap, (contact - dist) / contact);
  const double nx = dx / dist, ny = dy / dist;
  DiskMotion ma{a.vx, a.vy, a.omega, a.mass, a.radius, a.inertia};
  DiskMotion mb{b.vx, b.vy, b.omega, b.mass, b.radius, b.inertia};
  const ContactVelocity in = contact_velocity(nx, ny, ma, &mb);
  if (!(in.vn < 0.0)) {
    // a grazing contact that rounding turned away: no collision, and the pair, in free relative
    // flight without approaching, cannot meet until one of them collides (as after a collision)
    totals_.grazing++;
    a.last_partner = j;
    b.last_partner = i;
    a.last_encounter = encounter;
    b.last_encounter = -encounter;
    predict(i);
    predict(j);
    return;
  }
  const double tc = settings_.on_collapse == OnCollapse::TC ? settings_.tc_time : 0.0;
  const bool elastic = now_ - a.last_collision < tc || now_ - b.last_collision < tc;
  const double reduced_mass = collision_reduced_mass(ma, &mb), q = collision_q(ma, &mb);
  const Impulse J = impulse(in, reduced_mass, q, false, elastic);
  apply_impulse(nx, ny, J, ma, &mb);
  a.vx = ma.vx;
  a.vy = ma.vy;
  a.omega = ma.omega;
  b.vx = mb.vx;
  b.vy = mb.vy;
  b.omega = mb.omega;
  a.collisions++;
  b.collisions++;
  a.last_partner = j;
  b.last_partner = i;
  a.last_encounter = encounter;
  b.last_encounter = -encounter;
  a.last_collision = b.last_collision = now_;
  a.disk_collisions++;
  b.disk_collisions++;
  totals_.disk_collisions++;
  if (elastic) totals_.tc_collisions++;
  if (observer_) observer_({epoch_ + now_, i, j, in, after_impulse(in, J, reduced_mass, q), elastic});
  if (detector_->record(i, now_, j))
    collapse_.reset(new CollapseReport(detector_->report(i, now_, epoch_)));
  if (detector_->record(j, now_, i) && !collapse_)
    collapse_.reset(new CollapseReport(detector_->report(j, now_, epoch_)));
  predict(i);
  predict(j);
}

void Engine::collide_boundary(int i, int partner)
{
  Disk &a = disk_[i];
  advance(a, now_);
  double nx = 0.0, ny = 1.0, dist = a.y - floor_y_, contact = a.radius;
  if (is_bump(partner)) {
    const FixedDisk &bump = bump_[bump_index(partner)];
    double dx = a.x - bump.x;
    dx -= length_ * std::nearbyint(dx / length_);
    const double dy = a.y - bump.y;
    dist = std::hypot(dx, dy);
    contact = a.radius + bump.radius;
    nx = dx / dist;
    ny = dy / dist;
  }
  totals_.largest_overlap = std::max(totals_.largest_overlap, (contact - dist) / contact);
  DiskMotion ma{a.vx, a.vy, a.omega, a.mass, a.radius, a.inertia};
  const ContactVelocity in = contact_velocity(nx, ny, ma, nullptr);
  if (!(in.vn < 0.0)) {
    // the gap closed at its vertex with no normal velocity left to rounding: under gravity the
    // disk stays on the surface (a lasting contact, the end of an inelastic collapse), which
    // the hard-disk rule can only repeat at the same time; the detector counts it
    totals_.grazing++;
    if (detector_->record(i, now_, partner, true))
      collapse_.reset(new CollapseReport(detector_->report(i, now_, epoch_)));
    predict(i);
    return;
  }
  const double tc = settings_.on_collapse == OnCollapse::TC ? settings_.tc_time : 0.0;
  const bool elastic = now_ - a.last_collision < tc;
  const double reduced_mass = collision_reduced_mass(ma, nullptr), q = collision_q(ma, nullptr);
  const Impulse J = impulse(in, reduced_mass, q, true, elastic);
  apply_impulse(nx, ny, J, ma, nullptr);
  a.vx = ma.vx;
  a.vy = ma.vy;
  a.omega = ma.omega;
  a.collisions++;
  a.last_partner = partner;
  a.last_collision = now_;
  a.boundary_collisions++;
  totals_.boundary_collisions++;
  if (elastic) totals_.tc_collisions++;
  if (observer_) observer_({epoch_ + now_, i, partner, in, after_impulse(in, J, reduced_mass, q), elastic});
  if (detector_->record(i, now_, partner))
    collapse_.reset(new CollapseReport(detector_->report(i, now_, epoch_)));
  predict(i);
}

void Engine::cross(int i, int direction)
{
  Disk &d = disk_[i];
  advance(d, now_);
  unplace(i);
  int col = d.cell % nx_, row = d.cell / nx_;
  switch (direction) {
    case 0:
      if (++col == nx_) {
        col = 0;
        d.x -= length_;
        d.image++;
      }
      break;
    case 1:
      if (--col < 0) {
        col = nx_ - 1;
        d.x += length_;
        d.image--;
      }
      break;
    case 2:
      add_rows_to(++row);
      break;
    default:
      if (--row == 0 && (has_floor_ || !bump_.empty())) {
        // row 0 lies below the floor and every bump: the disk has passed the slope (between
        // bumps further apart than its diameter)
        std::ostringstream m;
        m.precision(17);
        m << "disk " << i << " fell through the slope at t = " << time() << " (x = " << d.x + xlo_
          << "): it passed below the floor and the bumps";
        throw std::runtime_error(m.str());
      }
      break;
  }
  place(i, row * nx_ + col);
  totals_.cell_crossings++;
  predict(i);
}

void Engine::rebase()
{
  const double by = now_;
  for (int i = 0; i < disks(); i++) {
    Disk &d = disk_[i];
    advance(d, now_);
    d.t = 0.0;
    d.last_collision -= by;
    event_[i].time -= by;
    tree_.set(i, event_[i].time);
  }
  detector_->shift(by);
  epoch_ += by;
  now_ = 0.0;
}

Engine::Stop Engine::run(double t_end, std::uint64_t max_events)
{
  if (collapse_) return Stop::Collapse;
  std::uint64_t done = 0;
  while (true) {
    if (now_ > REBASE_AFTER) rebase();
    const int i = tree_.first();
    const double t = tree_.first_time();
    if (!(t <= t_end - epoch_)) {
      now_ = std::max(now_, t_end - epoch_);
      return Stop::Time;
    }
    if (max_events && done >= max_events) return Stop::Events;
    now_ = t;
    const Event e = event_[i];
    switch (e.kind) {
      case Kind::Disk:
        if (disk_[e.partner].collisions != e.partner_collisions) {    // stale: j has collided
          totals_.invalid_predictions++;
          predict(i);
          continue;
        }
        collide_disks(i, e.partner);
        break;
      case Kind::Floor:
        collide_boundary(i, FLOOR);
        break;
      case Kind::Bump:
        collide_boundary(i, bump_partner(e.partner));
        break;
      case Kind::Cross:
        cross(i, e.partner);
        break;
      case Kind::None:
        return Stop::Time;
    }
    done++;
    totals_.events++;
    if (collapse_) return Stop::Collapse;
  }
}

DiskState Engine::state(int i) const
{
  const Disk &d = disk_[i];
  const Flight f = flight(d, now_);
  return {xlo_ + f.x + static_cast<double>(d.image) * length_, f.y, f.vx, f.vy, d.omega};
}

double Engine::largest_overlap_now() const
{
  double largest = 0.0;
  for (int i = 0; i < disks(); i++) {
    const Disk &a = disk_[i];
    const Flight f = flight(a, now_);
    if (has_floor_) largest = std::max(largest, (a.radius - (f.y - floor_y_)) / a.radius);
    const int col = a.cell % nx_, row = a.cell / nx_;
    for (int r = std::max(0, row - 1); r <= std::min(rows_ - 1, row + 1); r++)
      for (int dc = -1; dc <= 1; dc++) {
        const int cell = r * nx_ + (col + dc + nx_) % nx_;
        auto gap = [&](double x, double y, double contact) {
          double dx = f.x - x;
          dx -= length_ * std::nearbyint(dx / length_);
          largest = std::max(largest, (contact - std::hypot(dx, f.y - y)) / contact);
        };
        for (int j : cell_disks_[cell])
          if (j > i) {
            const Flight g = flight(disk_[j], now_);
            gap(g.x, g.y, a.radius + disk_[j].radius);
          }
        for (int b : cell_bumps_[cell]) gap(bump_[b].x, bump_[b].y, a.radius + bump_[b].radius);
      }
  }
  return largest;
}

void Engine::kinetic_energy(double *translational, double *rotational) const
{
  double et = 0.0, er = 0.0;
  for (const Disk &d : disk_) {
    const Flight f = flight(d, now_);
    et += 0.5 * d.mass * (f.vx * f.vx + f.vy * f.vy);
    er += 0.5 * d.inertia * d.omega * d.omega;
  }
  *translational = et;
  *rotational = er;
}

}    // namespace ed
}    // namespace mn
