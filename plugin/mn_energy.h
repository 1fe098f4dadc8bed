// Where a contact's energy goes (docs/model.md section 9), in the terms of mn_contact.h's law
// and free of LAMMPS, so that every host (the pair style, the wall fixes, LIGGGHTS's model) books
// it alike. A host that does not ask for energies calls none of this.
//
// A contact's forces take energy from the particles' motion (minus their work on the relative
// motion). Of it the springs store (mass scale)/2 (k_n delta^2 + k_t |u_t|^2); the rest is
// dissipated: by the normal force, and by the tangential force while sticking and while sliding.
// Each evaluation books the work of the force the integrator applies, with the integrator's own
// step, in two halves, the second at the next evaluation, when the velocity it acts on is known:
// - velocity Verlet applies F_m over two half steps; its work is dt F_m . v_m, v_m = (v_{m-1/2} +
//   v_{m+1/2})/2 the full-step velocity: half with the velocity the force saw, half with the next
//   evaluation's, in F_m's own frame. That is the integrator's own work: kinetic + taken - work
//   of gravity keeps its initial value but for (dt^2/8)(sum |F|^2/m + |T|^2/I now - then);
// - Adams-Bashforth 2 sees the step's velocity: dt/2 (P_{m-1} + P_m), the trapezoidal rule on
//   the power P = F . v_ij the force saw; the budget keeps its value to O(dt^2) once the work in
//   flight is counted (work_in_flight).
// So a contact keeps its last evaluation (force and normal, or power). The first evaluation
// after it ended books its last force's second half (book_ended_contact_energy); a
// re-evaluation (dt_history = 0, LAMMPS's setup) books nothing and keeps the force it gives, the
// one the next half step applies.
#ifndef MN_ENERGY_H
#define MN_ENERGY_H

#include "mn_contact.h"

namespace mn {

// A contact's energy history, energy_history_size values that the host keeps with its u_t (and
// in restart files), all 0 for a new contact.
enum EnergySlot {
  ENERGY_TAKEN_NORMAL,          // energy taken from the motion by the normal force so far
  ENERGY_TAKEN_TANGENTIAL,      // the same, tangential force
  ENERGY_DISSIPATED_SLIDING,    // the part of the tangential loss booked while sliding
  ENERGY_SLID,                  // 1 if the last evaluation slid, else 0
  ENERGY_PREVIOUS_FORCE         // the last evaluation: energy_previous_size values
};

// The last evaluation's values a contact keeps: velocity Verlet, its normal and its force
// (n, f_n, f_t: 4 values in 2D, 7 in 3D with the vectors); Adams-Bashforth 2 (2D only), the
// power of its normal and tangential force (2 values).
constexpr int energy_previous_size(Integrator integrator, int dimension)
{
  return integrator == Integrator::AdamsBashforth2 ? 2 : (dimension == 3 ? 7 : 4);
}

constexpr int energy_history_size(Integrator integrator, int dimension)
{
  return ENERGY_PREVIOUS_FORCE + energy_previous_size(integrator, dimension);
}

// The energy stored in a contact's springs: (mass scale)/2 k_n delta^2 (0 once delta <= 0) and
// (mass scale)/2 k_t |u_t|^2, force_scale as for contact_force (energies then come in force x
// length).
struct StoredEnergy {
  double normal, tangential;
};

inline StoredEnergy stored_energy(const Law &law, double force_scale, double delta,
                                  double ut_squared)
{
  const double half = 0.5 * force_scale;
  return {delta > 0.0 ? half * law.material.kn * delta * delta : 0.0,
          half * law.kt * ut_squared};
}

// A contact's energies now, from its history and its overlap and |u_t|^2 (0 and 0 once it has
// ended): what its springs store and what it has dissipated. With the literal u_t a sliding
// contact's spring stores more than the capped force can give back, so its "dissipated" energy
// can be negative (docs/model.md sections 2 and 11).
struct ContactEnergy {
  double stored_normal, stored_tangential;
  double dissipated_normal, dissipated_sticking, dissipated_sliding;

