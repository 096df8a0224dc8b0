"""Every code block of the documentation runs (issue 18): the pages of docs/ block by block
in a fresh folder (docs/run_blocks.py), the README's Python blocks from the repository
root, and the script that draws the documentation's pictures."""

from __future__ import annotations

import subprocess
import sys

import pytest
from conftest import ROOT

DOCS = ROOT / "docs"
sys.path.insert(0, str(DOCS))

import run_blocks  # noqa: E402

PAGES = sorted(DOCS.glob("*.md"))


def test_there_is_a_walkthrough_linked_from_the_readme():
    assert DOCS / "walkthrough.md" in PAGES
    assert "docs/walkthrough.md" in (ROOT / "README.md").read_text(encoding="utf-8")


@pytest.mark.parametrize("page", PAGES, ids=[p.name for p in PAGES])
def test_every_block_of_a_docs_page_runs(page, tmp_path):
    runnable = [b for b in run_blocks.blocks(page.read_text(encoding="utf-8"))
                if b.lang in ("bash", "python") or (b.lang == "yaml" and "file" in b.attrs)]
    assert runnable, f"{page.name} has no runnable block"
    run_blocks.run(page, tmp_path, log=lambda *_: None, in_process=True)


def test_the_readme_python_blocks_run(monkeypatch):
    blocks = [b for b in run_blocks.blocks((ROOT / "README.md").read_text(encoding="utf-8"))
              if b.lang == "python"]
    assert blocks
    monkeypatch.chdir(ROOT)
    namespace: dict = {"__name__": "__readme__"}
    for block in blocks:
        exec(compile(block.code, f"README.md:{block.line}", "exec"), namespace)


def test_the_readme_command_examples_run(tmp_path):
    """The README's shell blocks, from an empty folder; the ones that install packages
    are the quick start (run by .ci/run) and the benchmarks' setup."""
    def runnable(block):
        return block.lang == "bash" and "pip install" not in block.code
    blocks = [b for b in run_blocks.blocks((ROOT / "README.md").read_text(encoding="utf-8"))
              if runnable(b)]
    assert any("moorsolve check" in b.code and "moorsolve stiffness" in b.code for b in blocks)
    run_blocks.run(ROOT / "README.md", tmp_path, log=lambda *_: None, select=runnable,
                   in_process=True)
    assert (tmp_path / "ship.html").exists() and (tmp_path / "dock_optimised.yaml").exists()


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
    text = (ROOT / "README.md").read_text() + (DOCS / "walkthrough.md").read_text()
    import re
    for name in re.findall(r"\]\(((?:docs/)?[\w]+\.png)\)", text):
        assert (ROOT / name).exists() or (DOCS / name).exists(), f"{name} is not committed"
