"""bench/instructions.py's arithmetic: per-step counts are the difference of two runs over the
steps between them (set-up and warm-up drop out), and names are shortened without merging."""

from bench import instructions


def test_per_step_differences_out_what_both_runs_share():
    # a set-up of 1000 instructions and a warm-up of 10 steps, then 7 and 3 per step
    short = ({"PROGRAM TOTALS": 1000 + 10 * 10 + 20 * 10, "loop": 10 * 10 + 7 * 20,
              "setup": 1000}, 30)
    long = ({"PROGRAM TOTALS": 1000 + 10 * 10 + 60 * 10, "loop": 10 * 10 + 7 * 60,
             "setup": 1000, "late": 3 * 30}, 70)
    counts = instructions.per_step(short, long)
    assert counts["PROGRAM TOTALS"] == 10    # not (total / 70 steps) = 24.3
    assert counts["loop"] == 7
    assert counts["setup"] == 0
    assert counts["late"] == 90 / 40         # a function only the longer run reached


def test_short_names():
    assert instructions.short_name(
        "???:void LAMMPS_NS::PairGranMN::compute_loop<2, true, true>() "
        "[/b/plugin/granmnplugin.so]") == "PairGranMN::compute_loop<2, true, true>"
    assert instructions.short_name(
        "./string/../sysdeps/x86_64/multiarch/memset-vec-unaligned-erms.S:"
        "__memset_avx2_unaligned_erms [/usr/lib/x86_64-linux-gnu/libc.so.6]") == \
        "__memset_avx2_unaligned_erms"
    assert instructions.short_name(
        "???:(anonymous namespace)::Loop::forces() [/b/bench/reference-loop]") == "Loop::forces"
