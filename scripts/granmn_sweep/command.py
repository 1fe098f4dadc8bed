"""The `granmn` command: the runner (`granmn sweep`, as `python3 -m scripts.sweep`) and the
post-processing commands (`granmn summarize ...`, as `python3 -m postprocess summarize ...`),
one subcommand each, each with its own options and --help."""
import sys

from . import cli
from postprocess import __main__ as analysis

USAGE = f"""usage: granmn COMMAND [options]   (granmn COMMAND --help: its options)

commands:
  sweep        run a grid of scene points from a TOML config (python3 -m scripts.sweep)
  {", ".join(analysis.COMMANDS)}
               the post-processing (python3 -m postprocess)"""


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv or argv[0] in ("-h", "--help"):
        print(USAGE)
        return 0 if argv else 2
    if argv[0] == "sweep":
        return cli.main(argv[1:])
    if argv[0] in analysis.COMMANDS:
        return analysis.main(argv)
    print(f"{USAGE}\ngranmn: unknown command {argv[0]!r}", file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
