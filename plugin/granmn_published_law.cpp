/* ----------------------------------------------------------------------
   pair_style gran/mn's published law (granmn_published_law.h).
------------------------------------------------------------------------- */

#include "granmn_published_law.h"

#include "domain.h"
#include "error.h"
#include "input.h"
#include "utils.h"
#include "variable.h"

#include "mn_integration.h"
#include "mn_output_schema.h"

using namespace LAMMPS_NS;

namespace granmn {

void publish_law_variables(LAMMPS *lmp, const mn::Law &law)
{
  Variable *variables = lmp->input->variable;
  output::for_each_published(law, [&](const char *name, double value) {
    const int ivar = variables->find(name);
    if (ivar < 0)
      variables->set(fmt::format("{} internal {:.17g}", name, value));
    else if (variables->internalstyle(ivar))
      variables->internal_set(ivar, value);
    else
      lmp->error->all(FLERR, "pair_style gran/mn: variable {} is defined by the deck; pair_style "
                             "gran/mn publishes its derived values under that name", name);
  });
}

void report_law(LAMMPS *lmp, const mn::Law &law)
{
  utils::logmesg(lmp,
                 "pair_style gran/mn: kn = {:.8g} e = {} beta = {} mu = {} ({})\n"
                 "  eta_n = {:.8g} kt = {:.8g} eta_t = {:.8g}\n"
                 "  tau_c = {:.8g} tau_w = {:.8g} e_w = {:.8g}\n"
                 "  largest stable dt: {:.6g} (velocity Verlet), {:.6g} (Adams-Bashforth 2)\n",
                 law.material.kn, law.material.e, law.material.beta, law.material.mu,
                 lmp->domain->dimension == 3 ? "3D: solid spheres, q = 7/2" : "2D: disks, q = 3",
                 law.eta_n, law.kt, law.eta_t,
                 law.tau_c, law.tau_w, law.e_w,
                 mn::max_stable_dt(law, mn::Integrator::VelocityVerlet),
                 mn::max_stable_dt(law, mn::Integrator::AdamsBashforth2));
}

}    // namespace granmn
