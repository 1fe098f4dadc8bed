"""A point's checkpoints (inputs/lib/checkpoint.lmp): which one to resume from, and its output
files cut back to that step so that the resumed run appends to them as the killed run would
have gone on. Whatever the killed run wrote after the checkpoint goes, a half-written line or
frame included, and so do the outputs only a completed run writes."""
import re
from pathlib import Path

LINE = re.compile(r"^checkpoint (\d+) (checkpoint\.([12])\.restart)$")
# written once a run has completed (or stopped), or by the runner after it
FINAL = ("counts.txt", "stopped.txt", "profile.txt", "profile_chunk.txt", "done.txt",
         "timing.json", "failed.txt")


def latest(directory):
    """(step, N) of checkpoint.N.restart, the last checkpoint checkpoint.txt confirms complete
    (the deck writes the line once write_restart has returned), or None. A half-written last
    line is passed over."""
    log = Path(directory) / "checkpoint.txt"
    if not log.exists():
        return None
    for line in reversed(log.read_text(errors="replace").splitlines(keepends=True)):
        match = LINE.match(line.rstrip("\n"))
        if line.endswith("\n") and match and (Path(directory) / match[2]).exists():
            return int(match[1]), int(match[3])
    return None


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
