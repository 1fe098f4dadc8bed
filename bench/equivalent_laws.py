"""gran/mn's law in other codes' terms, for unit masses: 2M = 1 between two disks and m_i = 1
against a wall, so the forces are k_n delta - eta_n v_n and -k_t u_t - eta_t v_t with the
header's coefficients (`law`: the output of build/plugin/mn-law)."""


def liggghts_contacts(law, kn, mu, types=1):
    """LIGGGHTS 3.8 hooke/stiffness with absolute stiffness and damping between particles; its
    wall model takes damping per unit effective mass, which is m_i = 1 there. The same values
    for every pair of `types` atom types."""
    table = lambda value: f"{types} " + " ".join([repr(value)] * types ** 2)
    return f"""
fix m1 all property/global kn peratomtypepair {table(kn)}
fix m2 all property/global kt peratomtypepair {table(law['kt'])}
fix m3 all property/global gamman_abs peratomtypepair {table(law['eta_n'])}
fix m4 all property/global gammat_abs peratomtypepair {table(law['eta_t'])}
fix m5 all property/global gamman peratomtypepair {table(law['eta_n'])}
fix m6 all property/global gammat peratomtypepair {table(law['eta_t'])}
fix m7 all property/global coefficientFriction peratomtypepair {table(mu)}
pair_style gran model hooke/stiffness tangential history absolute_damping on
pair_coeff * *
"""


LIGGGHTS_FLOOR = ("fix floor all wall/gran model hooke/stiffness tangential history "
                  "primitive type 1 yplane 0.0\n")


def hooke_history_contacts(law, kn, mu):
    """LAMMPS gran/hooke/history damps with meff = m/2 between particles (gamma = 2 eta) and
    m at a wall (gamma = eta); it cuts the shear back while sliding, gran/mn by default not."""
    return f"""
pair_style gran/hooke/history {kn!r} {law['kt']!r} {2 * law['eta_n']!r} {2 * law['eta_t']!r} {mu!r} 1
pair_coeff * *
fix floor all wall/gran hooke/history {kn!r} {law['kt']!r} {law['eta_n']!r} {law['eta_t']!r} {mu!r} 1 yplane 0.0 NULL
"""
