#include "outputs.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <fstream>
#include <vector>

namespace mn {
namespace ed {

namespace {

// A value with the fewest digits (up to 17) that read back as the same double: postprocess checks
// params.txt's values against the point's own (point.json).
std::string exact(double v)
{
  char text[32];
  for (int digits = 10; digits <= 17; digits++) {
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    if (std::strtod(text, nullptr) == v) break;
  }
  return text;
}

const char *rule_name(RuleKind rule) { return rule == RuleKind::Paper ? "paper" : "soft"; }

void write_params(const std::string &path, const Engine &engine, const RunRequest &run)
{
  const Settings &s = run.settings;
  const OutputSettings &o = run.outputs;
  const Law law = law_at(o.kn, s.disk);
  std::ofstream out(path);
  out << "scene " << run.scene << "\n"
      << "engine event_driven\n"
      << "rule " << rule_name(s.rule) << "\n"
      << "tangential " << (s.coulomb_cutback ? "cutback" : "literal") << "\n"
      << "kn " << exact(o.kn) << "\n"
      << "e " << exact(s.disk.e) << "\n"
      << "beta " << exact(s.disk.beta) << "\n"
      << "mu " << exact(s.disk.mu) << "\n"
      << "e_w " << exact(s.boundary.e) << "\n"
      << "beta_w " << exact(s.boundary.beta) << "\n"
      << "sin_theta " << exact(s.sin_theta) << "\n"
      << "collapse " << (s.on_collapse == OnCollapse::TC ? "tc" : "stop") << "\n"
      << "tc_time " << exact(s.tc_time) << "\n"
      << "collapse_count " << s.collapse_count << "\n"
      << "collapse_time " << exact(s.collapse_time) << "\n"
      << "dt " << exact(o.interval) << "\n"
      << "output_interval " << exact(o.interval) << "\n"
      << "profile_bin " << exact(o.profile_bin) << "\n"
      << "tau_c " << exact(law.tau_c) << "\n"
      << "tau_w " << exact(law.tau_w) << "\n";
  if (!o.seed.empty()) out << "seed " << o.seed << "\n";
  out << "run_time " << exact(run.run_time) << "\n"
      << "average_start " << exact(o.average_start) << "\n"
      << "n_mobile " << engine.disks() << "\n"
      << "dimension 2\n";
}

// fix ave/chunk's running average with norm sample: per sample, each bin's count and the mean
// velocity of its disks (0 in an empty bin); the bins' values are the means over the samples.
class Profile {
 public:
  Profile(const OutputSettings &o, double length)
      : lo_(o.profile_lo), bin_(o.profile_bin), area_(o.profile_bin * length),
        bins_(static_cast<int>(std::ceil((o.profile_hi - o.profile_lo) / o.profile_bin))),
        count_(bins_), vx_(bins_), vy_(bins_)
  {
  }
  void sample(const Engine &engine)
  {
    std::vector<double> count(bins_), vx(bins_), vy(bins_);
    for (int i = 0; i < engine.disks(); i++) {
      const DiskState d = engine.state(i);
      const int b = static_cast<int>(std::floor((d.y - lo_) / bin_));
      if (b < 0 || b >= bins_) continue;
      count[b] += 1.0;
      vx[b] += d.vx;
      vy[b] += d.vy;
    }
    for (int b = 0; b < bins_; b++) {
      count_[b] += count[b];
      if (count[b] > 0.0) {
        vx_[b] += vx[b] / count[b];
        vy_[b] += vy[b] / count[b];
      }
    }
    samples_++;
  }
  void write(const std::string &path, long long step) const
  {
    std::ofstream out(path);
    out.precision(10);
    out << "# Chunk-averaged data (mn-event-driven: a running average over the samples, fix "
           "ave/chunk's norm sample)\n"
        << "# Timestep Number-of-chunks Total-count\n"
        << "# Chunk Coord1 Ncount density/number vx vy\n";
    double total = 0.0;
    for (double c : count_) total += c;
    const double n = samples_ ? samples_ : 1;
    out << step << " " << bins_ << " " << total / n << "\n";
    for (int b = 0; b < bins_; b++)
      out << b + 1 << " " << lo_ + (b + 0.5) * bin_ << " " << count_[b] / n << " "
          << count_[b] / n / area_ << " " << vx_[b] / n << " " << vy_[b] / n << "\n";
  }

 private:
  double lo_, bin_, area_;
  int bins_;
  std::vector<double> count_, vx_, vy_;
  long long samples_ = 0;
};

}    // namespace

Engine::Stop run_sampled(Engine &engine, const RunRequest &run)
{
  const OutputSettings &o = run.outputs;
  write_params(run.out + "/params.txt", engine, run);
  std::ofstream energy(run.out + "/energy.txt");
  energy.precision(10);
  energy << "# energy and counters: see plugin/event_driven/outputs.h\n"
            "# step e_trans e_rot e_total begun_disk begun_boundary time_disk time_boundary "
            "time_multiple contacts_now window\n";
  const int n = engine.disks();
  // each disk's collisions when the counters' window began
  std::vector<std::uint64_t> disk_at(n, 0), boundary_at(n, 0);
  double window_start = 0.0;
  auto print = [&](long long step, double t) {
    double et, er;
    engine.kinetic_energy(&et, &er);
    std::uint64_t disk = 0, boundary = 0;
    for (int i = 0; i < n; i++) {
      disk += engine.disk_collisions_of(i) - disk_at[i];
      boundary += engine.boundary_collisions_of(i) - boundary_at[i];
    }
    energy << step << " " << et / n << " " << er / n << " " << (et + er) / n << " " << disk
           << " " << boundary << " 0 0 0 0 " << t - window_start << "\n";
    energy.flush();
  };
  Profile profile(o, engine.box_length());
  const long long transient = static_cast<long long>(std::ceil(o.average_start / o.interval - 1e-9));
  const long long last = static_cast<long long>(std::ceil(run.run_time / o.interval - 1e-9));
  print(0, 0.0);
  if (transient == 0) profile.sample(engine);
  Engine::Stop stop = Engine::Stop::Time;
  long long step = 0;
  for (step = 1; step <= last; step++) {
    const double t = std::min(step * o.interval, run.run_time);
    const std::uint64_t done = engine.totals().events;
    if (run.max_events && done >= run.max_events) {
      stop = Engine::Stop::Events;
      break;
    }
    stop = engine.run(t, run.max_events ? run.max_events - done : 0);
    if (stop != Engine::Stop::Time) break;
    print(step, t);
    if (step == transient) {
      // the counters' window starts afresh (LAMMPS: fix_modify c reset after this line)
      for (int i = 0; i < n; i++) {
        disk_at[i] = engine.disk_collisions_of(i);
        boundary_at[i] = engine.boundary_collisions_of(i);
      }
      window_start = t;
    }
    if (step >= transient && transient > 0) profile.sample(engine);
  }
  profile.write(run.out + "/profile.txt", step > last ? last : step);
  std::ofstream counts(run.out + "/counts.txt");
  counts.precision(10);
  counts << "ITEM: TIMESTEP\n" << (step > last ? last : step) << "\nITEM: NUMBER OF ATOMS\n" << n
         << "\nITEM: ATOMS id diameter f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] f_c[6]\n";
  for (int i = 0; i < n; i++)
    counts << i + 1 << " " << 2.0 * engine.radius(i) << " "
           << engine.disk_collisions_of(i) - disk_at[i] << " "
           << engine.boundary_collisions_of(i) - boundary_at[i] << " 0 0 0 0\n";
  return stop;
}

}    // namespace ed
}    // namespace mn