  double stored() const { return stored_normal + stored_tangential; }
  double dissipated() const { return dissipated_normal + dissipated_sticking + dissipated_sliding; }
};

inline ContactEnergy contact_energy(const Law &law, double force_scale, double delta,
                                    double ut_squared, const double *energy)
{
  const StoredEnergy stored = stored_energy(law, force_scale, delta, ut_squared);
  ContactEnergy e;
  e.stored_normal = stored.normal;
  e.stored_tangential = stored.tangential;
  e.dissipated_normal = energy[ENERGY_TAKEN_NORMAL] - stored.normal;
  e.dissipated_sliding = energy[ENERGY_DISSIPATED_SLIDING];
  e.dissipated_sticking =
      energy[ENERGY_TAKEN_TANGENTIAL] - stored.tangential - e.dissipated_sliding;
  return e;
}

// What one evaluation booked: energy taken by the normal and the tangential force, and the
// tangential loss it booked as sliding (the hosts' per-atom and global sums add these); and the
// power of its force on the relative velocity it saw (0 for a contact that has ended), which an
// Adams-Bashforth 2 host needs for the budget of the step (work_in_flight).
struct EnergyStep {
  double taken_normal, taken_tangential, dissipated_sliding;
  double power;
};

// A contact that touches already where a run begins (it began at the run's setup,
// dt_history = 0: a start with overlaps, atoms placed or moved between runs): its springs hold
// energy that no step took from the motion (and the cut-back may have set its u_t at the setup,
// which that evaluation booked as a negative sliding loss). Its account opens after the setup's
// evaluation with what its springs hold as taken and no loss, so that it has dissipated nothing
// yet; the returned booking (the change, no power) goes to its atoms' sums as a step's does.
inline EnergyStep open_energy_account(const Law &law, double force_scale, double delta,
                                      double ut_squared, double *energy)
{
  const StoredEnergy stored = stored_energy(law, force_scale, delta, ut_squared);
  const EnergyStep opened = {stored.normal - energy[ENERGY_TAKEN_NORMAL],
                             stored.tangential - energy[ENERGY_TAKEN_TANGENTIAL],
                             -energy[ENERGY_DISSIPATED_SLIDING], 0.0};
  energy[ENERGY_TAKEN_NORMAL] = stored.normal;
  energy[ENERGY_TAKEN_TANGENTIAL] = stored.tangential;
  energy[ENERGY_DISSIPATED_SLIDING] = 0.0;
  return opened;
}

namespace detail {

// One step's booking, (t_{m-1}, t_m]: the previous force's second half (tail) and this force's
// first half (head), each a power (force . relative velocity) held for dt/2; the change of the
// tangential spring's energy over the step (advance and, under the cut-back, the cut), so that
// the step's tangential loss is taken - stored change; booked as sliding if `sliding` (this
// evaluation slid; for the step after a contact's end, its last evaluation did).
inline EnergyStep book_step(const Law &law, double force_scale, double dt, double tail_n,
                            double tail_t, double head_n, double head_t, double ut_squared_before,
                            double ut_squared_after, bool sliding, double *energy)
{
  EnergyStep step;
  step.taken_normal = -0.5 * dt * (tail_n + head_n);
  step.taken_tangential = -0.5 * dt * (tail_t + head_t);
  const double stored_change = 0.5 * force_scale * law.kt * (ut_squared_after - ut_squared_before);
  step.dissipated_sliding = sliding ? step.taken_tangential - stored_change : 0.0;
  step.power = head_n + head_t;
  energy[ENERGY_TAKEN_NORMAL] += step.taken_normal;
  energy[ENERGY_TAKEN_TANGENTIAL] += step.taken_tangential;
  energy[ENERGY_DISSIPATED_SLIDING] += step.dissipated_sliding;
  return step;
}

// The previous evaluation's normal and tangential power, held over the step now ending: under
// Adams-Bashforth 2 the power it saw; under velocity Verlet its force on the velocity of this
// evaluation (the half-step velocity after it), in its own frame. In 2D the translational
// relative velocity is dv = v_n n + (v_t + lever_spin) t (mn::kinematics).
inline void previous_power(Integrator integrator, const Kinematics &k, double lever_spin,
                           const double *previous, double *tail_n, double *tail_t)
{
  if (integrator == Integrator::AdamsBashforth2) {
    *tail_n = previous[0];
    *tail_t = previous[1];
    return;
  }
  const double nx = previous[0], ny = previous[1], fn = previous[2], ft = previous[3];
  const double along_t = k.vt + lever_spin;
  const double dvx = k.vn * k.nx - along_t * k.ny, dvy = k.vn * k.ny + along_t * k.nx;
  *tail_n = fn * (nx * dvx + ny * dvy);
  *tail_t = ft * (-ny * dvx + nx * dvy - lever_spin);
}

// In 3D (velocity Verlet): dv = v_n n + v_t - n x lever; the previous force's tangential part
// acts on dv + n_previous x lever.
inline void previous_power(const Kinematics3 &k, const double lever[3], const double *previous,
                           double *tail_n, double *tail_t)
{
  const double *np = previous, fn = previous[3], *ftp = previous + 4;
  const double nxl[3] = {k.n[1] * lever[2] - k.n[2] * lever[1],
                         k.n[2] * lever[0] - k.n[0] * lever[2],
                         k.n[0] * lever[1] - k.n[1] * lever[0]};
  const double npxl[3] = {np[1] * lever[2] - np[2] * lever[1],
                          np[2] * lever[0] - np[0] * lever[2],
                          np[0] * lever[1] - np[1] * lever[0]};
  double along_n = 0.0, along_t = 0.0;
  for (int c = 0; c < 3; c++) {
    const double dv = k.vn * k.n[c] + k.vt[c] - nxl[c];
    along_n += np[c] * dv;
    along_t += ftp[c] * (dv + npxl[c]);
  }
  *tail_n = fn * along_n;
  *tail_t = along_t;
}

}    // namespace detail

// Books one force evaluation of a contact in 2D: k its kinematics, lever_spin the z component of
// r_i omega_i + r_j omega_j given to mn::kinematics, f the force contact_force gave, |u_t|^2
// before and after contact_force (which advances and may cut u_t back), dt_history and the
// integrator as given to contact_force; energy its history (energy_history_size values).
inline EnergyStep book_contact_energy(const Law &law, double force_scale, const Kinematics &k,
                                      double lever_spin, const Force &f,
                                      double ut_squared_before, double ut_squared_after,
                                      double dt_history, Integrator integrator, double *energy)
{
  double *previous = energy + ENERGY_PREVIOUS_FORCE;
  double tail_n, tail_t;
  detail::previous_power(integrator, k, lever_spin, previous, &tail_n, &tail_t);
  const double head_n = f.fn * k.vn, head_t = f.ft * k.vt;
  const EnergyStep step =
      detail::book_step(law, force_scale, dt_history, tail_n, tail_t, head_n, head_t,
                        ut_squared_before, ut_squared_after, f.sliding, energy);
  energy[ENERGY_SLID] = f.sliding ? 1.0 : 0.0;
  if (integrator == Integrator::AdamsBashforth2) {
    previous[0] = head_n;
    previous[1] = head_t;
  } else {
    previous[0] = k.nx;
    previous[1] = k.ny;
    previous[2] = f.fn;
    previous[3] = f.ft;
  }
  return step;
}

// The same in 3D (velocity Verlet; lever = r_i omega_i + r_j omega_j as given to
// mn::kinematics3; |u_t|^2 before contact_force3, which keeps it when it turns u_t into the
// tangent plane).
inline EnergyStep book_contact_energy(const Law &law, double force_scale, const Kinematics3 &k,
                                      const double lever[3], const Force3 &f,
                                      double ut_squared_before, double ut_squared_after,
                                      double dt_history, double *energy)
{
  double *previous = energy + ENERGY_PREVIOUS_FORCE;
  double tail_n, tail_t;
  detail::previous_power(k, lever, previous, &tail_n, &tail_t);
  const double head_n = f.fn * k.vn;
  const double head_t = f.ft[0] * k.vt[0] + f.ft[1] * k.vt[1] + f.ft[2] * k.vt[2];
  const EnergyStep step =
      detail::book_step(law, force_scale, dt_history, tail_n, tail_t, head_n, head_t,
                        ut_squared_before, ut_squared_after, f.sliding, energy);
  energy[ENERGY_SLID] = f.sliding ? 1.0 : 0.0;
  for (int c = 0; c < 3; c++) {
    previous[c] = k.n[c];
    previous[4 + c] = f.ft[c];
  }
  previous[3] = f.fn;
  return step;
}

// The first evaluation after a contact ended (its overlap is gone; its history not yet cleared):
// k its kinematics now, lever_spin as above, ut_squared its last |u_t|^2. Books the last force's
// second half and the release of the energy its tangential spring held (sliding if the last
// evaluation slid). Its energies are then contact_energy(law, force_scale, 0.0, 0.0, energy):
// all it took is dissipated.
inline EnergyStep book_ended_contact_energy(const Law &law, double force_scale,
                                            const Kinematics &k, double lever_spin,
                                            double ut_squared, double dt_history,
                                            Integrator integrator, double *energy)
{
  double tail_n, tail_t;
  detail::previous_power(integrator, k, lever_spin, energy + ENERGY_PREVIOUS_FORCE, &tail_n,
                         &tail_t);
  return detail::book_step(law, force_scale, dt_history, tail_n, tail_t, 0.0, 0.0, ut_squared,
                           0.0, energy[ENERGY_SLID] != 0.0, energy);
}

inline EnergyStep book_ended_contact_energy(const Law &law, double force_scale,
                                            const Kinematics3 &k, const double lever[3],
                                            double ut_squared, double dt_history, double *energy)
{
  double tail_n, tail_t;
  detail::previous_power(k, lever, energy + ENERGY_PREVIOUS_FORCE, &tail_n, &tail_t);
  return detail::book_step(law, force_scale, dt_history, tail_n, tail_t, 0.0, 0.0, ut_squared,
                           0.0, energy[ENERGY_SLID] != 0.0, energy);
}

// The work the particles' kinetic energy has received at the end of a step and the contacts
// have not booked yet (less what they booked ahead of it), for the whole system's budget:
// kinetic + taken - work of gravity - in flight = its value at the start. None under velocity
// Verlet, whose step has applied the first half of each force the evaluation booked the first
// half of. Adams-Bashforth 2's velocities have received 3/2 of the previous evaluation's forces
// (the next step takes 1/2 back) and none of this one's, where the trapezoidal rule has booked
// 1 and 1/2: dt/2 (P_{M-1} - P_M), with P the sum over contacts of EnergyStep::power, this
// evaluation's and the previous one's (a run's setup counts as one; at the setup itself nothing
// is in flight). Per contact the difference washes out: it is only where a contact begins or
// ends that P_{M-1} - P_M is not O(dt).
inline double work_in_flight(Integrator integrator, double dt, double power_previous,
                             double power_now)
{
  return integrator == Integrator::AdamsBashforth2 ? 0.5 * dt * (power_previous - power_now)
                                                   : 0.0;
}

// force_and_torques (mn_contact.h) with the contact's energies booked: the same force and
// torques, to the bit; lever = r_i omega_i + r_j omega_j as given to mn::kinematics (in 2D only
// its z component is read); energy the contact's history.
inline EnergyStep force_and_torques_with_energy(
    const Law &law, double force_scale, const Kinematics &k, const double lever[3], double *ut,
    double dt_history, Integrator integrator, double *vt_previous, double *energy,
    double force[3], double radius_i, double *torque_i, double radius_j, double *torque_j)
{
  const double before = ut ? ut[0] * ut[0] : 0.0;
  const Force f = contact_force(law, force_scale, k, ut, dt_history, integrator, vt_previous);
  apply_force(k, f, force, radius_i, torque_i, radius_j, torque_j);
  return book_contact_energy(law, force_scale, k, lever[2], f, before, ut ? ut[0] * ut[0] : 0.0,
                             dt_history, integrator, energy);
}

// The same in 3D (velocity Verlet).
inline EnergyStep force_and_torques_with_energy(
    const Law &law, double force_scale, const Kinematics3 &k, const double lever[3], double *ut,
    double dt_history, Integrator, double *, double *energy, double force[3], double radius_i,
    double *torque_i, double radius_j, double *torque_j)
{
  auto squared = [](const double *u) { return u ? u[0] * u[0] + u[1] * u[1] + u[2] * u[2] : 0.0; };
  const double before = squared(ut);
  const Force3 f = contact_force3(law, force_scale, k, ut, dt_history);
  apply_force(k, f, force, radius_i, torque_i, radius_j, torque_j);
  return book_contact_energy(law, force_scale, k, lever, f, before, squared(ut), dt_history,
                             energy);
}

// A moving wall's work on the system (docs/model.md section 9). A wall contact's force F acts
// on the particle's motion v = (v - v_wall) + v_wall: the contact books its work on the relative
// motion, the energy it took, and the wall's force does F . v_wall on the particle besides,
// booked by the same rule, so that the two add up to the integrator's own work on the particle.
// Velocity Verlet: dt/2 (F_{m-1} + F_m) . v_wall,m at evaluation m, with the wall's velocity of
// this evaluation, the one the contact subtracts from both halves it books now (F_{m-1}'s tail
// sees v_{m+1/2} - v_wall,m). Adams-Bashforth 2: the trapezoidal rule on the wall's power
// F . v_wall, whose last value the contact keeps after its history: a wall that moves keeps
// moving_wall_energy_history_size values per contact. The wall's power is part of the power the
// budget's work in flight is made of.
constexpr int moving_wall_energy_history_size(Integrator integrator, int dimension)
{
  return energy_history_size(integrator, dimension) +
         (integrator == Integrator::AdamsBashforth2 ? 1 : 0);
}

// The wall's work over the step an evaluation closes, and the wall's power at it (F . v_wall).
struct WallWork {
  double work, power;
};

// The previous evaluation's force on the wall's velocity at this one (Adams-Bashforth 2: its
// power, kept): called before the contact's booking replaces the force it keeps.
inline double previous_wall_power(Integrator integrator, int dimension, const double *energy,
                                  const double v_wall[3])
{
  if (integrator == Integrator::AdamsBashforth2)
    return energy[energy_history_size(integrator, dimension)];
  const double *previous = energy + ENERGY_PREVIOUS_FORCE;
  if (dimension == 3)
    return previous[3] * (previous[0] * v_wall[0] + previous[1] * v_wall[1] +
                          previous[2] * v_wall[2]) +
           previous[4] * v_wall[0] + previous[5] * v_wall[1] + previous[6] * v_wall[2];
  const double nx = previous[0], ny = previous[1], fn = previous[2], ft = previous[3];
  return (fn * nx - ft * ny) * v_wall[0] + (fn * ny + ft * nx) * v_wall[1];
}

// Books the step's wall work: `tail` (previous_wall_power) and this evaluation's force on the
// particle (force_and_torques_with_energy's; 0 for a contact that has ended) on v_wall, each
// for dt_history/2.
inline WallWork book_wall_work(Integrator integrator, int dimension, double dt_history,
                               double tail, const double force[3], const double v_wall[3],
                               double *energy)
{
  double head = 0.0;
  for (int c = 0; c < dimension; c++) head += force[c] * v_wall[c];
  if (integrator == Integrator::AdamsBashforth2)
    energy[energy_history_size(integrator, dimension)] = head;
  return {0.5 * dt_history * (tail + head), head};
}

}    // namespace mn

#endif
