/* -*- c++ -*- ----------------------------------------------------------
   fix ave/window/mn: the mean of an equal-style variable over its last M samples, one every
   N steps, as fix ave/time N 1 N v_name ave window M computes it, with the window in restart
   files, so that a run resumed from one goes on with the window it had.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_AVE_WINDOW_MN_H
#define LMP_FIX_AVE_WINDOW_MN_H

#include "fix.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixAveWindowMN : public Fix {
 public:
  FixAveWindowMN(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  double compute_scalar() override;
  void write_restart(FILE *) override;
  void restart(char *) override;

 private:
  std::string variable;         // the variable's name (without v_)
  int ivariable;                // its index, set at init
  std::vector<double> samples;  // the last M samples, a ring: samples[next] is the oldest
  int next;                     // where the next sample goes
  bool full;                    // M samples taken: each new one replaces the oldest
  double total;                 // the running sum of the samples in the window
  bigint last_sampled;          // the step of the last sample (-1: none yet)
  bool resume;                  // the run resumes from a restart file: it must hold the window
  bool restored;                // restart() found this fix's record

  void sample();
};

}    // namespace LAMMPS_NS

#endif
