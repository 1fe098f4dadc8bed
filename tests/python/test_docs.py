"""The docs: docs/bad_input.md lists every bad input the tests try; the README is one screen;
docs/index.md lists every page."""
import re
from pathlib import Path

import test_bad_input
import test_bad_input_liggghts
import test_budget_warning
import test_checkpoint
import test_chute
import test_chute_3d
import test_counters
import test_energy
import test_nve_disc_mn
import test_scenes
import test_sweep
import test_sweep_runner

ROOT = Path(__file__).resolve().parents[2]

DOC = (ROOT / "docs" / "bad_input.md").read_text()


def test_every_bad_input_case_is_in_the_table():
    tables = [test_bad_input.ERRORS, test_bad_input.BONDED, test_counters.BAD,
              test_nve_disc_mn.BAD, test_scenes.BAD_VARIABLES,
              test_scenes.BAD_FRICTIONAL_VARIABLES, test_scenes.BAD_SINGLE_DISK_VARIABLES,
              test_sweep.BAD_CONFIGS, test_sweep.BAD_OUTPUTS,
              test_sweep_runner.BAD_SETTINGS, test_chute_3d.BAD_3D,
              test_checkpoint.BAD_WINDOWS, test_bad_input_liggghts.BAD,
              test_chute.BAD, test_energy.BAD, test_budget_warning.BAD]
    for table in tables:
        for case, (_, message) in table.items():
            assert f"| {case}" in DOC and message.replace("|", "\\|") in DOC, case


def relative_links(path):
    """The targets of a markdown file's links that are files of the repository (no URL)."""
    return [target for target in re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", path.read_text())
            if "://" not in target]


def test_readme_is_one_screen_and_its_links_resolve():
    """README.md is the one-screen overview: a changelog and results drift there, so they belong
    to docs/history.md and the pages that own the results; every page it or docs/index.md links
    exists."""
    readme = ROOT / "README.md"
    assert len(readme.read_text().splitlines()) <= 100
    for page in (readme, ROOT / "docs" / "index.md"):
        links = relative_links(page)
        assert links, page
        for target in links:
            assert (page.parent / target).exists(), f"{page.name} links {target}: no such file"


def test_the_index_lists_every_page():
    """docs/index.md links every page of docs/: a page it misses is one nobody finds."""
    listed = {(ROOT / "docs" / t).resolve() for t in relative_links(ROOT / "docs" / "index.md")}
    pages = [p for p in sorted((ROOT / "docs").glob("*")) if p.suffix in (".md", ".rst")
             and p.name != "index.md"]
    assert pages
    missing = [p.name for p in pages if p.resolve() not in listed]
    assert not missing, f"docs/index.md does not list {', '.join(missing)}"
