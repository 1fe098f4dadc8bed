"""The project's programs, run from the repository root as modules, so that the root is where
`postprocess` and the runner are imported from with nothing added to the path:

    python3 -m scripts.sweep CONFIG              the sweep runner (installed: `granmn sweep`)
    python3 -m scripts.studies.accuracy          a one-off study (scripts/studies/)

granmn_sweep is the runner's package (pyproject.toml installs it as `granmn_sweep`, hence its
modules import one another relatively); event_driven_point.py is the program the runner starts
for an event-driven point; studies/ holds the one-off studies, which use the runner and the
post-processing but are neither. The shell scripts (build.sh, main.sh, test.sh, setup.sh) run
from anywhere."""
