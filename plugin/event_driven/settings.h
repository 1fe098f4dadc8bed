// What an event-driven run is asked to do: the collision rule and its parameters, gravity, what
// happens at an inelastic collapse, and the run's extent; read from key=value arguments or a
// parameter file, each value checked with a refusal that names it.
#ifndef MN_EVENT_DRIVEN_SETTINGS_H
#define MN_EVENT_DRIVEN_SETTINGS_H

#include "mn_collision.h"
#include "start.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mn {
namespace ed {

enum class RuleKind {
  Paper,       // rule (a): the paper's eqs. (2)-(5), e and beta (e_w and beta_w at the boundary)
  SoftLimit    // rule (b): the soft law's binary collision in the limit k_n -> infinity
};

enum class OnCollapse {
  Stop,    // the pure rule; a detected collapse ends the run with a report
  TC       // the TC model throughout: a collision within tc_time of a disk's previous is elastic
};

// The defaults of rule (a) at the boundary that go with e and beta: the soft law's own boundary
// restitutions (e_w of docs/model.md section 3; beta_w of a sticking boundary collision, which
// is e_w when beta = e), so that rule (a) and rule (b) meet where the contact sticks. For
// beta <= 0 (outside the soft law's range) beta_w defaults to beta.
PaperRule boundary_defaults(double e, double beta, double mu);

struct Settings {
  double g = 1.0;             // gravity's magnitude (the unit: g = 1)
  double sin_theta = 0.0;     // the slope: gravity (g sin(theta), -g cos(theta))
  RuleKind rule = RuleKind::Paper;
  PaperRule disk{0.7, 0.7, 0.5};        // rule (a) between disks: e, beta, mu
  PaperRule boundary = boundary_defaults(0.7, 0.7, 0.5);    // rule (a) with the boundary:
                                                          // e_w, beta_w, mu
  bool coulomb_cutback = false;         // rule (b): the law's u_t reading
  OnCollapse on_collapse = OnCollapse::Stop;
  double tc_time = 0.0;       // the TC model's t_c (on_collapse TC)
  double tc_beta = -1.0;      // a TC collision's tangential restitution (-1: smooth)
  int collapse_count = 100;   // collapse: a disk with more than this many collisions ...
  double collapse_time = 1e-6;    // ... within this time

  // The soft law whose limit rule (b) is: e, beta, mu and the u_t reading (k_n does not matter).
  Law soft_law() const;
  // The rule of a collision the TC model makes elastic.
  PaperRule tc_rule() const { return {1.0, tc_beta, disk.mu}; }
};

// One name=value, and where it came from ("the command line", "FILE line N").
struct Parameter {
  std::string name, value, origin;
};

// Reads a parameter file: one "name value" (or "name = value") per line, # comments.
std::vector<Parameter> read_parameter_file(const std::string &path);

// The sampled outputs of a run with out= and output_interval (outputs.h): the files a LAMMPS
// run of the scene writes (params.txt, energy.txt, counts.txt, profile.txt), read by postprocess.
struct OutputSettings {
  double interval = 0.0;        // time between lines of energy.txt and profile samples (0: none)
  double average_start = 0.0;   // the counters' window and the profile's span start here
  double profile_bin = 0.25;    // bin height of profile.txt
  double profile_lo = 0.0, profile_hi = 0.0;    // its bins cover [lo, hi) (the deck's box)
  double kn = 0.0;              // the soft run's k_n this run stands for: params.txt's kn, tau_c
                                // and tau_w (and tc_time = tau_c)
  std::string seed;             // the deck's seed the start was made with, for params.txt
};

// The soft law at k_n with the run's e (and mu): its tau_c and tau_w, which depend on k_n and e
// alone (beta, outside the law's range under rule (a), is taken as 1 there).
Law law_at(double kn, const PaperRule &disk);

// A whole run: its settings, its start, where its outputs go, and how long it lasts.
struct RunRequest {
  Settings settings;
  std::string scene = "custom";    // a name for the outputs: one of the project's scenes or custom
  std::string start_path;
  std::string out;                 // the output directory ("" = none)
  double run_time = 0.0;           // physical time to run
  std::uint64_t max_events = 0;    // 0: no limit
  OutputSettings outputs;
  std::vector<Parameter> given;    // every parameter as given, for params.txt
};

// The scenes a run may name.
const std::vector<std::string> &known_scenes();

// Checks and applies the parameters (later ones override earlier ones). Throws InputError,
// naming the parameter and where it came from, for an unknown name, a value that is not a
// finite number where one is needed, a value out of range, an unknown rule, reading, scene or
// collapse choice, a parameter that does not apply to the chosen rule, or a missing start.
RunRequest parse_run(const std::vector<Parameter> &parameters);

}    // namespace ed
}    // namespace mn

#endif
