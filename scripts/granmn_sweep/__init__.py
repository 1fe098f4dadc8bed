"""The sweep runner behind scripts/sweep.py (`python3 -m scripts.sweep --help`: the config, the
layout, the options). In the checkout it is scripts.granmn_sweep, installed granmn_sweep
(pyproject.toml): its modules import one another relatively, each only those before it: decks
(what the runner reads from the decks, and asks them), event_driven (an event-driven point's
run: the deck's start, then the engine), config (a config's points and their names), cost (the
predicted CPU time: each point's size as its deck says it), processes (the runner's lmp
processes), points (the output directory and its points' directories), schedule (running the
points) and cli (the command); mn_law (the law's derived numbers from build/plugin/mn-law, for
bench and tests), mpirun_slots (the slots mpirun gives) and checkpoints (a run cut back to a
checkpoint) import none of them; command (`granmn`: the runner and the post-processing) imports
cli; build_layout (the paths inside a build directory) imports none."""


class SweepError(Exception):
    """A refusal: a bad config, path or output (the command says `sweep: MESSAGE`, exit 2)."""
