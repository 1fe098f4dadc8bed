"""The frictional flow's steady-state selection (docs/model.md section 5)."""
from collections import deque
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Selection:
    """The paper's rule and this project's reading of its time resolution: steady parts are
    spans longer than min_length over which E(t), averaged over windows of `resolution`, stays
    within max_width; those whose mean lies in energy_range are kept."""
    resolution: float = 1.0
    min_length: float = 500.0
    max_width: float = 0.45
    energy_range: tuple = (0.4, 0.8)

    def describe(self):
        return (f"spans > {self.min_length:g} narrower than {self.max_width:g} with mean E in "
                f"[{self.energy_range[0]:g}, {self.energy_range[1]:g}], E(t) averaged over "
                f"windows of {self.resolution:g}")


def add_selection_arguments(parser):
    """The selection's command-line options, for every command that selects steady parts."""
    parser.add_argument("--resolution", type=float, default=Selection.resolution)
    parser.add_argument("--energy-range", type=float, nargs=2, default=Selection.energy_range,
                        metavar=("LOW", "HIGH"))
    parser.add_argument("--min-span", type=float, default=Selection.min_length)
    parser.add_argument("--max-width", type=float, default=Selection.max_width)


def selection_of(parser, args):
    """The Selection the options of add_selection_arguments ask for; a value that selects
    nothing meaningful is the parser's error."""
    if not args.resolution > 0:
        parser.error(f"--resolution {args.resolution:g} must be > 0")
    low, high = args.energy_range
    if not 0 <= low < high:
        parser.error(f"--energy-range {low:g} {high:g} must satisfy 0 <= LOW < HIGH")
    if not args.min_span > 0:
        parser.error(f"--min-span {args.min_span:g} must be > 0")
    if not args.max_width > 0:
        parser.error(f"--max-width {args.max_width:g} must be > 0")
    return Selection(resolution=args.resolution, energy_range=(low, high),
                     min_length=args.min_span, max_width=args.max_width)


def steady_spans(t, energy, min_length=500.0, max_width=0.45):
    """Maximal spans of the series, longer than min_length, over which the width of the energy
    fluctuation (max - min) stays below max_width. Scans left to right: a span is extended as
    far as it stays narrow, recorded if long enough, and the next span starts after it.
    Returns [(start_index, stop_index)] with stop exclusive."""
    t = np.asarray(t, dtype=float)
    e = np.asarray(energy, dtype=float)
    spans, start = [], 0
    low, high = deque(), deque()    # indices of the running min and max
    for stop in range(len(e)):
        while low and e[low[-1]] >= e[stop]:
            low.pop()
        low.append(stop)
        while high and e[high[-1]] <= e[stop]:
            high.pop()
        high.append(stop)
        while e[high[0]] - e[low[0]] >= max_width:
            # the span [start, stop) was as long as it could be
            if t[stop - 1] - t[start] > min_length:
                spans.append((start, stop))
                start = stop
                low, high = deque([stop]), deque([stop])
                break
            start += 1
            if low[0] < start:
                low.popleft()
            if high[0] < start:
                high.popleft()
    if len(e) and t[-1] - t[start] > min_length:
        spans.append((start, len(e)))
    return spans


def select_steady(t, energy, min_length=500.0, max_width=0.45, energy_range=(0.4, 0.8)):
    """Steady spans whose mean energy lies in energy_range, and all steady spans found."""
    spans = steady_spans(t, energy, min_length, max_width)
    e = np.asarray(energy, dtype=float)
    kept = [s for s in spans if energy_range[0] <= e[s[0]:s[1]].mean() <= energy_range[1]]
    return kept, spans


def window_means(t, energy, resolution):
    """The series at a time resolution: means over consecutive windows of length `resolution`
    (a resolution at or below the sample spacing keeps every sample). Returns the windows'
    start times, their means, and the sample index where each window begins (plus the end), so
    that a span of windows [a, b) covers the samples [edges[a], edges[b])."""
    t = np.asarray(t, dtype=float)
    e = np.asarray(energy, dtype=float)
    if not resolution > 0:
        raise ValueError(f"resolution = {resolution!r} must be > 0")
    if len(t) == 0:
        return t, e, np.zeros(1, dtype=int)
    # a small slack so that samples written at exact multiples of the resolution do not split
    # on rounding (t is step * dt)
    window = np.floor((t - t[0]) / resolution + 1e-9).astype(int)
    starts = np.flatnonzero(np.r_[True, np.diff(window) != 0])
    edges = np.r_[starts, len(t)]
    means = np.add.reduceat(e, starts) / np.diff(edges)
    return t[starts], means, edges


def steady_parts(t, energy, selection=Selection()):
    """The steady parts found in the energy series averaged over windows of
    selection.resolution, before the energy range is applied: [(start, stop, mean)] with
    start, stop a sample-index span of the original series and mean the mean of the window
    means over it (what the energy range is tested on)."""
    tw, ew, edges = window_means(t, energy, selection.resolution)
    return [(int(edges[a]), int(edges[b]), float(ew[a:b].mean()))
            for a, b in steady_spans(tw, ew, selection.min_length, selection.max_width)]


def in_energy_range(mean, selection):
    """Whether a steady part of this mean energy is kept."""
    return selection.energy_range[0] <= mean <= selection.energy_range[1]


def select_at_resolution(t, energy, selection=Selection()):
    """The selection applied to the energy series averaged over windows of
    selection.resolution: (kept, found) as sample-index spans of the original series."""
    found = steady_parts(t, energy, selection)
    return ([(a, b) for a, b, mean in found if in_energy_range(mean, selection)],
            [(a, b) for a, b, _ in found])
