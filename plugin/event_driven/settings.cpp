#include "settings.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

namespace mn {
namespace ed {

Law Settings::soft_law() const
{
  Options options;
  options.coulomb_cutback = coulomb_cutback;
  return derive({1.0, disk.e, disk.beta, disk.mu}, options);
}

Law law_at(double kn, const PaperRule &disk)
{
  return derive({kn, disk.e, disk.beta > 0.0 ? disk.beta : 1.0, disk.mu});
}

PaperRule boundary_defaults(double e, double beta, double mu)
{
  if (!(beta > 0.0)) return {derive({1.0, e, 1.0, mu}).e_w, beta, mu};
  const Law law = derive({1.0, e, beta, mu});
  return {law.e_w, boundary_sticking_restitution(law), mu};
}

std::vector<Parameter> read_parameter_file(const std::string &path)
{
  std::ifstream in(path);
  if (!in) throw InputError("cannot open the parameter file '" + path + "'");
  std::vector<Parameter> out;
  std::string line;
  for (int n = 1; std::getline(in, line); n++) {
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    for (char &c : line)
      if (c == '=') c = ' ';
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    if (w.empty()) continue;
    const std::string where = path + " line " + std::to_string(n);
    if (w.size() != 2)
      throw InputError(where + ": a parameter line is 'name value', not '" + line + "'");
    out.push_back({w[0], w[1], where});
  }
  return out;
}

const std::vector<std::string> &known_scenes()
{
  static const std::vector<std::string> scenes{"custom", "single_disk", "collisional_flow",
                                               "frictional_flow", "bouncing_ball"};
  return scenes;
}

namespace {

std::string named(const Parameter &p) { return p.name + " = " + p.value + " (" + p.origin + ")"; }

double finite(const Parameter &p)
{
  char *end = nullptr;
  const double v = std::strtod(p.value.c_str(), &end);
  if (p.value.empty() || *end != '\0') throw InputError(named(p) + " is not a number");
  if (!std::isfinite(v)) throw InputError(named(p) + ": the value must be finite");
  return v;
}

double within(const Parameter &p, double lo, bool lo_open, double hi, bool hi_open,
              const char *range)
{
  const double v = finite(p);
  if ((lo_open ? !(v > lo) : !(v >= lo)) || (hi_open ? !(v < hi) : !(v <= hi)))
    throw InputError(named(p) + " is out of range: " + p.name + " must lie in " + range);
  return v;
}

std::string choice(const Parameter &p, const std::vector<std::string> &allowed)
{
  for (const std::string &a : allowed)
    if (p.value == a) return a;
  std::string list;
  for (std::size_t k = 0; k < allowed.size(); k++)
    list += (k ? (k + 1 == allowed.size() ? " or " : ", ") : "") + allowed[k];
  throw InputError(named(p) + ": unknown " + p.name + " (" + list + ")");
}

}    // namespace

RunRequest parse_run(const std::vector<Parameter> &parameters)
{
  RunRequest run;
  run.given = parameters;
  // the last value of each name counts
  std::map<std::string, Parameter> last;
  static const std::vector<std::string> names{
      "start", "out", "scene", "run_time", "events", "rule", "tangential", "e", "beta", "mu",
      "e_w", "beta_w", "g", "sin_theta", "collapse", "tc_time", "tc_beta", "collapse_count",
      "collapse_time", "kn", "seed", "output_interval", "average_start", "profile_bin",
      "profile_lo", "profile_hi"};
  for (const Parameter &p : parameters) {
    bool known = false;
    for (const std::string &n : names) known = known || p.name == n;
    if (!known) {
      std::string list;
      for (const std::string &n : names) list += " " + n;
      throw InputError("unknown parameter '" + p.name + "' (" + p.origin + "); the parameters are:" + list);
    }
    last[p.name] = p;
  }
  auto has = [&](const char *name) { return last.count(name) > 0; };
  Settings &s = run.settings;

  if (!has("start")) throw InputError("no start: give start=FILE (a start file: box, floor, disk and bump lines)");
  run.start_path = last["start"].value;
  if (has("out")) run.out = last["out"].value;
  if (has("scene")) run.scene = choice(last["scene"], known_scenes());
  if (!has("run_time")) throw InputError("no run_time: give run_time=T, the physical time to run");
  run.run_time = within(last["run_time"], 0.0, true, INFINITY, true, "(0, inf)");
  if (has("events")) {
    const double events = within(last["events"], 1.0, false, 1e19, false, "[1, 1e19]");
    if (events != std::floor(events)) throw InputError(named(last["events"]) + " must be a whole number");
    run.max_events = static_cast<std::uint64_t>(events);
  }

  if (has("rule"))
    s.rule = choice(last["rule"], {"paper", "soft"}) == "paper" ? RuleKind::Paper : RuleKind::SoftLimit;
  const bool soft = s.rule == RuleKind::SoftLimit;
  if (has("e")) s.disk.e = within(last["e"], 0.0, true, 1.0, false, "(0, 1]");
  if (has("beta"))
    s.disk.beta = soft ? within(last["beta"], 0.0, true, 1.0, false, "(0, 1] under rule soft (the soft law's range)")
                       : within(last["beta"], -1.0, false, 1.0, false, "[-1, 1]");
  if (has("mu")) s.disk.mu = within(last["mu"], 0.0, false, INFINITY, true, "[0, inf)");
  if (has("tangential")) {
    if (!soft) throw InputError(named(last["tangential"]) + ": tangential (the soft law's u_t reading) applies to rule soft only");
    s.coulomb_cutback = choice(last["tangential"], {"literal", "cutback"}) == "cutback";
  }
  s.boundary = boundary_defaults(s.disk.e, s.disk.beta, s.disk.mu);
  for (const char *name : {"e_w", "beta_w"})
    if (has(name) && soft)
      throw InputError(named(last[name]) + ": " + name +
                       " applies to rule paper only; under rule soft the boundary's restitution is the soft law's own (set by e and beta)");
  if (has("e_w")) s.boundary.e = within(last["e_w"], 0.0, true, 1.0, false, "(0, 1]");
  if (has("beta_w")) s.boundary.beta = within(last["beta_w"], -1.0, false, 1.0, false, "[-1, 1]");

  if (has("g")) s.g = within(last["g"], 0.0, false, INFINITY, true, "[0, inf)");
  if (has("sin_theta")) s.sin_theta = within(last["sin_theta"], -1.0, false, 1.0, false, "[-1, 1]");

  if (has("collapse"))
    s.on_collapse = choice(last["collapse"], {"stop", "tc"}) == "stop" ? OnCollapse::Stop : OnCollapse::TC;
  const bool tc = s.on_collapse == OnCollapse::TC;
  for (const char *name : {"tc_time", "tc_beta"})
    if (has(name) && !tc)
      throw InputError(named(last[name]) + ": " + name + " applies to collapse = tc only");
  OutputSettings &o = run.outputs;
  if (has("kn")) {
    o.kn = within(last["kn"], 0.0, true, INFINITY, true, "(0, inf)");
    if (const char *why = law_error(law_at(o.kn, s.disk)))
      throw InputError(named(last["kn"]) + ": " + why);
  }
  if (tc) {
    if (!has("tc_time")) throw InputError("collapse = tc (" + last["collapse"].origin + ") needs tc_time, the TC model's t_c > 0 (or tau_c: the soft law's at kn)");
    if (last["tc_time"].value == "tau_c") {
      if (!has("kn")) throw InputError(named(last["tc_time"]) + ": tau_c is the soft law's at kn: give kn");
      s.tc_time = law_at(o.kn, s.disk).tau_c;
    } else {
      s.tc_time = within(last["tc_time"], 0.0, true, INFINITY, true, "(0, inf), or tau_c");
    }
    if (has("tc_beta")) s.tc_beta = within(last["tc_beta"], -1.0, false, 1.0, false, "[-1, 1]");
  }
  if (has("collapse_count")) {
    const double n = within(last["collapse_count"], 1.0, false, 1e9, false, "[1, 1e9]");
    if (n != std::floor(n)) throw InputError(named(last["collapse_count"]) + " must be a whole number");
    s.collapse_count = static_cast<int>(n);
  }
  if (has("collapse_time")) s.collapse_time = within(last["collapse_time"], 0.0, true, INFINITY, true, "(0, inf)");

  if (has("seed")) o.seed = last["seed"].value;
  if (has("output_interval")) {
    o.interval = within(last["output_interval"], 0.0, true, INFINITY, true, "(0, inf)");
    if (!has("out")) throw InputError(named(last["output_interval"]) + ": the sampled outputs go to out=DIR: give out");
    if (!has("kn"))
      throw InputError(named(last["output_interval"]) + ": params.txt names the soft law's tau_c and tau_w at the k_n this run stands for: give kn");
    for (const char *name : {"profile_lo", "profile_hi"})
      if (!has(name)) throw InputError(named(last["output_interval"]) + ": profile.txt's bins need " + name + " (the deck's box)");
  } else {
    for (const char *name : {"average_start", "profile_bin", "profile_lo", "profile_hi"})
      if (has(name)) throw InputError(named(last[name]) + ": " + name + " applies to the sampled outputs only: give output_interval");
  }
  if (has("average_start"))
    o.average_start = within(last["average_start"], 0.0, false, run.run_time, true, "[0, run_time)");
  if (has("profile_bin")) o.profile_bin = within(last["profile_bin"], 0.0, true, INFINITY, true, "(0, inf)");
  if (has("profile_lo")) o.profile_lo = finite(last["profile_lo"]);
  if (has("profile_hi")) {
    o.profile_hi = finite(last["profile_hi"]);
    if (!(o.profile_hi > o.profile_lo))
      throw InputError(named(last["profile_hi"]) + " must be greater than profile_lo = " + last["profile_lo"].value);
  }
  return run;
}

}    // namespace ed
}    // namespace mn
