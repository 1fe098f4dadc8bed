"""Checkpoints (inputs/lib/checkpoint.lmp, fix checkpoint/mn): a point killed with kill -9
mid-chunk and resumed by the runner (python3 -m scripts.sweep) from its last checkpoint ends with the same outputs
as the uninterrupted checkpointed run; what the killed run left half-written is never taken;
a checkpoint of another point, another restart layout or a damaged file is refused."""
import glob
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from test_sweep import (BUILD, ROOT, SWEEP, kill_processes_mentioning, processes_mentioning,
                        signal_all, sweep, wait_for)

from scripts.granmn_sweep import checkpoints
from scripts.granmn_sweep.build_layout import build_layout
from granmn_run import LMP, PLUGIN, SERIAL, SERIAL_REASON, run_lammps

# A contact-rich stretch: the frictional pile falls and flows (friction, multiple contacts,
# the floor wall); the single disk bounces over its bumps. Checkpoints every 2 time units, the
# transient's end (4) falls between two of them.
CONFIGS = {
    "frictional_flow": 'scene = "frictional_flow"\nrun_time = 24\naverage_start = 5\n'
                       'stop_energy = 0\nrows = "yes"\n',
    "single_disk": 'scene = "single_disk"\nrun_time = 40\naverage_start = 5\n',
}


def write_config(tmp_path, scene, interval=2):
    path = tmp_path / f"{scene}.toml"
    path.write_text(f'name = "c"\n[defaults]\ncheckpoint_interval = {interval}\n'
                    f'{CONFIGS[scene]}[[grid]]\nseed = 1\n' if scene != "single_disk" else
                    f'name = "c"\n[defaults]\ncheckpoint_interval = {interval}\n'
                    f'{CONFIGS[scene]}[[grid]]\nkn = 5e4\n')
    return path


def data_lines(path):
    return [line for line in path.read_text().splitlines() if not line.startswith("#")]


def point_dir(output):
    return Path(glob.glob(str(output / "*" / "*"))[0])


def kill_mid_chunk(config, output, *options, after=2):
    """Starts the sweep (with its options, e.g. --ranks 2) and kills it once checkpoint.txt
    names `after` checkpoints or more and the run is at least 2 output lines into the chunk
    after the newest, short of its end; the step of that newest checkpoint, which a resume
    starts from. Short of the chunk's end: from its last output line on the run writes the
    next checkpoint into the file of the older one, and a kill there would leave that one
    half-written while checkpoint.txt still names it complete (the tests below damage the
    files themselves, knowing which). The run goes in slices of a few ms: the sweep's processes
    are stopped (SIGSTOP) while they are listed and the files read, so that neither a fast
    machine nor ranks that starve this loop move the run on between two looks; then the runner
    and its lmp, or mpirun and its ranks, get kill -9 together, as in a machine's crash.
    (Killed alone, the runner takes its runs with it by SIGTERM, but mpirun gives its ranks a
    second to end, which is enough for a fast machine to finish this run.)"""
    runner = subprocess.Popen(SWEEP + [str(config), "--output", str(output), "--build",
                                       str(BUILD), "--jobs", "1", *options], cwd=ROOT,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                              start_new_session=True)
    deadline = time.time() + 300
    step = None
    while time.time() < deadline:
        os.kill(runner.pid, signal.SIGSTOP)
        running = [runner.pid]
        # (again until no new one: a process started between the listing and its stop)
        while started := sorted(set(processes_mentioning(output)) - set(running)):
            signal_all(started, signal.SIGSTOP)
            running += started
        logs = glob.glob(str(output / "*" / "*" / "checkpoint.txt"))
        named = Path(logs[0]).read_text() if logs else ""
        # (a line being written is not judged on: its step may be cut short)
        steps = [int(line.split()[1]) for line in named.splitlines()] \
            if named.endswith("\n") else []
        if len(steps) >= max(after, 2):
            newest, chunk_steps = steps[-1], steps[-1] - steps[-2]
            energy = (Path(logs[0]).parent / "energy.txt").read_text()
            later = [int(line.split()[0]) for line in energy.splitlines() if line[:1].isdigit()]
            later = [s for s in later if s > newest]
            if energy.endswith("\n") and len(later) >= 2 and max(later) < newest + chunk_steps:
                step = newest
                break
        signal_all(running, signal.SIGCONT)
        time.sleep(0.003)
    os.killpg(runner.pid, signal.SIGKILL)
    kill_processes_mentioning(output)
    runner.wait()
    assert wait_for(lambda: not processes_mentioning(output), 30), processes_mentioning(output)
    directory = point_dir(output)
    assert step is not None and not (directory / "done.txt").exists(), \
        "the run ended before it could be killed"
    return directory, step


