// mn-event-driven: runs the event-driven hard-disk engine on a start.
//   mn-event-driven [PARAMETER_FILE ...] [name=value ...]
// Parameters (settings.h; later ones override earlier ones): start=FILE (box, floor, disk and
// bump lines, start.h), run_time=T, events=N, out=DIR, scene=NAME, rule=paper|soft,
// tangential=literal|cutback, e, beta, mu, e_w, beta_w, g, sin_theta, collapse=stop|tc,
// tc_time (a time, or tau_c: the soft law's at kn), tc_beta, collapse_count, collapse_time;
// kn (the soft run's k_n the run stands for), seed (the deck's, for params.txt);
// output_interval, average_start, profile_bin, profile_lo, profile_hi: with out, the files a
// LAMMPS run of the scene writes (outputs.h).
// Exit status: 0 the run reached run_time (or events); 1 a refused input or a failed run;
// 3 an inelastic collapse ended the run (its report on stderr and, with out, in collapse.txt;
// summary.txt says "end collapse").
#include "engine.h"
#include "outputs.h"

#include <ctime>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

namespace {

const char *stop_name(mn::ed::Engine::Stop stop)
{
  switch (stop) {
    case mn::ed::Engine::Stop::Time: return "time";
    case mn::ed::Engine::Stop::Events: return "events";
    case mn::ed::Engine::Stop::Collapse: return "collapse";
  }
  return "";
}

void write_summary(std::ostream &out, const mn::ed::Engine &engine, mn::ed::Engine::Stop stop,
                   double setup_cpu, double cpu)
{
  const mn::ed::Totals &t = engine.totals();
  const std::uint64_t collisions = t.disk_collisions + t.boundary_collisions;
  out.precision(17);
  out << "end " << stop_name(stop) << "\n"
      << "time " << engine.time() << "\n"
      << "events " << t.events << "\n"
      << "disk_collisions " << t.disk_collisions << "\n"
      << "boundary_collisions " << t.boundary_collisions << "\n"
      << "tc_collisions " << t.tc_collisions << "\n"
      << "tc_fraction " << (collisions ? double(t.tc_collisions) / collisions : 0.0) << "\n"
      << "cell_crossings " << t.cell_crossings << "\n"
      << "invalid_predictions " << t.invalid_predictions << "\n"
      << "grazing " << t.grazing << "\n"
      << "largest_overlap " << t.largest_overlap << "\n"
      << "setup_cpu_seconds " << setup_cpu << "\n"
      << "cpu_seconds " << cpu << "\n";
}

}    // namespace

int main(int argc, char **argv)
{
  using namespace mn::ed;
  if (argc < 2 || std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help") {
    std::cerr << "usage: mn-event-driven [PARAMETER_FILE ...] [name=value ...]\n"
                 "  start=FILE run_time=T [events=N] [out=DIR] [scene=NAME] [rule=paper|soft]\n"
                 "  [tangential=literal|cutback] [e beta mu e_w beta_w g sin_theta]\n"
                 "  [collapse=stop|tc] [tc_time tc_beta collapse_count collapse_time]\n"
                 "  [kn seed] [output_interval average_start profile_bin profile_lo profile_hi]\n";
    return argc < 2 ? 1 : 0;
  }
  try {
    std::vector<Parameter> parameters;
    for (int k = 1; k < argc; k++) {
      const std::string arg = argv[k];
      const std::size_t eq = arg.find('=');
      if (eq == std::string::npos) {
        const std::vector<Parameter> from_file = read_parameter_file(arg);
        parameters.insert(parameters.end(), from_file.begin(), from_file.end());
      } else {
        parameters.push_back({arg.substr(0, eq), arg.substr(eq + 1), "the command line"});
      }
    }
    const RunRequest run = parse_run(parameters);
    const Start start = read_start(run.start_path);
    // the setup (rule (b)'s tables, the cells) and the run, timed apart
    const std::clock_t begin = std::clock();
    Engine engine(start, run.settings);
    const double setup_cpu = double(std::clock() - begin) / CLOCKS_PER_SEC;
    const std::clock_t running = std::clock();
    if (!run.out.empty()) std::filesystem::create_directories(run.out);
    const Engine::Stop stop = run.outputs.interval > 0.0 ? run_sampled(engine, run)
                                                         : engine.run(run.run_time, run.max_events);
    const double cpu = double(std::clock() - running) / CLOCKS_PER_SEC;
    write_summary(std::cout, engine, stop, setup_cpu, cpu);
    if (!run.out.empty()) {
      std::ofstream summary(run.out + "/summary.txt");
      write_summary(summary, engine, stop, setup_cpu, cpu);
      if (engine.collapse()) std::ofstream(run.out + "/collapse.txt") << engine.collapse()->describe() << "\n";
    }
    if (stop == Engine::Stop::Collapse) {
      const CollapseReport &c = *engine.collapse();
      std::cerr << "ERROR: " << c.describe()
                << (run.settings.on_collapse == OnCollapse::Stop
                        ? " (collapse = stop; collapse = tc with tc_time > 0 continues under the TC model)"
                        : c.grazing ? " (under the TC model: a lasting contact, which no restitution makes into collisions)"
                                    : " (under the TC model: tc_time is too short to prevent it)")
                << "\n";
      return 3;
    }
    return 0;
  } catch (const InputError &e) {
    std::cerr << "ERROR: " << e.what() << "\n";
    return 1;
  } catch (const std::exception &e) {
    std::cerr << "ERROR: " << e.what() << "\n";
    return 1;
  }
}
