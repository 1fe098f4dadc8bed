/* ----------------------------------------------------------------------
   fix ave/window/mn: a windowed time average of an equal-style variable whose window is kept
   in restart files.
------------------------------------------------------------------------- */

#include "fix_ave_window_mn.h"

#include "comm.h"
#include "error.h"
#include "input.h"
#include "modify.h"
#include "update.h"
#include "utils.h"
#include "variable.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

// fix ID group ave/window/mn N M v_name [resume yes|no]
FixAveWindowMN::FixAveWindowMN(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), ivariable(-1), next(0), full(false), total(0.0), last_sampled(-1),
    resume(false), restored(false)
{
  if (narg < 6) error->all(FLERR, "Illegal fix ave/window/mn command: needs N M v_name");
  nevery = utils::inumeric(FLERR, arg[3], false, lmp);
  const int window = utils::inumeric(FLERR, arg[4], false, lmp);
  if (nevery <= 0) error->all(FLERR, "Illegal fix ave/window/mn command: N = {} must be > 0", nevery);
  if (window <= 0) error->all(FLERR, "Illegal fix ave/window/mn command: M = {} must be > 0", window);
  if (strncmp(arg[5], "v_", 2) != 0 || arg[5][2] == '\0')
    error->all(FLERR, "Illegal fix ave/window/mn command: {} is not v_name (an equal-style "
                      "variable)", arg[5]);
  variable = arg[5] + 2;
  samples.assign(window, 0.0);
  int iarg = 6;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "resume") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "Illegal fix ave/window/mn command: resume needs yes or no");
      if (strcmp(arg[iarg + 1], "yes") != 0 && strcmp(arg[iarg + 1], "no") != 0)
        error->all(FLERR, "Illegal fix ave/window/mn command: resume {}: yes or no", arg[iarg + 1]);
      resume = strcmp(arg[iarg + 1], "yes") == 0;
      iarg += 2;
    } else {
      error->all(FLERR, "Illegal fix ave/window/mn command: unknown keyword {}", arg[iarg]);
    }
  }
  scalar_flag = 1;
  extscalar = 0;
  global_freq = nevery;
  restart_global = 1;
}

int FixAveWindowMN::setmask()
{
  return END_OF_STEP;
}

void FixAveWindowMN::init()
{
  ivariable = input->variable->find(variable.c_str());
  if (ivariable < 0)
    error->all(FLERR, "Fix ave/window/mn: variable {} does not exist", variable);
  if (!input->variable->equalstyle(ivariable))
    error->all(FLERR, "Fix ave/window/mn: variable {} is not equal-style", variable);
  // a window begun afresh at the resumed step would decide otherwise than the run it continues
  if (resume && !restored)
    error->all(FLERR, "Fix ave/window/mn: the restart file holds no window of fix {} "
                      "(ave/window/mn): it cannot continue this run's average", id);
}

// A run's first step, if it falls on the N-step grid, is sampled here, once: the next run of
// a sequence begins at the step the last one sampled at its end, a resumed run at the step its
// restart file sampled last (fix ave/time samples so too).
void FixAveWindowMN::setup(int)
{
  if (update->ntimestep % nevery == 0 && update->ntimestep != last_sampled) sample();
}

void FixAveWindowMN::end_of_step()
{
  if (update->ntimestep != last_sampled) sample();
}

// The sum in fix ave/time's order (the new sample added, then the oldest taken off), so that
// the mean is bitwise fix ave/time's.
void FixAveWindowMN::sample()
{
  modify->clearstep_compute();
  const double value = input->variable->compute_equal(ivariable);
  modify->addstep_compute((update->ntimestep / nevery + 1) * nevery);
  total += value;
  if (full) total -= samples[next];
  samples[next] = value;
  if (++next == (int) samples.size()) {
    next = 0;
    full = true;
  }
  last_sampled = update->ntimestep;
}

// The mean over the samples in the window (0 before the first).
double FixAveWindowMN::compute_scalar()
{
  const int count = full ? (int) samples.size() : next;
  return count ? total / count : 0.0;
}

// Record: N, M, next, full, total, the last sampled step, then the M samples, all as doubles.
static constexpr int HEAD = 6;

void FixAveWindowMN::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  std::vector<double> record = {(double) nevery, (double) samples.size(), (double) next,
                                full ? 1.0 : 0.0, total, (double) last_sampled};
  record.insert(record.end(), samples.begin(), samples.end());
  const int size = record.size() * sizeof(double);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(record.data(), sizeof(double), record.size(), fp);
}

void FixAveWindowMN::restart(char *buf)
{
  double head[HEAD];
  memcpy(head, buf, sizeof(head));
  if (head[0] != nevery || head[1] != (double) samples.size())
    error->all(FLERR, "Fix ave/window/mn: the restart file's window of fix {} is {} samples "
                      "every {} steps, this fix's {} every {}: it cannot continue it",
               id, head[1], head[0], samples.size(), nevery);
  next = (int) head[2];
  full = head[3] != 0.0;
  total = head[4];
  last_sampled = (bigint) head[5];
  memcpy(samples.data(), buf + sizeof(head), samples.size() * sizeof(double));
  restored = true;
}