@pytest.mark.parametrize("scene", sorted(CONFIGS))
def test_killed_point_resumes_from_its_checkpoint_to_the_same_outputs(tmp_path, scene):
    """The uninterrupted run and the resumed one pass through the same LAMMPS setups at the
    same steps (each chunk between checkpoints is one `run`), and the restart file holds the
    full state (positions, velocities, contact histories, the wall's and the counters' per-atom
    state and window): the outputs agree bit for bit. Any loss (a counter's window restarted,
    a contact's history dropped, a setup the other run did not have, an output line written
    twice or lost) changes energy.txt at its 10 digits within the first chunk after the
    resume, and the flow's chaos amplifies even a 1e-16 difference to all digits by the end."""
    config = write_config(tmp_path, scene)
    sweep(config, tmp_path / "whole", "--jobs", "1")
    directory, step = kill_mid_chunk(config, tmp_path / "killed")
    # a line cut mid-way by the kill, and a done.txt without this run's token
    with open(directory / "energy.txt", "a") as energy:
        energy.write(f"{step + 10**6} 0.12")
    (directory / "done.txt").write_text("kn 1 steps 1 dt 1\n")
    proc = sweep(config, tmp_path / "killed", "--jobs", "1")
    assert "1 to run" in proc.stdout
    # (the deck's print, not its command echoed in the log)
    assert f"resuming from checkpoint {directory}/checkpoint." in \
        (directory / "log.lammps").read_text()
    whole = point_dir(tmp_path / "whole")
    names = ["energy.txt", "snapshots.lammpstrj"]
    names += ["counts.txt", "profile_chunks.txt", "contacts.txt"] if scene != "single_disk" \
        else ["trajectory.txt"]
    for name in names:    # (each LAMMPS run heads its lines with the column names: not compared)
        assert data_lines(directory / name) == data_lines(whole / name), name
    assert not list(directory.glob("checkpoint*")), "checkpoints left after the run completed"
    if scene != "single_disk":
        from postprocess.io import read_profile
        # 100 disks in the bins, on average over the span's chunks
        assert read_profile(directory)["count"].sum() == pytest.approx(100, abs=1e-5)


# The stiff frictional preset's deck (inputs/sweeps/stiff_frictional.toml: velocity Verlet at
# tau_c/20, contact rows over 2 time units, the stop test at its default stop_energy 1e-5 over
# stop_time 10) made cheap: k_n 1e6 and a short run. Flowing: the default start at sin(theta)
# 0.20 still flows at t = 24. Stopping: rows dropped from 1.1 apart at sin(theta) 0.10 come to
# rest at t ~ 20 (not at t < stop_time + 6 = 16 nor after 30: the test below needs a checkpoint
# between the last stop_time before the stop and the stop).
STIFF = ('scene = "frictional_flow"\nkn = 1e6\ndt_fraction = 0.05\ndt_cap = 1\n'
         'integrator = "verlet"\nrows = "yes"\nrows_time = 2\naverage_start = 5\n')
STIFF_PILES = {"flowing": ("run_time = 24\n", 2),
               "stopping": ("run_time = 40\nsin_theta = 0.1\nrow_spacing = 1.1\n", 8)}


