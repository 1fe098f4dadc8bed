// Every refusal of the event-driven engine, one test each: a clear error that names the input
// (the parameter and where it was given, or the start file's line), never a crash or a run on
// wrong input; and the executable's exit status for a refused input and for a collapse under
// collapse = stop (outputs kept and marked).
#include "engine.h"
#include "scenes.h"
#include "settings.h"
#include "start.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using mn::ed::InputError;
using mn::ed::Parameter;

std::vector<Parameter> with(std::vector<Parameter> extra)
{
  std::vector<Parameter> p{{"start", "some.start", "the command line"},
                           {"run_time", "10", "the command line"}};
  for (Parameter &e : extra)
    if (e.origin.empty()) e.origin = "the command line";
  p.insert(p.end(), extra.begin(), extra.end());
  return p;
}

// The parameters are refused with a message that contains every one of `words`.
void refused(const std::vector<Parameter> &parameters, const std::vector<std::string> &words)
{
  try {
    mn::ed::parse_run(parameters);
    ADD_FAILURE() << "accepted";
  } catch (const InputError &e) {
    const std::string what = e.what();
    for (const std::string &w : words) EXPECT_NE(what.find(w), std::string::npos) << what << "\n  lacks: " << w;
  }
}

// A file of its own for each test (ctest runs them in parallel).
std::string temporary(const std::string &name, const std::string &text)
{
  const std::string path = ::testing::TempDir() + "mn_ed_" +
      ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" + name;
  std::ofstream(path) << text;
  return path;
}

// The start file is refused (by the reader or by the engine) with a message containing `words`.
void start_refused(const std::string &text, const std::vector<std::string> &words)
{
  const std::string path = temporary("refused.start", text);
  try {
    const mn::ed::Start start = mn::ed::read_start(path);
    mn::ed::Engine engine(start, mn::ed::Settings());
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const InputError &e) {
    const std::string what = e.what();
    for (const std::string &w : words) EXPECT_NE(what.find(w), std::string::npos) << what << "\n  lacks: " << w;
  }
}

}    // namespace

TEST(BadInput, EOutOfRange)
{
  refused(with({{"e", "1.5", ""}}), {"e = 1.5", "the command line", "(0, 1]"});
  refused(with({{"e", "0", ""}}), {"e = 0", "(0, 1]"});
}

TEST(BadInput, BetaOutOfRange)
{
  refused(with({{"beta", "-1.2", ""}}), {"beta = -1.2", "[-1, 1]"});
  // rule (b) is the soft law's limit: beta in the law's range
  refused(with({{"rule", "soft", ""}, {"beta", "-0.5", ""}}), {"beta = -0.5", "(0, 1] under rule soft"});
}

TEST(BadInput, EwOutOfRange)
{
  refused(with({{"e_w", "1.01", ""}}), {"e_w = 1.01", "(0, 1]"});
  refused(with({{"e_w", "-0.1", ""}}), {"e_w = -0.1"});
}

TEST(BadInput, BetaWOutOfRange) { refused(with({{"beta_w", "2", ""}}), {"beta_w = 2", "[-1, 1]"}); }

TEST(BadInput, MuNegative) { refused(with({{"mu", "-0.1", ""}}), {"mu = -0.1", "[0, inf)"}); }

TEST(BadInput, NonFiniteValues)
{
  refused(with({{"e", "nan", ""}}), {"e = nan", "finite"});
  refused(with({{"sin_theta", "inf", ""}}), {"sin_theta = inf", "finite"});
  refused({{"start", "x", "a.txt line 1"}, {"run_time", "-inf", "a.txt line 2"}}, {"run_time = -inf", "a.txt line 2", "finite"});
}

TEST(BadInput, NotANumber) { refused(with({{"mu", "0.5x", ""}}), {"mu = 0.5x", "not a number"}); }

TEST(BadInput, OtherValuesOutOfRange)
{
  refused(with({{"sin_theta", "1.5", ""}}), {"sin_theta = 1.5", "[-1, 1]"});
  refused(with({{"g", "-1", ""}}), {"g = -1"});
  refused(with({{"run_time", "0", ""}}), {"run_time = 0"});
  refused(with({{"events", "2.5", ""}}), {"events = 2.5", "whole"});
  refused(with({{"collapse_count", "0", ""}}), {"collapse_count = 0"});
  refused(with({{"collapse_time", "0", ""}}), {"collapse_time = 0"});
  refused(with({{"collapse", "tc", ""}, {"tc_time", "1e-4", ""}, {"tc_beta", "1.5", ""}}), {"tc_beta = 1.5"});
}

