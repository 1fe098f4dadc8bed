/* LIGGGHTS 3.8 normal model `mn`: the normal force of the Mitarai-Nakanishi linear
   spring-dashpot law (Phys. Rev. E 67, 021301 (2003)), with tangential model `mn`
   (docs/liggghts.md). The force is mn_contact.h's, as in the LAMMPS pair style gran/mn:
   fn = 2M (k_n delta - eta_n v_n), 2M -> m_i against walls and frozen particles.
   Setting: limit_damping on|off (off): clamp fn at zero. With a fix contacts/mn defined, it
   adds each touching contact to the fix's tallies at every evaluation (a flag per contact,
   in the contact's history, tells those begun). */
#ifdef NORMAL_MODEL
NORMAL_MODEL(MN,mn,20)
#else
#ifndef NORMAL_MODEL_MN_H_
#define NORMAL_MODEL_MN_H_
#include "atom.h"
#include "contact_models.h"
#include "granmn_liggghts_law.h"
#include "normal_model_base.h"

namespace LIGGGHTS {
namespace ContactModels {

template <>
class NormalModel<MN> : public NormalModelBase {
 public:
  NormalModel(LAMMPS *lmp, IContactHistorySetup *hsetup, class ContactModelBase *c)
      : NormalModelBase(lmp, hsetup, c),
        touching_offset(hsetup->add_history_value("mn_touching", "0"))
  {
  }

  void registerSettings(Settings &settings)
  {
    settings.registerOnOff("limit_damping", law.options.limit_damping, false);
  }

  void postSettings(IContactHistorySetup *, ContactModelBase *) {}

  void connectToProperties(PropertyRegistry &registry)
  {
    law.connect(lmp, registry, "model mn");
    counter = granmn_liggghts::find_counter(lmp);
    granmn_liggghts::see_every_listed_pair(lmp);
  }

  double stressStrainExponent() { return 1.0; }

  void surfacesIntersect(SurfacesIntersectData &sidata, ForceData &i_forces, ForceData &j_forces)
  {
    if (sidata.contact_flags) *sidata.contact_flags |= CONTACT_NORMAL_MODEL;
    const mn::Law &pair_law = law.laws(sidata.itype, sidata.jtype);
    const double scale =
        granmn_liggghts::mass_scale(sidata) * law.laws.force_per_mass_acceleration;
    double fn;
    if (law.two_d) {
      const mn::Kinematics k = granmn_liggghts::kinematics<2>(sidata);
      granmn_liggghts::keep(sidata, k);    // for tangential mn
      fn = mn::normal_force(pair_law, scale, k);
    } else {
      const mn::Kinematics3 k = granmn_liggghts::kinematics<3>(sidata);
      granmn_liggghts::keep(sidata, k);
      fn = mn::normal_force(pair_law, scale, k);
    }
    sidata.Fn = fn;
    // the absolute coefficients of this contact, for what reads them from a normal model
    // (LIGGGHTS's timestep check, pair/gran/local)
    sidata.kn = scale * pair_law.material.kn;
    sidata.gamman = scale * pair_law.eta_n;
    sidata.kt = scale * pair_law.kt;
    sidata.gammat = scale * pair_law.eta_t;

    const double f = sidata.is_wall ? fn * sidata.area_ratio : fn;
    for (int c = 0; c < 3; c++) i_forces.delta_F[c] += f * sidata.en[c];
    if (!sidata.is_wall)
      for (int c = 0; c < 3; c++) j_forces.delta_F[c] -= f * sidata.en[c];
    if (counter) count(sidata);
  }

  // the contact has ended (it is in the neighbour list, not touching): the next one begins anew
  void surfacesClose(SurfacesCloseData &scdata, ForceData &, ForceData &)
  {
    if (scdata.contact_history) scdata.contact_history[touching_offset] = 0.0;
  }
  void beginPass(SurfacesIntersectData &, ForceData &, ForceData &) {}
  void endPass(SurfacesIntersectData &, ForceData &, ForceData &) {}

 private:
  // i's share of a touching contact, and j's where j is owned here (newton off: a pair with a
  // ghost is computed by both processes)
  void count(const SurfacesIntersectData &sidata)
  {
    double &touching = sidata.contact_history[touching_offset];
    const bool began = touching == 0.0;
    touching = 1.0;
    const granmn::ContactTallies &tallies = counter->tallies();
    tallies.add(sidata.i, granmn_liggghts::partner_is_boundary(sidata), began);
    if (!sidata.is_wall && sidata.j < atom->nlocal)
      tallies.add(sidata.j, granmn_liggghts::i_is_boundary(sidata), began);
  }

  int touching_offset;
  const granmn::ContactCounter *counter = nullptr;
  granmn_liggghts::ModelLaw law;
};

}    // namespace ContactModels
}    // namespace LIGGGHTS
#endif
#endif
