/* ----------------------------------------------------------------------
   Registers the gran/mn styles with LAMMPS's PLUGIN package:
   plugin load granmnplugin.so
------------------------------------------------------------------------- */

#include "lammpsplugin.h"
#include "version.h"

#include "fix_contacts_mn.h"
#include "fix_nve_ab2.h"
#include "fix_wall_gran_mn.h"
#include "pair_gran_mn.h"

using namespace LAMMPS_NS;

static Pair *pair_gran_mn_creator(LAMMPS *lmp)
{
  return new PairGranMN(lmp);
}

static Fix *fix_contacts_mn_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixContactsMN(lmp, argc, argv);
}

static Fix *fix_nve_ab2_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixNVEAB2(lmp, argc, argv);
}

static Fix *fix_wall_gran_mn_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixWallGranMN(lmp, argc, argv);
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
  plugin.info = "Mitarai-Nakanishi 2D linear spring-dashpot granular pair style";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &pair_gran_mn_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "wall/gran/mn";
  plugin.info = "Flat walls with the Mitarai-Nakanishi boundary contact law";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_wall_gran_mn_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "contacts/mn";
  plugin.info = "Per-contact counters for the gran/mn styles";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_contacts_mn_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "nve/ab2";
  plugin.info = "Adams-Bashforth 2 / trapezoidal integrator for disks (Mitarai-Nakanishi)";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_nve_ab2_creator;
  (*register_plugin)(&plugin, lmp);
}
