/* -*- c++ -*- ----------------------------------------------------------
   The law's keywords on a gran/mn style's line (kn, e, beta, mu, limit_damping,
   coulomb_cutback), the law they give, checked, and how the wall fix takes the pair style's.
------------------------------------------------------------------------- */

#ifndef LMP_GRANMN_LAW_ARGUMENTS_H
#define LMP_GRANMN_LAW_ARGUMENTS_H

#include "domain.h"
#include "error.h"
#include "force.h"
#include "lammps.h"
#include "pair.h"
#include "utils.h"

#include "mn_contact.h"

#include <cstring>
#include <string>

namespace granmn {

// The name under which pair_style gran/mn hands out its law through Pair::extract (a
// const mn::Law *, dim 0; read only): the wall fixes take what their line does not give.
constexpr const char *LAW_EXTRACT_NAME = "granmn_law";

// The shape of inertia the law is derived for (mn::derive's q): the dimension decides it, as
// it decides what atom_style sphere's particles are. In 2D disks (I = m r^2/2, the paper's
// law), in 3D solid spheres (I = 2 m r^2/5, what fix nve/sphere integrates in 3D).
inline double dimension_q(LAMMPS_NS::LAMMPS *lmp)
{
  return lmp->domain->dimension == 3 ? mn::SOLID_SPHERE_Q : mn::DISC_Q;
}

// The law's keywords on a style's line: a number of the material, or an option (a flag).
struct LawKeyword {
  const char *name;
  double mn::Material::*number;
  bool mn::Options::*option;
};
constexpr LawKeyword LAW_KEYWORDS[] = {
    {"kn", &mn::Material::kn, nullptr},     {"e", &mn::Material::e, nullptr},
    {"beta", &mn::Material::beta, nullptr}, {"mu", &mn::Material::mu, nullptr},
    {"limit_damping", nullptr, &mn::Options::limit_damping},
    {"coulomb_cutback", nullptr, &mn::Options::coulomb_cutback}};
constexpr int N_LAW_KEYWORDS = sizeof(LAW_KEYWORDS) / sizeof(LAW_KEYWORDS[0]);

// The law keywords a style's arguments hold: their values, and which were given.
struct LawArguments {
  mn::Material material{0.0, 0.0, 0.0, 0.0};
  mn::Options options;
  bool given[N_LAW_KEYWORDS] = {};

  bool all_numbers_given() const
  {
    for (int k = 0; k < N_LAW_KEYWORDS; k++)
      if (LAW_KEYWORDS[k].number && !given[k]) return false;
    return true;
  }
};

// Reads the law keyword at arg[iarg] ("kn K", ..., "limit_damping"); returns how many
// arguments it used, 0 if arg[iarg] is none of them.
inline int parse_law_keyword(LAMMPS_NS::LAMMPS *lmp, const char *command, int narg, char **arg,
                             int iarg, LawArguments &law)
{
  for (int k = 0; k < N_LAW_KEYWORDS; k++) {
    const LawKeyword &keyword = LAW_KEYWORDS[k];
    if (strcmp(arg[iarg], keyword.name) != 0) continue;
    if (keyword.option) {
      law.options.*keyword.option = law.given[k] = true;
      return 1;
    }
    if (law.given[k])
      lmp->error->all(FLERR, "Illegal {} command: {} given twice", command, keyword.name);
    law.given[k] = true;
    if (iarg + 2 > narg)
      lmp->error->all(FLERR, "Illegal {} command: {} needs a value", command, keyword.name);
    law.material.*keyword.number = LAMMPS_NS::utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    return 2;
  }
  return 0;
}

// The law of a material and options for particles of shape q (dimension_q), checked: an
// error of `command` says what is wrong.
inline mn::Law checked_law(LAMMPS_NS::LAMMPS *lmp, const char *command,
                           const mn::Material &material, const mn::Options &options, double q)
{
  const char *problem = mn::material_error(material);
  if (problem) lmp->error->all(FLERR, "Illegal {} command: {}", command, problem);
  const mn::Law law = mn::derive(material, options, q);
  problem = mn::law_error(law);
  if (problem)
    lmp->error->all(FLERR, "Illegal {} command: {} (kn = {})", command, problem, material.kn);
  return law;
}

// The law the arguments give, what they do not give taken from `defaults` (nullptr: every
// number must be given, an option not given is off).
inline mn::Law law_from_arguments(LAMMPS_NS::LAMMPS *lmp, const char *command,
                                  const LawArguments &arguments, const mn::Law *defaults)
{
  mn::Material material = arguments.material;
  mn::Options options = arguments.options;
  for (int k = 0; k < N_LAW_KEYWORDS; k++) {
    const LawKeyword &keyword = LAW_KEYWORDS[k];
    if (arguments.given[k]) continue;
    if (keyword.option && defaults) options.*keyword.option = defaults->options.*keyword.option;
    if (keyword.number && defaults)
      material.*keyword.number = defaults->material.*keyword.number;
    else if (keyword.number)
      lmp->error->all(FLERR, "Illegal {} command: {} must be given", command, keyword.name);
  }
  return checked_law(lmp, command, material, options, dimension_q(lmp));
}

// A wall fix's law: the keywords its line gives, the rest from pair_style gran/mn; `own`:
// it is not exactly the pair style's (the fix then checks the time step against it itself).
struct WallLaw {
  mn::Law law;
  bool own;
};
inline WallLaw wall_law(LAMMPS_NS::LAMMPS *lmp, const char *style, const LawArguments &parsed)
{
  // asked of gran/mn alone: some styles' extract() fails on a name they do not know
  LAMMPS_NS::Pair *pair = lmp->force->pair_match("gran/mn", 1);
  int dim = 0;
  const auto *pair_law =
      pair ? static_cast<const mn::Law *>(pair->extract(LAW_EXTRACT_NAME, dim)) : nullptr;
  if (!pair_law && !parsed.all_numbers_given())
    lmp->error->all(FLERR, "Fix {} takes its kn, e, beta, mu from pair_style gran/mn: define "
                           "that pair style first or give all four on the fix line", style);
  const std::string command = std::string("fix ") + style;
  WallLaw wall{law_from_arguments(lmp, command.c_str(), parsed, pair_law), !pair_law};
  for (const LawKeyword &keyword : LAW_KEYWORDS)
    wall.own = wall.own ||
        (keyword.number ? wall.law.material.*keyword.number != pair_law->material.*keyword.number
                        : wall.law.options.*keyword.option != pair_law->options.*keyword.option);
  return wall;
}

}    // namespace granmn

#endif
