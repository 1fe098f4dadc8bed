"""A point's checkpoints (inputs/lib/checkpoint.lmp): which one to resume from, and its output
files cut back to that step so that the resumed run appends to them as the killed run would
have gone on. Whatever the killed run wrote after the checkpoint goes, a half-written line or
frame included, and so do the outputs only a completed run writes."""
import re
from pathlib import Path

from postprocess.rundir import COUNTS, DONE, FAILED, PROFILE, STOPPED, TIMING

LINE = re.compile(r"^checkpoint (\d+) (checkpoint\.([12])\.restart)$")
# written once a run has completed (or stopped), or by the runner after it
FINAL = (COUNTS, STOPPED, PROFILE, "profile_chunk.txt", DONE, TIMING, FAILED)


def candidates(directory):
    """[(step, N)] of the checkpoints checkpoint.txt confirms complete (the deck writes a line
    once write_restart has returned), the newest first: of each file checkpoint.N.restart, the
    last step its lines name, if the file is there and energy.txt reaches that step (the deck
    writes the step's line before the checkpoint; outputs cut back to an older checkpoint do
    not reach a newer one). A half-written last line is passed over. The older file may since
    have been begun again for a later step and cut short by a kill: the deck checks that the
    step it reads is the one named (resume_step)."""
    directory = Path(directory)
    log = directory / "checkpoint.txt"
    if not log.exists() or not (directory / "energy.txt").exists():
        return []
    steps = {}
    for line in log.read_text(errors="replace").splitlines(keepends=True):
        match = LINE.match(line.rstrip("\n"))
        if line.endswith("\n") and match:
            steps[int(match[3])] = int(match[1])
    reached = -1
    for line in whole_lines(directory / "energy.txt"):
        try:
            reached = max(reached, float(line.split()[0]))
        except (ValueError, IndexError):    # the comments, the column names
            pass
    return sorted(((step, slot) for slot, step in steps.items()
                   if step <= reached and (directory / f"checkpoint.{slot}.restart").exists()),
                  reverse=True)


def latest(directory):
    """(step, N) of the newest confirmed checkpoint (candidates), or None."""
    found = candidates(directory)
    return found[0] if found else None


def whole_lines(path):
    return [line for line in path.read_text(errors="replace").splitlines(keepends=True)
            if line.endswith("\n")]


def cut_table(path, keep):
    """Keeps a text table's comment lines and the data lines whose first number passes keep;
    a half-written last line goes."""
    kept = []
    for line in whole_lines(path):
        words = line.split()
        if not words or line.startswith("#"):
            kept.append(line)
            continue
        try:
            first = float(words[0])
        except ValueError:
            break
        if not keep(first):
            break
        kept.append(line)
    path.write_text("".join(kept))


def cut_dump(path, step):
    """Keeps a text dump's frames up to `step`; a frame cut short by the kill only comes after
    them (the resumed run writes again from the next step)."""
    text = path.read_text(errors="replace")
    kept = []
    for frame in text.split("ITEM: TIMESTEP\n")[1:]:
        head = frame.split("\n", 1)[0].strip()
        if not head.isdigit() or int(head) > step:
            break
        kept.append("ITEM: TIMESTEP\n" + frame)
    path.write_text("".join(kept))


def cut_chunks(path, step):
    """profile_chunks.txt: the blocks of the chunks that ended by `step`."""
    kept = []
    for line in whole_lines(path):
        words = line.split()
        if words[:2] == ["#", "chunk"] and int(words[3]) > step:
            break
        kept.append(line)
    path.write_text("".join(kept))


def time_step(directory):
    """dt as the deck wrote it into params.txt."""
    for line in (Path(directory) / "params.txt").read_text().splitlines():
        words = line.split()
        if words[:1] == ["dt"] and len(words) == 2:
            return float(words[1])
    raise ValueError(f"{directory}/params.txt names no dt")


def cut_outputs(directory, step):
    """A point's outputs cut back to checkpoint `step`, for a run resumed from it: the lines and
    frames up to the step (the resumed run writes from the next one)."""
    directory = Path(directory)
    dt = time_step(directory)
    if (directory / "energy.txt").exists():
        cut_table(directory / "energy.txt", lambda first: first <= step)
    if (directory / "trajectory.txt").exists():
        cut_table(directory / "trajectory.txt", lambda time: time < (step + 0.5) * dt)
    for name in ("snapshots.lammpstrj", "contacts.txt"):
        if (directory / name).exists():
            cut_dump(directory / name, step)
    if (directory / "profile_chunks.txt").exists():
        cut_chunks(directory / "profile_chunks.txt", step)
    for name in FINAL:
        (directory / name).unlink(missing_ok=True)
    if (directory / "log.lammps").exists():
        (directory / "log.lammps").replace(directory / "log.before_resume.lammps")
