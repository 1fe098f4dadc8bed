"""Post-processing of the scenes' outputs: pure numpy functions (see the modules)."""
