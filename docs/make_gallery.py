"""Build the gallery page from examples/: ``python docs/make_gallery.py [--text-only]``.

Each example's docstring is its entry; an example that takes ``--out FOLDER`` is run into
docs/gallery/ and the picture it writes (``<example>.png``) is shown under its text. The
pictures are committed, so building the site runs nothing; tests/test_docs.py checks that
the page is what :func:`render` makes of the examples and that every picture it shows is
committed (tests/test_examples.py runs every example).
"""

from __future__ import annotations

import argparse
import ast
import os
import pathlib
import subprocess
import sys

DOCS = pathlib.Path(__file__).resolve().parent
ROOT = DOCS.parent
EXAMPLES = ROOT / "examples"
FOLDER = DOCS / "gallery"
PAGE = DOCS / "gallery.md"

INTRO = """\
# Gallery

The examples of `examples/`, each with what it does and the picture it draws. Run one from
the repository's root (`python examples/NAME.py --out FOLDER`); `python docs/make_gallery.py`
runs them all again and rewrites this page.
"""


def examples() -> list:
    """``(path, docstring, draws)`` of every example, by name."""
    out = []
    for path in sorted(EXAMPLES.glob("*.py")):
        source = path.read_text(encoding="utf-8")
        doc = ast.get_docstring(ast.parse(source)) or ""
        draws = "--out" in source and f'"{path.stem}.png"' in source
        out.append((path, doc, draws))
    return out


def _entry(path: pathlib.Path, doc: str, draws: bool) -> str:
    all_lines = doc.splitlines()
    head = 0
    while head < len(all_lines) and all_lines[head].strip() and \
            not all_lines[head].strip().startswith("Run:"):
        head += 1
    title = " ".join(line.strip() for line in all_lines[:head])
    lines = []
    run = None
    for line in all_lines[head:]:
        if line.strip().startswith("Run:"):
            run = line.split("Run:", 1)[1].strip().replace("``", "")
            continue
        lines.append(line)
    text = "\n".join(lines).strip()
    out = [f"## {title.strip().rstrip('.')}\n", f"`examples/{path.name}`\n"]
    if run:
        out.append(f"```text\n{run}\n```\n")      # shown, not run by the docs' test
    if text:
        out.append(text + "\n")
    if draws:
        out.append(f"![{title.strip().rstrip('.')}](gallery/{path.stem}.png)\n")
    return "\n".join(out)


def render() -> str:
    """The gallery page's Markdown."""
    return INTRO + "\n" + "\n".join(_entry(*e) for e in examples())


def draw() -> None:
    """Run every example that draws, into docs/gallery/."""
    FOLDER.mkdir(exist_ok=True)
    env = dict(os.environ, MPLBACKEND="Agg")
    for path, _, draws in examples():
        if draws:
            print(f"running {path.name}")
            subprocess.run([sys.executable, str(path), "--out", str(FOLDER)], check=True,
                           cwd=ROOT, env=env, stdout=subprocess.DEVNULL)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--text-only", action="store_true",
                        help="rewrite the page without running the examples")
    args = parser.parse_args(argv)
    if not args.text_only:
        draw()
    PAGE.write_text(render(), encoding="utf-8")
    print(f"wrote {PAGE}")


if __name__ == "__main__":
    main()
