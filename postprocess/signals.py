"""Time series: periods."""
import numpy as np


def dominant_period(t, y, max_period=None, fraction=0.85):
    """The fundamental period of a series sampled at uniform times t: the lag of the first
    autocorrelation peak after the first zero crossing that reaches `fraction` of the highest
    peak (so that a motion repeating every second bump with nearly equal bumps in between gives
    the bump period, not twice it). Returns (period, autocorrelation at that lag); (nan, nan)
    when the series is constant or never decorrelates."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if len(t) < 4:
        raise ValueError("dominant_period needs at least 4 samples")
    dt = t[1] - t[0]
    if not np.allclose(np.diff(t), dt, rtol=1e-6, atol=1e-12 * abs(dt)):
        raise ValueError("dominant_period needs uniformly sampled times")
    v = y - y.mean()
    if not np.any(v):
        return np.nan, np.nan
    ac = np.correlate(v, v, "full")[len(v) - 1:]
    ac /= ac[0]
    below = np.nonzero(ac < 0)[0]
    if len(below) == 0:
        return np.nan, np.nan
    first = below[0]
    last = len(ac) if max_period is None else min(len(ac), int(max_period / dt) + 1)
    if first >= last:
        return np.nan, np.nan
    window = ac[first:last]
    highest = window.max()
    inner = np.flatnonzero((window[1:-1] >= window[:-2]) & (window[1:-1] >= window[2:]) &
                           (window[1:-1] >= fraction * highest)) + 1
    peak = first + (int(inner[0]) if len(inner) else int(np.argmax(window)))
    return peak * dt, ac[peak]


def block_means(t, y, start, stop, n_blocks):
    """Means of y over n_blocks equal spans of [start, stop), with the spans' centres."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if not stop > start or n_blocks < 2:
        raise ValueError("block_means needs stop > start and at least 2 blocks")
    edges = np.linspace(start, stop, n_blocks + 1)
    means = []
    for a, b in zip(edges[:-1], edges[1:]):
        inside = (t >= a) & (t < b)
        if not np.any(inside):
            raise ValueError(f"no samples in [{a}, {b})")
        means.append(y[inside].mean())
    return 0.5 * (edges[:-1] + edges[1:]), np.array(means)


def trend(t, y, start, stop, n_blocks=10):
    """Linear trend of block means over [start, stop): (slope, its standard error). Blocks
    much longer than the correlation time make their means nearly independent."""
    centres, means = block_means(t, y, start, stop, n_blocks)
    coefficients, covariance = np.polyfit(centres, means, 1, cov=True)
    return coefficients[0], np.sqrt(covariance[0, 0])