TEST(BadInput, UnknownRule) { refused(with({{"rule", "walton", ""}}), {"rule = walton", "unknown rule", "paper or soft"}); }

TEST(BadInput, UnknownScene)
{
  refused(with({{"scene", "chute", ""}}), {"scene = chute", "unknown scene", "collisional_flow"});
}

TEST(BadInput, UnknownTangentialReading)
{
  refused(with({{"rule", "soft", ""}, {"tangential", "history", ""}}), {"tangential = history", "literal or cutback"});
}

TEST(BadInput, UnknownCollapseChoice) { refused(with({{"collapse", "continue", ""}}), {"collapse = continue", "stop or tc"}); }

TEST(BadInput, UnknownParameter) { refused(with({{"k_n", "1e5", "p.txt line 4"}}), {"unknown parameter 'k_n'", "p.txt line 4"}); }

// The sampled outputs (outputs.h) need a directory, the k_n whose tau_c and tau_w params.txt
// names, and the box's heights for the profile; their parameters mean nothing without them.
TEST(BadInput, SampledOutputsWithoutWhatTheyNeed)
{
  const std::vector<Parameter> box{{"profile_lo", "-1", ""}, {"profile_hi", "60", ""}};
  auto plus = [&](std::vector<Parameter> p) {
    p.insert(p.end(), box.begin(), box.end());
    return with(p);
  };
  refused(plus({{"output_interval", "0.1", ""}, {"kn", "1e7", ""}}), {"output_interval = 0.1", "give out"});
  refused(plus({{"output_interval", "0.1", ""}, {"out", "d", ""}}), {"output_interval = 0.1", "give kn"});
  refused(with({{"output_interval", "0.1", ""}, {"out", "d", ""}, {"kn", "1e7", ""}}), {"profile_lo"});
  refused(with({{"average_start", "5", ""}}), {"average_start = 5", "give output_interval"});
  refused(plus({{"output_interval", "0.1", ""}, {"out", "d", ""}, {"kn", "1e7", ""}, {"average_start", "10", ""}}),
          {"average_start = 10", "[0, run_time)"});
  refused(with({{"output_interval", "0.1", ""}, {"out", "d", ""}, {"kn", "1e7", ""}, {"profile_lo", "2", ""},
                {"profile_hi", "1", ""}}),
          {"profile_hi = 1", "greater than profile_lo"});
}

TEST(BadInput, KnOutOfRange)
{
  refused(with({{"kn", "0", ""}}), {"kn = 0", "(0, inf)"});
  refused(with({{"kn", "1e308", ""}}), {"kn = 1e308", "kn is too large"});
}

TEST(BadInput, TcTimeTauCWithoutKn)
{
  refused(with({{"collapse", "tc", ""}, {"tc_time", "tau_c", ""}}), {"tc_time = tau_c", "give kn"});
  refused(with({{"collapse", "tc", ""}, {"tc_time", "short", ""}}), {"tc_time = short", "not a number"});
}

TEST(BadInput, ParameterOfTheOtherRule)
{
  refused(with({{"rule", "soft", ""}, {"e_w", "0.8", ""}}), {"e_w = 0.8", "rule paper only"});
  refused(with({{"tangential", "cutback", ""}}), {"tangential = cutback", "rule soft only"});
}

TEST(BadInput, TcParametersWithoutTheTcModel)
{
  refused(with({{"tc_time", "1e-4", ""}}), {"tc_time = 1e-4", "collapse = tc only"});
  refused(with({{"collapse", "tc", ""}}), {"collapse = tc", "needs tc_time"});
}

TEST(BadInput, MissingStartOrRunTime)
{
  refused({{"run_time", "1", "the command line"}}, {"no start"});
  refused({{"start", "a", "the command line"}}, {"no run_time"});
}

TEST(BadInput, ParameterFileLine)
{
  const std::string path = temporary("bad.params", "e 0.7\nbeta\n");
  try {
    mn::ed::read_parameter_file(path);
    ADD_FAILURE() << "accepted";
  } catch (const InputError &e) {
    EXPECT_NE(std::string(e.what()).find("bad.params line 2"), std::string::npos) << e.what();
  }
}

TEST(BadInput, OverlappingDisks)
{
  start_refused("box 0 10\nfloor 0\ndisk 2 3 0 0 0 1\ndisk 2.9 3 0 0 0 1\n",
                {"line 3", "overlaps disk 1", "line 4", "apart"});
}

TEST(BadInput, DiskOutsideTheBox)
{
  start_refused("box 0 10\nfloor 0\ndisk 10 3 0 0 0 1\n", {"line 3", "outside the box"});
  start_refused("box 0 10\nfloor 0\ndisk -0.1 3 0 0 0 1\n", {"line 3", "outside the box"});
}

