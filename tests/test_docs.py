"""Every code block of the documentation runs: the pages of docs/ block by block in a fresh
folder (docs/run_blocks.py), the README's Python blocks from the repository root, and the
script that draws the documentation's pictures; the site builds with warnings as errors and
every link of the README resolves."""

from __future__ import annotations

import subprocess
import sys

import pytest
from conftest import ROOT

DOCS = ROOT / "docs"
sys.path.insert(0, str(DOCS))

import run_blocks  # noqa: E402

PAGES = sorted(DOCS.glob("*.md"))


def _runnable(block) -> bool:
    return block.lang in ("bash", "python") or (block.lang == "yaml" and "file" in block.attrs)


RUNNABLE = [p for p in PAGES
            if any(_runnable(b) for b in run_blocks.blocks(p.read_text(encoding="utf-8")))]
# Files a page's commands must leave behind (the command reference writes one of each).
LEAVES = {"commands.md": ("ship.html", "dock_optimised.yaml", "dock.png", "envelope.png")}


def test_there_is_a_walkthrough_linked_from_the_readme():
    assert DOCS / "walkthrough.md" in PAGES
    assert "docs/walkthrough.md" in (ROOT / "README.md").read_text(encoding="utf-8")


def test_the_pages_that_teach_by_example_have_runnable_blocks():
    names = {p.name for p in RUNNABLE}
    assert {"walkthrough.md", "commands.md", "python.md", "studies.md", "berths.md"} <= names


@pytest.mark.parametrize("page", RUNNABLE, ids=[p.name for p in RUNNABLE])
def test_every_block_of_a_docs_page_runs(page, tmp_path):
    run_blocks.run(page, tmp_path, log=lambda *_: None, in_process=True)
    for name in LEAVES.get(page.name, ()):
        assert (tmp_path / name).exists(), f"{page.name} should have written {name}"


def test_the_readme_python_blocks_run(monkeypatch):
    blocks = [b for b in run_blocks.blocks((ROOT / "README.md").read_text(encoding="utf-8"))
              if b.lang == "python"]
    assert blocks
    monkeypatch.chdir(ROOT)
    namespace: dict = {"__name__": "__readme__"}
    for block in blocks:
        exec(compile(block.code, f"README.md:{block.line}", "exec"), namespace)


def test_the_command_reference_shows_every_command():
    text = (DOCS / "commands.md").read_text(encoding="utf-8")
    examples = "\n".join(b.code for b in run_blocks.blocks(text) if b.lang == "bash")
    from moorsolve.cli import _parser
    commands = set(_parser()._subparsers._group_actions[0].choices)
    missing = sorted(c for c in commands if f"moorsolve {c}" not in examples)
    assert not missing, f"docs/commands.md has no example of: {missing}"


def test_every_relative_link_of_the_readme_resolves():
    import re
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    for target in re.findall(r"\]\(([^)#:]+)(?:#[^)]*)?\)", text):
        assert (ROOT / target).exists(), f"README.md links to {target}, which does not exist"


def test_the_site_builds_strictly(tmp_path):
    pytest.importorskip("mkdocs", reason="the docs extra (pip install -e '.[docs]')")
    pytest.importorskip("mkdocstrings")
    from mkdocs.commands.build import build
    from mkdocs.config import load_config
    config = load_config(str(ROOT / "mkdocs.yml"), site_dir=str(tmp_path / "site"),
                         strict=True)
    build(config)
    assert (tmp_path / "site" / "reference" / "index.html").exists()


def test_unknown_block_attributes_and_exit_codes_are_honoured(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("```bash exit=2\nmoorsolve solve missing.yaml\n```\n"
                    "```yaml file=x.yaml\na: 1\n```\n"
                    "```python\nassert open('x.yaml').read() == 'a: 1\\n'\n```\n")
    run_blocks.run(page, tmp_path, log=lambda *_: None)
    page.write_text("```bash\nmoorsolve solve missing.yaml\n```\n")
    with pytest.raises(RuntimeError, match="exited 2, expected 0"):
        run_blocks.run(page, tmp_path, log=lambda *_: None)


def test_the_pictures_of_the_docs_are_drawn_by_their_script(tmp_path):
    # The walkthrough's own blocks are run by the test above; here only the drawing.
    done = subprocess.run([sys.executable, str(DOCS / "make_figures.py"), "--out",
                           str(tmp_path), "--skip-walkthrough"], capture_output=True,
                          text=True, timeout=600, cwd=tmp_path)
    assert done.returncode == 0, done.stderr[-3000:]
    for name in ("directions.png", "equilibrium_dock_sloped.png"):
        assert (tmp_path / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    text = "".join(p.read_text() for p in [ROOT / "README.md", *PAGES])
    import re
    for name in re.findall(r"\]\(((?:docs/)?[\w]+\.png)\)", text):
        assert (ROOT / name).exists() or (DOCS / name).exists(), f"{name} is not committed"


def test_a_blocks_shown_output_is_compared_with_what_it_prints(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("```python\nprint('offset 5.00 m, solved in 12.6 ms')\n"
                    "print('force residual 2.81e-10 N (9.4e-15 of max tension)')\n```\n"
                    "```text\noffset 5.00 m, solved in 3.1 ms\n"
                    "force residual 1.00e-09 N (1.1e-14 of max tension)\n```\n")
    run_blocks.run(page, tmp_path, log=lambda *_: None)          # times, residuals masked
    page.write_text("```python\nprint('offset 5.01 m')\n```\n```text\noffset 5.00 m\n```\n")
    with pytest.raises(RuntimeError, match="differs from what the block prints"):
        run_blocks.run(page, tmp_path, log=lambda *_: None)
    page.write_text("```python\nprint('offset 5.01 m')\n```\n"
                    "```text compare=no\noffset 5.00 m\n```\n")
    run_blocks.run(page, tmp_path, log=lambda *_: None)


@pytest.mark.parametrize("printed, shown, same", [
    ("a\nb\nc\n", "a\n...\nc", True),                    # ... stands for any lines
    ("a\nb\nc\n", "...\nb\n...", True),
    ("a\nb\nc\n", "a\nc", False),                         # a line left out without ...
    ("a\nb\n", "a", False),                               # printed more than shown
    ("x 1.2346\n", "x 1.235", True),                      # equal to the digits shown
    ("x 1.2344\n", "x 1.235", False),
    ("T 69622.066536\n", "T 69622.0665361", True),        # and to 1e-6 relative
    ("moorsolve 1.4.0.dev3\n", "moorsolve 1.3.0", True),  # version strings masked
    ("wrote /tmp/abc/x.png\n", "wrote /home/u/x.png", True),   # paths masked
    ("T/MBL 0.32\n", "T/MBL 0.32", True),
    ("6 iterations\n", "7 iterations", False),
])
def test_output_comparison_rules(printed, shown, same):
    assert (run_blocks.compare_output(printed, shown) == "") is same


def test_the_gallery_shows_every_example_and_its_committed_picture():
    import make_gallery
    assert (DOCS / "gallery.md").read_text(encoding="utf-8") == make_gallery.render(), \
        "docs/gallery.md is stale: run python docs/make_gallery.py"
    found = make_gallery.examples()
    assert {p.name for p, _, _ in found} == {p.name for p in (ROOT / "examples").glob("*.py")}
    drawn = [p for p, _, draws in found if draws]
    assert len(drawn) >= 3
    for path in drawn:
        png = DOCS / "gallery" / f"{path.stem}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", f"{png.name} is not committed"
