"""python3 -m postprocess {report,compare} SWEEP_DIR [--output DIR]

report   tables, figures, the comparison and report.md in DIR (default SWEEP_DIR/report)
compare  the comparison table on the terminal; exit status 1 if a claim fails"""
import argparse
import sys
from pathlib import Path

from .io import DataError
from .reference import evaluate
from .report import fmt, write_report
from .study import analyse


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m postprocess", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=("report", "compare"))
    parser.add_argument("sweep", type=Path)
    parser.add_argument("--output", type=Path)
    args = parser.parse_args(argv)
    try:
        scenes, left_out, completed = analyse(args.sweep)
    except DataError as error:
        print(f"postprocess: {error}", file=sys.stderr)
        return 2
    for point, reason in left_out:
        print(f"left out {point}: {reason}", file=sys.stderr)
    if args.command == "report":
        path, results = write_report(args.sweep, scenes, left_out, completed,
                                     args.output or args.sweep / "report")
        print(f"report: {path}")
        return 0
    results = evaluate(scenes)
    width = max(len(c["id"]) for c, _, _ in results)
    for claim, value, status in results:
        print(f"{claim['id']:<{width}}  {fmt(value):>10}  [{claim['low']:g}, {claim['high']:g}]"
              f"  {status}")
    failed = sum(status == "FAIL" for _, _, status in results)
    passed = sum(status == "pass" for _, _, status in results)
    print(f"comparison: {passed} pass, {failed} FAIL, {len(results) - passed - failed} not evaluated")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