TEST(BadInput, DiskBelowTheFloor) { start_refused("box 0 10\nfloor 0\ndisk 5 0.4 0 0 0 1\n", {"line 3", "below the floor"}); }

TEST(BadInput, DiskInsideABump)
{
  start_refused("box 0 10\nbump 5 0 1\ndisk 5.3 0.9 0 0 0 1\n", {"line 3", "inside bump 0", "line 2"});
}

TEST(BadInput, NonFiniteStart) { start_refused("box 0 10\nfloor 0\ndisk 5 nan 0 0 0 1\n", {"line 3", "must be finite"}); }

TEST(BadInput, MalformedStartLines)
{
  start_refused("box 0 10\nball 1 2 3\n", {"line 2", "unknown line 'ball'"});
  start_refused("box 0 10\ndisk 1 2 3\n", {"line 2", "takes 6 values"});
  start_refused("floor 0\ndisk 5 3 0 0 0 1\n", {"no 'box XLO XHI' line"});
  start_refused("box 0 10\nfloor 0\n", {"no disks"});
  start_refused("box 0 10\ndisk 5 3 0 0 0 0\n", {"line 2", "DIAMETER = 0"});
  start_refused("box 5 5\n", {"line 1", "greater than XLO"});
}

TEST(BadInput, BoxTooShortForTheCells) { start_refused("box 0 2.5\nfloor 0\ndisk 1 3 0 0 0 1\n", {"at least 3 times"}); }

TEST(BadInput, MissingStartFile)
{
  EXPECT_THROW(mn::ed::read_start("/nonexistent/x.start"), InputError);
}

// A disk that passes between bumps further apart than its diameter leaves the slope: the run
// stops with an error (as LAMMPS does for a lost atom) rather than letting it fall for ever.
TEST(BadInput, DiskFallsThroughTheSlope)
{
  mn::ed::Start s;
  s.origin = "gaps";
  s.xhi = 12.0;
  for (int k = 0; k < 4; k++) s.bumps.push_back({3.0 * k, 0.0, 1.0, "bump"});
  s.disks = {scenes::disk(1.5, 3.0, 0, 0, 0, 0.9)};
  mn::ed::Engine engine(s, mn::ed::Settings());
  try {
    engine.run(20.0);
    ADD_FAILURE() << "ran on";
  } catch (const std::runtime_error &e) {
    EXPECT_NE(std::string(e.what()).find("fell through the slope"), std::string::npos) << e.what();
  }
}

#ifdef MN_EVENT_DRIVEN_EXE
namespace {

int run_executable(const std::string &arguments, std::string *stderr_text)
{
  const std::string err = ::testing::TempDir() + "mn_ed_" +
      ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_stderr.txt";
  const int status = std::system((std::string(MN_EVENT_DRIVEN_EXE) + " " + arguments + " > /dev/null 2> " + err).c_str());
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  *stderr_text = text.str();
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string file_text(const std::string &path)
{
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}    // namespace

TEST(BadInput, ExecutableRefusesWithStatus1)
{
  const std::string start = temporary("ball.start", "box -3 3\nfloor 0\ndisk 0 1.5 0 0 0 1\n");
  std::string err;
  EXPECT_EQ(run_executable("start=" + start + " run_time=10 e=2", &err), 1);
  EXPECT_NE(err.find("ERROR: e = 2 (the command line) is out of range"), std::string::npos) << err;
}

// collapse = stop: the run ends at the collapse with exit status 3, the report on stderr and in
// collapse.txt, and summary.txt kept and marked "end collapse".
TEST(BadInput, CollapseUnderStopEndsWithStatus3AndKeepsOutputs)
{
  const std::string start = temporary("ball.start", "box -3 3\nfloor 0\ndisk 0 1.5 0 0 0 1\n");
  const std::string out = ::testing::TempDir() + "mn_ed_collapsed";
  std::string err;
  EXPECT_EQ(run_executable("start=" + start + " run_time=100 e_w=0.7 out=" + out, &err), 3);
  EXPECT_NE(err.find("inelastic collapse at t = 8.01387685344"), std::string::npos) << err;
  EXPECT_NE(file_text(out + "/summary.txt").find("end collapse"), std::string::npos);
  EXPECT_NE(file_text(out + "/collapse.txt").find("partners: the floor x 101"), std::string::npos);
  // under the TC model the same ball runs to the end
  EXPECT_EQ(run_executable("start=" + start + " run_time=100 e_w=0.7 collapse=tc tc_time=1e-3", &err), 0) << err;
}
#endif
