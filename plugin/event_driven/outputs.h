// The sampled outputs of an event-driven run, in the files and columns a LAMMPS run of the scene
// writes (inputs/lib/outputs.lmp, inputs/lib/run.lmp), so that postprocess reads the run as it
// reads a LAMMPS one:
//   params.txt   name value per line: the scene, the rule and its parameters, kn, tau_c and
//                tau_w (the soft law's at the k_n the run stands for), dt (= output_interval:
//                energy.txt's step is the sample's number), run_time, average_start, n_mobile
//   energy.txt   every output_interval: step, kinetic energy per disk (translational,
//                rotational, total), then the counters' sums over the disks since the window
//                began (at 0, then at average_start): collisions with disks (each counted by
//                both disks, as fix contacts/mn counts contacts begun) and with the boundary;
//                the time touching disks, the boundary, and with two or more contacts, and the
//                contacts now, all 0 (collisions are instantaneous); the window's length
//   counts.txt   per disk (a LAMMPS dump snapshot): id (the start's order, from 1), diameter,
//                the same six counters over the window from average_start
//   profile.txt  per bin of height y over [profile_lo, profile_hi), averaged over the samples
//                from average_start (fix ave/chunk's norm sample): chunk, centre, count,
//                number density (per area), mean vx, mean vy
#ifndef MN_EVENT_DRIVEN_OUTPUTS_H
#define MN_EVENT_DRIVEN_OUTPUTS_H

#include "engine.h"

namespace mn {
namespace ed {

// Runs `engine` (at time 0) to run.run_time (or run.max_events events, or a collapse), writing
// the sampled outputs into run.out as it goes: what is written stays when the run ends early.
Engine::Stop run_sampled(Engine &engine, const RunRequest &run);

}    // namespace ed
}    // namespace mn

#endif
