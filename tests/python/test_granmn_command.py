"""The Python side as one installed thing (pyproject.toml): `pip install --no-deps
--no-build-isolation .` into a fresh venv over Debian's packages gives a `granmn` command whose
subcommands are the runner and the post-processing, doing what scripts/sweep.py and
`python3 -m postprocess` do (rules out a package left out of the install, package data not
installed, a subcommand dispatched to the wrong command or with its arguments changed)."""
import filecmp
import shutil
import subprocess
import sys
import venv
from pathlib import Path

import pytest

from test_summary import sweep

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def granmn(tmp_path_factory):
    """The `granmn` of a fresh install, run from outside the repository."""
    if shutil.which("pip", path=str(Path(sys.executable).parent)) is None and \
            subprocess.run([sys.executable, "-m", "pip", "--version"],
                           capture_output=True).returncode != 0:
        pytest.skip(f"{sys.executable} has no pip (Debian: apt-get install python3-pip)")
    where = tmp_path_factory.mktemp("venv")
    try:
        venv.EnvBuilder(system_site_packages=True, with_pip=True).create(where / "env")
    except (subprocess.CalledProcessError, OSError) as error:
        pytest.skip(f"no venv with pip here ({error}; Debian: apt-get install python3-venv)")
    python = where / "env" / "bin" / "python3"
    # a copy of the tree: pip's setuptools writes build/ and granmn.egg-info/ in the source
    source = where / "source"
    shutil.copytree(ROOT, source, ignore=shutil.ignore_patterns(
        ".git", "build", "build-*", "results", "data", "docs", "__pycache__"))
    install = subprocess.run([python, "-m", "pip", "install", "--no-deps", "--no-build-isolation",
                              "--no-index", "-q", str(source)], capture_output=True, text=True)
    assert install.returncode == 0, install.stdout + install.stderr
    return where / "env" / "bin" / "granmn"


def run(command, cwd):
    proc = subprocess.run([str(c) for c in command], capture_output=True, text=True, cwd=cwd)
    return proc.returncode, proc.stdout, proc.stderr


def test_the_installed_command_lists_its_subcommands_and_each_has_its_help(granmn, tmp_path):
    code, out, err = run([granmn, "--help"], tmp_path)
    assert code == 0, err
    for command in ("sweep", "summarize", "report", "compare", "limit", "transition", "engines",
                    "finite-size"):
        assert command in out, f"granmn --help does not list {command}:\n{out}"
    code, out, err = run([granmn, "sweep", "--help"], tmp_path)
    assert code == 0 and "--partitions" in out and "Config (TOML)" in out, out + err
    code, out, err = run([granmn, "summarize", "--help"], tmp_path)
    assert code == 0 and "--replace" in out, out + err
    # a copy installed without -e has no decks beside it: the runner says so rather than
    # finding no scenes
    code, out, err = run([granmn, "sweep", ROOT / "inputs" / "sweeps" / "quick.toml",
                          "--dry-run"], tmp_path)
    assert code == 2 and "is not the project's checkout (no inputs/ with the decks)" in err, err
    code, out, err = run([granmn, "frobnicate"], tmp_path)
    assert code == 2 and "unknown command 'frobnicate'" in err


def test_installed_granmn_summarize_writes_what_python_m_postprocess_writes(granmn, tmp_path):
    results = sweep(tmp_path)
    theirs = run([sys.executable, "-m", "postprocess", "summarize", results, "--to",
                  tmp_path / "by-module"], ROOT)
    ours = run([granmn, "summarize", results, "--to", tmp_path / "by-granmn"], tmp_path)
    assert ours[0] == theirs[0] == 0, ours[2] + theirs[2]
    assert ours[1].replace("by-granmn", "by-module") == theirs[1]
    written = sorted(p.relative_to(tmp_path / "by-module")
                     for p in (tmp_path / "by-module").rglob("*.json"))
    assert len(written) == len(list(results.glob("*/*/point.json")))    # one per run
    match, mismatch, errors = filecmp.cmpfiles(tmp_path / "by-module", tmp_path / "by-granmn",
                                               [str(p) for p in written], shallow=False)
    assert not mismatch and not errors, (mismatch, errors)
    # installed, there is no repository data/ to be summarize's default (it would have written
    # into site-packages)
    code, _, err = run([granmn, "summarize", results], tmp_path)
    assert code == 2 and "summarize needs --to DIR where postprocess is installed" in err, err


def test_installed_granmn_compare_on_committed_summaries_is_python_m_postprocess_compare(
        granmn, tmp_path):
    data = ROOT / "data" / "paper_single_disk"
    assert run([granmn, "compare", data], tmp_path) == \
        run([sys.executable, "-m", "postprocess", "compare", data], ROOT)