@pytest.mark.parametrize("pile", sorted(STIFF_PILES))
def test_stiff_point_with_its_stop_test_resumes_to_the_same_outputs(tmp_path, pile):
    """The runner's --checkpoint-interval (not part of the point's name) on a point with the
    stop test (stop_energy > 0), killed with kill -9 after a checkpoint and resumed: the
    outputs, stopped.txt included, are the uninterrupted checkpointed run's to the bit. The
    stopping pile is resumed from a checkpoint less than stop_time before it stops, so that
    the stop depends on the samples of the window taken before the kill: a window begun
    afresh at the resume (fix ave/time's, which is not in restart files) would average fewer,
    later samples and stop earlier, and a test on LAMMPS's `time` (0 again after
    read_restart) would wait stop_time after the resume and stop later."""
    text, after = STIFF_PILES[pile]
    config = tmp_path / "stiff.toml"
    config.write_text(f'name = "c"\n[defaults]\n{STIFF}{text}[[grid]]\nseed = 1\n')
    every = ("--checkpoint-interval", "2")
    sweep(config, tmp_path / "whole", "--jobs", "1", *every)
    directory, step = kill_mid_chunk(config, tmp_path / "killed", *every, after=after)
    proc = sweep(config, tmp_path / "killed", "--jobs", "1", *every)
    assert "1 to run" in proc.stdout
    # (the deck's print, not its command echoed in the log)
    assert f"resuming from checkpoint {directory}/checkpoint." in \
        (directory / "log.lammps").read_text()
    whole = point_dir(tmp_path / "whole")
    assert "checkpoint" not in whole.name and whole.name == directory.name
    for name in ("energy.txt", "counts.txt", "contacts.txt", "profile_chunks.txt",
                 "snapshots.lammpstrj"):
        assert data_lines(directory / name) == data_lines(whole / name), name
    assert not list(directory.glob("checkpoint*")), "checkpoints left after the run completed"
    resumed_at = step * checkpoints.time_step(directory)
    if pile == "stopping":
        stopped = (whole / "stopped.txt").read_text()
        assert (directory / "stopped.txt").read_text() == stopped
        stopped_at = float(stopped.split()[1])
        assert stopped_at - 10 < resumed_at < stopped_at, (resumed_at, stopped_at)
    else:
        assert not (whole / "stopped.txt").exists()
        assert not (directory / "stopped.txt").exists()


def confirmed(directory):
    """(step, path) of the newest checkpoint checkpoint.txt names and of the older one (the
    other file's last line)."""
    lines = [line.split() for line in (directory / "checkpoint.txt").read_text().splitlines()]
    older = [words for words in lines if words[2] != lines[-1][2]][-1]
    return [(int(words[1]), directory / words[2]) for words in (lines[-1], older)]


# Checkpoints that checkpoint.txt names complete but that cannot be resumed from:
# {case: (what is done to them, the checkpoint the point is resumed from: "older" or None)}.
# "cut short": half the file (a full disk); "later step": the older file holds, complete, the
# newest file's step (begun again for a later checkpoint and written, the kill before its line).
CUT_SHORT = {"the newest cut short": ("cut short", "older"),
             "both cut short": ("both cut short", None),
             "the newest cut short, the older of a later step": ("later step", None)}


