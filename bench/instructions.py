"""Instructions per step of the two flowing 2D scenes, as the study runs them (counters and
outputs on), and in the hand-written reference loop (bench/reference_loop.cpp), counted by
callgrind (Debian's valgrind): the steady side of bench/run_benchmarks.py's timed comparison.
On a shared machine the same binary's time per step moves by up to 2x between runs; a run's
counts do not depend on the machine's load.

Each figure is the difference of two runs that share their warm-up (WARMUP + SPAN1 and
WARMUP + SPAN2 time units), divided by the steps between them: the set-up, the warm-up and the
run's end drop out. Then the functions that take most of a step, in both.

callgrind counts an instruction with a repeat prefix once per repetition: glibc's memset of
more than about 2 kB (LAMMPS's force clear of f and torque) is `rep stosb`, counted once per
byte, though the processor clears such a block in a few dozen cycles. The ratios are printed
with it and without it.

    python3 -m bench.instructions [--warmup 30] [--spans 1 2.5] [--top 8]
                          [--scenes frictional_flow collisional_flow]

About 4.5 minutes of CPU a scene (both scenes: 282 s of wall on two cores)."""
import argparse
import concurrent.futures
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from bench.run_benchmarks import KN, ROOT, SCENES, Build, law

DT_FRACTION = 0.01    # the decks' default
MEMSET = "memset"     # in the name of glibc's memset variants


def callgrind(command, out_file, cwd):
    """Runs command under callgrind; its functions' self counts {name: instructions}."""
    proc = subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out_file}"]
                          + command, cwd=cwd, capture_output=True, text=True, errors="replace")
    if proc.returncode != 0:
        sys.exit(f"{' '.join(command)} failed under callgrind (exit {proc.returncode}):\n"
                 f"{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    listing = subprocess.run(["callgrind_annotate", "--show-percs=no", "--threshold=100",
                              str(out_file)], check=True, capture_output=True, text=True).stdout
    counts = {}
    for line in listing.splitlines():
        match = re.match(r"\s*([\d,]+)\s+(.*\S)\s*$", line)
        if match:
            counts[match.group(2)] = int(match.group(1).replace(",", ""))
    return counts


def lammps_run(build, scene, run_time, warmup, work):
    """Counts and final step of the scene deck run for run_time (average_start = warmup)."""
    out = work / f"{scene}-{run_time}"
    out.mkdir()
    command = [str(build.lmp), "-in", str(ROOT / "inputs" / f"{scene}.lmp"), "-log", "none",
               "-screen", "none", "-var", "plugin", str(build.plugin),
               "-var", "lib", str(ROOT / "inputs" / "lib"), "-var", "out", str(out),
               "-var", "kn", repr(KN), "-var", "run_time", repr(run_time),
               "-var", "average_start", repr(warmup), "-var", "stop_energy", "0",
               "-var", "dt_fraction", repr(DT_FRACTION)]
    counts = callgrind(command, out / "callgrind.out", work)
    steps = int(re.search(r"steps (\d+)", (out / "done.txt").read_text()).group(1))
    return counts, steps


def reference_run(build, scene, steps, warmup, work):
    """Counts of the reference loop measured over `steps` steps after the warm-up."""
    command = [str(build.reference_loop), SCENES[scene], repr(KN), repr(DT_FRACTION), repr(warmup),
               str(steps)]
    return callgrind(command, work / f"reference-{scene}-{steps}.out", work), steps


def per_step(short, long):
    """{function: instructions per step} between two (counts, steps) runs."""
    (a, steps_a), (b, steps_b) = short, long
    steps = steps_b - steps_a
    return {name: (b.get(name, 0) - a.get(name, 0)) / steps for name in b}


def scene_counts(build, scene, args, work, pool):
    dt = min(DT_FRACTION * law(build)["tau_c"], 1e-4)    # as the decks choose it (dt_cap 1e-4)
    lammps = [pool.submit(lammps_run, build, scene, args.warmup + s, args.warmup, work)
              for s in args.spans]
    reference = [pool.submit(reference_run, build, scene, round(s / dt), args.warmup, work)
                 for s in args.spans]
    return (per_step(*(f.result() for f in lammps)),
            per_step(*(f.result() for f in reference)))


def short_name(function):
    """'Class::method' of a callgrind_annotate name: no file, arguments, namespace or object."""
    name = re.sub(r"\s*\[[^\]]*\]$", "", function)
    name = re.sub(r"^(\?\?\?|\.?/[^:]*):", "", name)
    name = re.sub(r"^void |LAMMPS_NS::|\(anonymous namespace\)::", "", name)
    return re.sub(r"\(.*", "", name)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--warmup", type=float, default=30.0, help="time units before the spans")
    parser.add_argument("--spans", type=float, nargs=2, default=[1.0, 2.5],
                        help="the two runs' time units after the warm-up")
    parser.add_argument("--top", type=int, default=8, help="functions listed per variant")
    parser.add_argument("--scenes", nargs="+", choices=sorted(SCENES), default=list(SCENES))
    parser.add_argument("--build", default="build",
                        help="the build directory to count: build (Debian 12's LAMMPS), "
                             "build-2025 or build-2026")
    args = parser.parse_args()
    build = Build.of(ROOT, args.build)
    if not args.spans[1] > args.spans[0] > 0:
        sys.exit("--spans S1 S2: 0 < S1 < S2")
    for tool in ("valgrind", "callgrind_annotate"):
        if not shutil.which(tool):
            sys.exit(f"{tool} is missing: apt-get install valgrind")
    for path in build.programs:
        if not path.exists():
            sys.exit(f"{path} is missing: run ./scripts/build.sh first")
    print(f"Instructions per step (callgrind), kn = {KN:g}, dt = tau_c x {DT_FRACTION}, between "
          f"{args.spans[0]:g} and {args.spans[1]:g} time units after a {args.warmup:g} warm-up")
    with tempfile.TemporaryDirectory() as tmp, \
            concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        for scene in args.scenes:
            lammps, reference = scene_counts(build, scene, args, Path(tmp), pool)
            total, base = lammps["PROGRAM TOTALS"], reference["PROGRAM TOTALS"]
            memset = sum(v for k, v in lammps.items() if MEMSET in k)
            base_memset = sum(v for k, v in reference.items() if MEMSET in k)
            print(f"\n{scene}: LAMMPS {total:.0f}, reference loop {base:.0f}: {total / base:.2f}x;"
                  f" without memset {total - memset:.0f} and {base - base_memset:.0f}: "
                  f"{(total - memset) / (base - base_memset):.2f}x")
            for label, counts in (("LAMMPS", lammps), ("reference loop", reference)):
                ranked = sorted(((v, k) for k, v in counts.items() if k != "PROGRAM TOTALS"),
                                reverse=True)[:args.top]
                print(f"  {label}: " + "; ".join(f"{short_name(k)} {v:.0f}" for v, k in ranked))


if __name__ == "__main__":
    main()
