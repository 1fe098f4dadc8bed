/* -*- c++ -*- ----------------------------------------------------------
   fix checkpoint/mn: the identity of a run in its restart files, so that a run resumed from a
   checkpoint refuses one written for another point or by another restart layout of the plugin.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_CHECKPOINT_MN_H
#define LMP_FIX_CHECKPOINT_MN_H

#include "fix.h"

#include <string>

namespace LAMMPS_NS {

// What the gran/mn styles write to restart files, as one number: raise it whenever any of
// them changes what it writes or how it reads it back (per-atom columns of the fixes, the pair
// history, fix contacts/mn's clock), so that a plugin that cannot read a checkpoint refuses it.
// A plugin reads the layouts from GRANMN_RESTART_LAYOUT_OLDEST_READ on: 2 holds fix
// wall/gran/mn's rows in slots, which that fix also reads from a file of layout 1.
constexpr int GRANMN_RESTART_LAYOUT = 2;
constexpr int GRANMN_RESTART_LAYOUT_OLDEST_READ = 1;

class FixCheckpointMN : public Fix {
 public:
  FixCheckpointMN(class LAMMPS *, int, char **);
  int setmask() override { return 0; }
  void init() override;
  void write_restart(FILE *) override;
  void restart(char *) override;

 private:
  std::string signature;    // the run's point, as the deck words it
  std::string resume;       // the restart file this run resumed from, "" if none
  bool restored;            // restart() found this fix's record in the restart file
};

}    // namespace LAMMPS_NS

#endif
