"""Whether mpirun can start a number of processes here: OpenMPI starts no more than it has
slots (one per physical core, unless an allocation or a hostfile says otherwise). The one
place that asks; scripts/sweep.py and bench/scaling.py say what to do about it."""
import os
import shlex
import subprocess


def slots_problem(command, env, timeout=120):
    """None if `command` (an mpirun line for N processes, without the program) runs `true`;
    else why not, in a sentence that names the command and this machine's cores."""
    line = shlex.join(command + ["true"])
    try:
        proc = subprocess.run(command + ["true"], capture_output=True, text=True, env=env,
                              timeout=timeout)
    except (OSError, subprocess.TimeoutExpired) as error:
        return f"`{line}` does not run ({error})"
    if proc.returncode == 0:
        return None
    said = " ".join((proc.stdout + proc.stderr).split())
    return (f"`{line}` fails here: "
            f"{'not enough slots' if 'not enough slots' in said else said[:400]} (this machine "
            f"has {os.cpu_count()} logical cores; OpenMPI counts the physical ones)")
