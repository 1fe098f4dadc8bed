#!/usr/bin/python3
"""Runs a grid of scene points described in a TOML config, resumably, with progress and ETA:
the command of the runner, scripts/granmn_sweep/ (`scripts/sweep.py --help`)."""
import sys

from granmn_sweep.cli import main

if __name__ == "__main__":
    sys.exit(main())
