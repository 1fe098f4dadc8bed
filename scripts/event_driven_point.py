#!/usr/bin/python3
"""Runs one event-driven point for the sweep runner: scripts/granmn_sweep/event_driven.py."""
import sys

from granmn_sweep.event_driven import main

if __name__ == "__main__":
    sys.exit(main())
