/* LIGGGHTS 3.8 normal model `mn`: the normal force of the Mitarai-Nakanishi linear
   spring-dashpot law (Phys. Rev. E 67, 021301 (2003)), with tangential model `mn`
   (docs/liggghts.md). The force is mn_contact.h's, as in the LAMMPS pair style gran/mn:
   fn = 2M (k_n delta - eta_n v_n), 2M -> m_i against walls and frozen particles.
   Setting: limit_damping on|off (off): clamp fn at zero. At a run's setup it says which pairs
   of particles start deeply overlapping (mn::deep_overlap). */
#ifdef NORMAL_MODEL
NORMAL_MODEL(MN,mn,20)
#else
#ifndef NORMAL_MODEL_MN_H_
#define NORMAL_MODEL_MN_H_
#include "contact_models.h"
#include "granmn_liggghts_law.h"
#include "normal_model_base.h"

namespace LIGGGHTS {
namespace ContactModels {

template <>
class NormalModel<MN> : public NormalModelBase {
 public:
  NormalModel(LAMMPS *lmp, IContactHistorySetup *hsetup, class ContactModelBase *c)
      : NormalModelBase(lmp, hsetup, c)
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
  }

  double stressStrainExponent() { return 1.0; }

  GRANMN_CONTACT_WORK void surfacesIntersect(SurfacesIntersectData &sidata, ForceData &i_forces,
                                             ForceData &j_forces)
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
    if (deep_overlaps.watching) deep_overlaps.see(lmp, sidata, pair_law);
  }

  void surfacesClose(SurfacesCloseData &, ForceData &, ForceData &) {}

  // (the pair style's passes only: a wall's evaluation has none)
  void beginPass(SurfacesIntersectData &sidata, ForceData &, ForceData &)
  {
    deep_overlaps.begin(lmp, sidata);
  }
  void endPass(SurfacesIntersectData &, ForceData &, ForceData &)
  {
    deep_overlaps.report(lmp, "model mn");
  }

 private:
  granmn_liggghts::ModelLaw law;
  granmn_liggghts::DeepOverlaps deep_overlaps;
};

}    // namespace ContactModels
}    // namespace LIGGGHTS
#endif
#endif
