/* ----------------------------------------------------------------------
   fix checkpoint/mn: a run's identity (its point and the plugin's restart layout) in its
   restart files, checked when a run resumes from one.
------------------------------------------------------------------------- */

#include "fix_checkpoint_mn.h"

#include "comm.h"
#include "error.h"

#include <cstring>
#include <vector>

using namespace LAMMPS_NS;

// fix ID group checkpoint/mn SIGNATURE [resume FILE]
FixCheckpointMN::FixCheckpointMN(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), restored(false)
{
  if (narg < 4) error->all(FLERR, "Illegal fix checkpoint/mn command: needs a signature");
  signature = arg[3];
  if (signature.empty()) error->all(FLERR, "Illegal fix checkpoint/mn command: empty signature");
  int iarg = 4;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "resume") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "Illegal fix checkpoint/mn command: resume needs a file name");
      resume = arg[iarg + 1];
      iarg += 2;
    } else {
      error->all(FLERR, "Illegal fix checkpoint/mn command: unknown keyword {}", arg[iarg]);
    }
  }
  restart_global = 1;
}

// A resumed run whose restart file had no record of this fix did not come from a checkpoint of
// these decks (or the fix ID changed): its state cannot be trusted to be this point's.
void FixCheckpointMN::init()
{
  if (!resume.empty() && !restored)
    error->all(FLERR,
               "Fix checkpoint/mn: restart file {} holds no fix {} (checkpoint/mn): it is not a "
               "checkpoint of a granmn run",
               resume, id);
}

// Layout: the restart layout number, the signature's length, then its characters, all as
// doubles (one per character), so that the record is a plain array of doubles.
void FixCheckpointMN::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  std::vector<double> record = {(double) GRANMN_RESTART_LAYOUT, (double) signature.size()};
  for (char c : signature) record.push_back((double) (unsigned char) c);
  const int size = record.size() * sizeof(double);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(record.data(), sizeof(double), record.size(), fp);
}

void FixCheckpointMN::restart(char *buf)
{
  const std::string file = resume.empty() ? std::string("the restart file") : resume;
  double head[2];
  memcpy(head, buf, sizeof(head));
  if (head[0] < GRANMN_RESTART_LAYOUT_OLDEST_READ || head[0] > GRANMN_RESTART_LAYOUT)
    error->all(FLERR,
               "Fix checkpoint/mn: {} was written with restart layout {} of the gran/mn styles, "
               "this plugin reads layouts {} to {}: start the point afresh",
               file, head[0], GRANMN_RESTART_LAYOUT_OLDEST_READ, GRANMN_RESTART_LAYOUT);
  std::string stored(static_cast<size_t>(head[1]), ' ');
  std::vector<double> chars(stored.size());
  memcpy(chars.data(), buf + sizeof(head), chars.size() * sizeof(double));
  for (size_t k = 0; k < stored.size(); k++) stored[k] = (char) (int) chars[k];
  if (stored != signature)
    error->all(FLERR, "Fix checkpoint/mn: {} is a checkpoint of point '{}', not of this run's "
                      "point '{}'",
               file, stored, signature);
  restored = true;
}
