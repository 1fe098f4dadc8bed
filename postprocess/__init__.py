"""Post-processing of the scenes' outputs: readers, observables, the comparison with the
paper (numpy), figures (matplotlib) and the report (see the modules)."""
