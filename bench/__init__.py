"""The benchmarks, each a module run from the repository root (`python3 -m bench.NAME --help`,
docs/performance.md), with the helpers they share (paired: the sign test on paired ratios;
equivalent_laws: the other engines' laws matched to gran/mn's)."""
