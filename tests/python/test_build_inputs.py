"""The build's bad inputs (docs/bad_input.md, "Building") stop before anything is fetched or
built, with the message that names the three LAMMPS generations."""
import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
GENERATIONS = ("debian12 (Debian 12's LAMMPS, 29 Sep 2021), 2025 (LAMMPS 4 Feb 2025) or 2026 "
               "(LAMMPS 4 Jul 2026)")


def one_line(text):
    """CMake wraps and indents its messages: compare with the words only."""
    return re.sub(r"\s+", " ", text)


@pytest.mark.parametrize("script", ["build.sh", "test.sh", "main.sh"])
def test_unknown_generation_is_named_by_the_scripts(script):
    proc = subprocess.run([str(ROOT / "scripts" / script), "--lammps", "2030"],
                          capture_output=True, text=True)
    assert proc.returncode == 2
    assert f"{script}: --lammps takes {GENERATIONS}, not '2030'" in proc.stderr


def cmake_configure(tmp_path, *options):
    return subprocess.run(["cmake", "-S", str(ROOT), "-B", str(tmp_path / "build"), *options],
                          capture_output=True, text=True)


def test_unknown_generation_is_named_by_cmake(tmp_path):
    proc = cmake_configure(tmp_path, "-DGRANMN_LAMMPS=2030")
    assert proc.returncode != 0
    assert (f"GRANMN_LAMMPS is '2030': {GENERATIONS}; or give -DLAMMPS_SOURCE_DIR=<tree>"
            in one_line(proc.stderr))


def test_a_directory_that_is_no_lammps_tree_is_named_by_cmake(tmp_path):
    empty = tmp_path / "not-lammps"
    empty.mkdir()
    proc = cmake_configure(tmp_path, f"-DLAMMPS_SOURCE_DIR={empty}")
    assert proc.returncode != 0
    assert f"{empty} is not a LAMMPS source tree with the PLUGIN package" in one_line(proc.stderr)
