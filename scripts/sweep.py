"""Runs a grid of scene points described in a TOML config, resumably, with progress and ETA:
the command of the runner, scripts/granmn_sweep/ (`python3 -m scripts.sweep --help` from the
repository root; installed, `granmn sweep`)."""
import sys

if not __package__:
    print("the runner runs from the repository root as `python3 -m scripts.sweep CONFIG ...` "
          "(installed: `granmn sweep CONFIG ...`)", file=sys.stderr)
    sys.exit(2)

from scripts.granmn_sweep.cli import main    # noqa: E402 (after the check above)

if __name__ == "__main__":
    sys.exit(main())
