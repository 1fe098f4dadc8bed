"""The one-off studies, each a module run from the repository root
(`python3 -m scripts.studies.NAME --help`): each answers one question of the docs from runs or
committed data, with the post-processing (postprocess) and the runner (scripts.granmn_sweep);
example_runs is what the examples' comparisons share."""