@pytest.mark.parametrize("mode", ["jobs", "partitions"])
@pytest.mark.parametrize("case", sorted(CUT_SHORT))
def test_a_checkpoint_that_cannot_be_resumed_is_passed_over(tmp_path, case, mode):
    """A checkpoint named complete in checkpoint.txt but cut short failed every later resume of
    the point (read_restart's ERROR, failed.txt), the older intact checkpoint never tried: the
    runner sets it aside and resumes from the older one, or, where that cannot be resumed from
    either (cut short; a file of another step than checkpoint.txt names, which the deck
    refuses), starts the point afresh, saying so; the point ends with the uninterrupted run's
    outputs (a fresh start repeats the run to the bit)."""
    if mode == "partitions" and SERIAL:
        pytest.skip(SERIAL_REASON)
    damage, resumed = CUT_SHORT[case]
    options = ("--jobs", "1") if mode == "jobs" else ("--partitions", "1")
    config = write_config(tmp_path, "single_disk")
    sweep(config, tmp_path / "whole", "--jobs", "1")
    directory, _ = kill_mid_chunk(config, tmp_path / "killed")
    (newest_step, newest), (older_step, older) = confirmed(directory)
    complete = newest.read_bytes()
    newest.write_bytes(complete[:len(complete) // 2])
    if damage == "both cut short":
        older.write_bytes(older.read_bytes()[:len(complete) // 2])
    elif damage == "later step":
        older.write_bytes(complete)
    proc = sweep(config, tmp_path / "killed", *options)
    said = proc.stdout
    assert f"the resume from {newest.name} (step {newest_step}) failed (ERROR" in said, said
    # (the deck's print, not its command echoed in the log)
    resumed_line = f"resuming from checkpoint {directory}/checkpoint."
    if resumed == "older":
        assert f"resuming from {older.name} (step {older_step})" in said, said
        assert f"resuming from checkpoint {older}\n" in (directory / "log.lammps").read_text()
    else:
        assert f"the resume from {older.name} (step {older_step}) failed" in said, said
        assert "starting it afresh" in said, said
        assert resumed_line not in (directory / "log.lammps").read_text()
    if damage == "later step":
        assert f"holds step {newest_step}, not the checkpoint checkpoint.txt names" in said
    # the run kept aside while the point started afresh goes once the fresh start has completed
    assert not (tmp_path / "killed" / "unresumed").exists()
    whole = point_dir(tmp_path / "whole")
    for name in ("energy.txt", "snapshots.lammpstrj", "trajectory.txt"):
        assert data_lines(directory / name) == data_lines(whole / name), name


def test_a_point_whose_fresh_start_fails_too_keeps_its_run(tmp_path):
    """Where lmp or the plugin is at fault (here the plugin is no library: LAMMPS loads nothing
    and read_restart meets an unknown pair style), every resume fails and so does the fresh
    start: the run so far must not be lost with the checkpoints it blamed. It is kept aside,
    failed.txt says where and what to do, and once the build is mended and the run put back,
    the point resumes to the uninterrupted run's outputs. (A plugin at fault in the decks' dry
    runs too has the sweep refused before anything runs: here the runs alone get the broken
    one, through an lmp that swaps it in.)"""
    config = write_config(tmp_path, "single_disk")
    sweep(config, tmp_path / "whole", "--jobs", "1")
    directory, _ = kill_mid_chunk(config, tmp_path / "killed")
    broken = build_layout(tmp_path / "broken")
    broken.plugin.parent.mkdir(parents=True)
    broken.lammps.parent.mkdir()
    broken.plugin.write_text("not a library\n")
    lmp = Path(LMP).resolve()
    broken.lammps.write_text(
        f"#!{sys.executable}\nimport os, sys\nwords = sys.argv[1:]\n"
        "if 'dry_run' not in words:\n"
        f"    words[words.index('plugin') + 1] = {str(broken.plugin)!r}\n"
        "else:\n"
        f"    words[words.index('plugin') + 1] = {str(Path(PLUGIN).resolve())!r}\n"
        f"os.execv({str(lmp)!r}, [{str(lmp)!r}] + words)\n")
    broken.lammps.chmod(0o755)
    proc = subprocess.run(SWEEP + [str(config), "--output", str(tmp_path / "killed"), "--build",
                                   str(broken.directory), "--jobs", "1"], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 1, proc.stdout + proc.stderr
    aside = tmp_path / "killed" / "unresumed" / "single_disk" / directory.name
    failed = (directory / "failed.txt").read_text()
    assert "this run began afresh" in failed and f"is kept in {aside}" in failed, failed
    assert len(list(aside.glob("checkpoint.*.unreadable"))) == 2
    # mended: the run put back, its checkpoints named again
    shutil.rmtree(directory)
    aside.replace(directory)
    for kept in directory.glob("checkpoint.*.unreadable"):
        kept.replace(kept.with_suffix(".restart"))
    sweep(config, tmp_path / "killed", "--jobs", "1")
    assert f"resuming from checkpoint {directory}/checkpoint." in \
        (directory / "log.lammps").read_text()
    whole = point_dir(tmp_path / "whole")
    for name in ("energy.txt", "snapshots.lammpstrj", "trajectory.txt"):
        assert data_lines(directory / name) == data_lines(whole / name), name


def test_failed_txt_says_how_the_run_began_and_what_to_do(tmp_path):
    """failed.txt gave the exit status and the ERROR alone: whether the run had resumed, and
    what to do about it, were left to guess."""
    config = write_config(tmp_path, "single_disk")
    # a deck check past the dry run's end (inputs/lib/outputs.lmp): it fails the run
    config.write_text(config.read_text().replace("average_start = 5",
                                                 "average_start = 5\nsnapshot_interval = 1e12"))
    proc = sweep(config, tmp_path / "out", "--jobs", "1", check=False)
    assert proc.returncode == 1
    failed = (point_dir(tmp_path / "out") / "failed.txt").read_text()
    assert "ERROR: deck variable snapshot_interval = 1e+12 is more than 2^31 - 1 steps" in failed
    assert "this run began afresh" in failed
    assert "what to do: mend what the ERROR names, then run the sweep again" in failed


def test_truncated_done_is_not_taken(tmp_path):
    """done.txt without the token of the run that timing.json recorded is rerun, not read."""
    config = write_config(tmp_path, "single_disk", interval=5)
    sweep(config, tmp_path / "out", "--jobs", "1")
    directory = point_dir(tmp_path / "out")
    (directory / "done.txt").write_text("kn 5e4 steps")
    proc = sweep(config, tmp_path / "out", "--jobs", "1")
    assert "1 to run" in proc.stdout and "run " in (directory / "done.txt").read_text()


def resume_by_hand(tmp_path, deck_vars, restart):
    """lmp on the single-disk deck resuming from `restart` (put where the deck looks)."""
    out = tmp_path / "resume"
    out.mkdir(exist_ok=True)
    (out / "checkpoint.1.restart").write_bytes(restart)
    command = [str(build_layout(BUILD).lammps), "-in", str(ROOT / "inputs" / "single_disk.lmp"),
               "-screen", "none", "-log", str(out / "log.lammps"), "-nocite"]
    variables = {"plugin": str(build_layout(BUILD).plugin),
                 "lib": str(ROOT / "inputs" / "lib"), "out": str(out), "run_token": "t",
                 "checkpoint_interval": 5, "run_time": 40, "average_start": 5, "resume": 1,
                 **deck_vars}
    for name, value in variables.items():
        command += ["-var", name, str(value)]
    proc = subprocess.run(command, capture_output=True, text=True, timeout=120)
    return proc.returncode, (out / "log.lammps").read_text(errors="replace")


@pytest.fixture(scope="module")
def checkpoint_file(tmp_path_factory):
    """A checkpoint of the single disk (kn 5e4, run_time 40, checkpoint_interval 5)."""
    tmp = tmp_path_factory.mktemp("ckpt")
    config = tmp / "c.toml"
    config.write_text('name = "c"\n[defaults]\ncheckpoint_interval = 5\n'
                      f'{CONFIGS["single_disk"]}[[grid]]\nkn = 5e4\n')
    directory, _ = kill_mid_chunk(config, tmp / "out")
    return (directory / "checkpoint.1.restart").read_bytes()


def test_checkpoint_of_the_same_point_is_taken(tmp_path, checkpoint_file):
    status, log = resume_by_hand(tmp_path, {"kn": "50000"}, checkpoint_file)
    assert status == 0, log[-2000:]


def test_checkpoint_of_another_point_is_refused(tmp_path, checkpoint_file):
    status, log = resume_by_hand(tmp_path, {"kn": "1e5"}, checkpoint_file)
    assert status != 0
    assert "is a checkpoint of point 'single_disk,kn=50000," in log and "kn=1e5" in log


def with_layout(checkpoint_file, layout):
    """The checkpoint with another layout number: the first double of fix checkpoint/mn's
    record, written as 2."""
    import struct
    at = checkpoint_file.index(b"checkpoint/mn")
    where = checkpoint_file.index(struct.pack("d", 2.0), at)
    return checkpoint_file[:where] + struct.pack("d", layout) + checkpoint_file[where + 8:]


def test_checkpoint_of_another_layout_is_refused(tmp_path, checkpoint_file):
    """A file of a later plugin (layout 3)."""
    status, log = resume_by_hand(tmp_path, {"kn": "50000"}, with_layout(checkpoint_file, 3.0))
    assert status != 0 and "restart layout 3 of the gran/mn styles" in log


def test_checkpoint_of_the_layout_before_is_taken(tmp_path, checkpoint_file):
    """Layout 1 differs from 2 only in fix wall/gran/mn's rows, which that fix reads in either
    (the single disk has no wall fix: this is the check of the number alone; the rows'
    conversion is test_region_wall.py's)."""
    status, log = resume_by_hand(tmp_path, {"kn": "50000"}, with_layout(checkpoint_file, 1.0))
    assert status == 0, log[-2000:]


def test_damaged_checkpoint_is_refused(tmp_path, checkpoint_file):
    """A file cut short (a disk that filled up) stops the run with read_restart's ERROR after
    the line naming the file; it is never run from."""
    status, log = resume_by_hand(tmp_path, {"kn": "50000"}, checkpoint_file[:len(checkpoint_file) // 2])
    assert status != 0
    assert "resuming from checkpoint" in log and "ERROR" in log
    assert "Loop time" not in log


# fix ave/window/mn on its own: a Lennard-Jones liquid whose kinetic energy changes at every
# step, averaged over windows of 7 samples 10 steps apart, with LAMMPS's fix ave/time beside it.
WINDOW_LIQUID = """plugin load {plugin}
units lj
atom_style atomic
lattice fcc 0.8442
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 box
mass 1 1.0
velocity all create 1.5 87287 loop geom
"""
WINDOW_DYNAMICS = """pair_style lj/cut 2.5
pair_coeff 1 1 1.0 1.0 2.5
fix nve all nve
variable ke equal ke
"""


def window_means(path):
    """{step: [the means printed]} of a fix print file."""
    return {int(line.split()[0]): line.split()[1:] for line in path.read_text().splitlines()
            if not line.startswith("#")}


def test_window_average_is_fix_ave_time_s_to_the_bit_and_goes_on_after_a_restart(tmp_path):
    """fix ave/window/mn's mean is fix ave/time ave window's at every sample, across run
    boundaries on and off the sampling grid (a sample taken twice at a run's setup, or missed,
    changes the mean at its 17 digits), and a run resumed from a restart file written
    mid-way goes on with the window: the same means to the bit (a window begun afresh would
    average the samples after the restart only)."""
    run_lammps(WINDOW_LIQUID.format(plugin=PLUGIN) + WINDOW_DYNAMICS + """
fix old all ave/time 10 1 10 v_ke ave window 7
fix recent_energy all ave/window/mn 10 7 v_ke
fix means all print 10 "$(step) $(f_old:%.17g) $(f_recent_energy:%.17g)" file whole.txt screen no
run 35
run 35
write_restart window.restart
run 100
""", tmp_path, header=False)
    whole = window_means(tmp_path / "whole.txt")
    assert sorted(whole) == list(range(0, 171, 10))
    assert all(old == new for old, new in whole.values())
    run_lammps(f"plugin load {PLUGIN}\nread_restart window.restart\n" + WINDOW_DYNAMICS + """
fix recent_energy all ave/window/mn 10 7 v_ke resume yes
fix means all print 10 "$(step) $(f_recent_energy:%.17g)" file resumed.txt screen no
run 100
""", tmp_path, header=False)
    resumed = window_means(tmp_path / "resumed.txt")
    assert sorted(resumed) == list(range(70, 171, 10))
    assert all(resumed[step] == whole[step][1:] for step in resumed)


# fix ave/window/mn refusing a restart file that cannot continue its window:
# {case: (the fix command of the resumed run, message)}
BAD_WINDOWS = {
    "a restart file without the stop test's window, resumed with `fix ave/window/mn ... resume "
    "yes` (the decks' stop test with stop_energy > 0)": (
        "fix recent_energy all ave/window/mn 200 100 v_ke resume yes",
        "the restart file holds no window of fix recent_energy (ave/window/mn): it cannot "
        "continue this run's average"),
    "a restart file whose window has another N or M (`fix ave/window/mn`)": (
        "fix recent_energy all ave/window/mn 200 50 v_ke",
        "the restart file's window of fix recent_energy is 100 samples every 200 steps, this "
        "fix's 50 every 200: it cannot continue it"),
}


@pytest.mark.parametrize("case", sorted(BAD_WINDOWS))
def test_a_window_the_restart_file_cannot_continue_is_refused(tmp_path, case):
    command, message = BAD_WINDOWS[case]
    written = "" if "without" in case else "fix recent_energy all ave/window/mn 200 100 v_ke\n"
    run_lammps(WINDOW_LIQUID.format(plugin=PLUGIN) + WINDOW_DYNAMICS + written +
               "run 400\nwrite_restart window.restart\n", tmp_path, header=False)
    run = run_lammps(f"plugin load {PLUGIN}\nread_restart window.restart\n" + WINDOW_DYNAMICS +
                     command + "\nrun 10\n", tmp_path, header=False, check=False)
    assert run.returncode != 0 and message in run.output, run.output[-2000:]
