/* ----------------------------------------------------------------------
   Registers the gran/mn styles with LAMMPS's PLUGIN package:
   plugin load granmnplugin.so
------------------------------------------------------------------------- */

#include "lammpsplugin.h"
#include "version.h"

#include "fix_atom_ids.h"
#include "fix_ave_window_mn.h"
#include "fix_checkpoint_mn.h"
#include "fix_contacts_mn.h"
#include "fix_nve_disc_mn.h"
#include "fix_wall_gran_mn.h"
#include "fix_wall_gran_region_mn.h"
#include "pair_gran_mn.h"

using namespace LAMMPS_NS;

static Pair *pair_gran_mn_creator(LAMMPS *lmp)
{
  return new PairGranMN(lmp);
}

template <class FixStyle> static Fix *fix_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixStyle(lmp, argc, argv);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto register_plugin = (lammpsplugin_regfunc) regfunc;
  lammpsplugin_t plugin;
  plugin.version = LAMMPS_VERSION;
  plugin.author = "granmn project";
  plugin.handle = handle;

  plugin.style = "pair";
  plugin.name = "gran/mn";
  plugin.info = "Mitarai-Nakanishi linear spring-dashpot granular pair style (2D disks, 3D spheres)";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &pair_gran_mn_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "fix";
  const struct {
    const char *name, *info;
    lammpsplugin_factory2 *creator;
  } fixes[] = {
      {"wall/gran/mn", "Flat walls (2D, 3D) with the Mitarai-Nakanishi boundary contact law",
       (lammpsplugin_factory2 *) &fix_creator<FixWallGranMN>},
      {"wall/gran/region/mn",
       "A region's surface as a wall (2D, 3D; moving, rotating) with the Mitarai-Nakanishi "
       "boundary contact law",
       (lammpsplugin_factory2 *) &fix_creator<FixWallGranRegionMN>},
      {"contacts/mn", "Per-contact counters for the gran/mn styles",
       (lammpsplugin_factory2 *) &fix_creator<FixContactsMN>},
      {"nve/ab2", "Adams-Bashforth 2 / trapezoidal integrator for disks (Mitarai-Nakanishi)",
       (lammpsplugin_factory2 *) &fix_creator<FixNVEDiscMN>},
      {"nve/disc/mn", "Velocity Verlet or Adams-Bashforth 2 for 2D disks, with gravity, in one pass",
       (lammpsplugin_factory2 *) &fix_creator<FixNVEDiscMN>},
      {"checkpoint/mn", "A run's identity in its restart files, checked on resuming",
       (lammpsplugin_factory2 *) &fix_creator<FixCheckpointMN>},
      {"ave/window/mn", "A windowed time average of a variable, its window in restart files",
       (lammpsplugin_factory2 *) &fix_creator<FixAveWindowMN>},
      {"GRANMN/ATOM_IDS", "internal to pair_style gran/mn: each atom's ID, carried with it",
       (lammpsplugin_factory2 *) &fix_creator<FixAtomIDs>}};
  for (const auto &fix : fixes) {
    plugin.name = fix.name;
    plugin.info = fix.info;
    plugin.creator.v2 = fix.creator;
    (*register_plugin)(&plugin, lmp);
  }
}
