"""Run the code blocks of a Markdown page in order, as a reader would type them.

    python docs/run_blocks.py docs/walkthrough.md [--keep DIR]

Fenced blocks are read by their info string:

- ``yaml file=NAME``: written to NAME in the working folder (a case file the reader saves);
- ``bash``: each command run by bash (lines ending in ``\\`` continue); a non-zero exit
  fails the run unless the block says ``exit=N`` (``bash exit=1`` for a check that fails);
- ``python``: executed in one namespace shared by the page's Python blocks, headless;
- anything else (``text`` output, ``yaml`` fragments without a file name): not run.

A ``bash`` or ``python`` block followed at once by a ``text`` (or bare) block shows its
output: what the block prints (stdout) is compared with it (:func:`compare_output`), with
times, residuals at rounding level, paths and version strings masked, numbers equal to
the digits shown, and a line ``...`` standing for any lines. ``text compare=no`` shows an
output that is not compared (an excerpt of another machine's run).

Everything runs in an empty temporary folder (or ``--keep DIR``) holding a link to the
repository's ``cases/``, so a page can use the shipped cases. tests/test_docs.py runs every
page of docs/ this way; docs/make_figures.py keeps the pictures a page's commands draw.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import re
import shlex
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
_FENCE = re.compile(r"^```([^\n`]*)\n(.*?)^```", re.S | re.M)


@dataclass
class Block:
    """One fenced code block: its language, attributes (``key=value``) and code."""

    lang: str
    attrs: dict = field(default_factory=dict)
    code: str = ""
    line: int = 0


def blocks(text: str) -> list[Block]:
    """The fenced code blocks of Markdown ``text``, in order."""
    out = []
    for match in _FENCE.finditer(text):
        info = match.group(1).split()
        lang = info[0] if info else ""
        attrs = dict(item.split("=", 1) for item in info[1:] if "=" in item)
        out.append(Block(lang, attrs, match.group(2), text[:match.start()].count("\n") + 1))
    return out


def commands(code: str) -> list[str]:
    """Shell commands of a bash block: comments dropped, ``\\`` continuations joined."""
    out, current = [], ""
    for raw in code.splitlines():
        line = raw.rstrip()
        if not current and (not line.strip() or line.lstrip().startswith("#")):
            continue
        if line.endswith("\\"):
            current += line[:-1] + " "
            continue
        out.append(current + line)
        current = ""
    if current:
        out.append(current)
    return out


def run(page: Path, workdir: Path, log=print, select=None, in_process: bool = False) -> None:
    """Run every runnable block of ``page`` (those ``select(block)`` accepts, when given)
    in ``workdir``; raise on the first failure.

    ``in_process`` runs a plain ``moorsolve ...`` command (no pipes or redirection) by
    calling :func:`moorsolve.cli.main` in this process, which saves the interpreter's
    start-up per command; anything else still goes to bash.
    """
    page = Path(page)
    workdir = Path(workdir)
    link = workdir / "cases"
    if not link.exists():
        link.symlink_to(ROOT / "cases", target_is_directory=True)
    env = dict(os.environ, MPLBACKEND="Agg")
    # The moorsolve command of this Python first on the PATH.
    env["PATH"] = str(Path(sys.executable).parent) + os.pathsep + env.get("PATH", "")
    namespace: dict = {"__name__": "__docs__"}
    found = blocks(page.read_text(encoding="utf-8"))
    for i, block in enumerate(found):
        if select is not None and not select(block):
            continue
        where = f"{page.name}:{block.line}"
        shown = found[i + 1] if i + 1 < len(found) else None
        if shown is not None and not (shown.lang in ("text", "")
                                      and shown.attrs.get("compare") != "no"):
            shown = None
        printed = []
        if block.lang == "yaml" and "file" in block.attrs:
            (workdir / block.attrs["file"]).write_text(block.code, encoding="utf-8")
        elif block.lang == "bash":
            expected = int(block.attrs.get("exit", "0"))
            for command in commands(block.code):
                log(f"{where}: $ {command}")
                if in_process and _plain_moorsolve(command):
                    status, stdout, stderr = _call_main(command, workdir)
                else:
                    done = subprocess.run(["bash", "-c", command], cwd=workdir, env=env,
                                          capture_output=True, text=True, timeout=600)
                    status, stdout, stderr = done.returncode, done.stdout, done.stderr
                output = stdout + "\n" + stderr
                printed.append(stdout)
                if status != expected:
                    raise RuntimeError(f"{where}: `{command}` exited {status}, "
                                       f"expected {expected}\n{output}")
        elif block.lang == "python":
            log(f"{where}: python block")
            import io
            out = io.StringIO()
            with _inside(workdir), contextlib.redirect_stdout(out):
                exec(compile(block.code, where, "exec"), namespace)
            printed.append(out.getvalue())
        else:
            continue
        if shown is not None:
            problem = compare_output("".join(printed), shown.code)
            if problem:
                raise RuntimeError(f"{where}: the output shown at {page.name}:{shown.line} "
                                   f"differs from what the block prints: {problem}")


#: What differs from run to run or machine to machine, masked before comparing.
_MASKS = (
    # Wall times: "12.6 ms", "(0.22 s)".
    (re.compile(r"\b\d+(?:\.\d+)?(?:e[+-]?\d+)? ?(?:ms|s)(?=[)\s,;]|$)"), "<time>"),
    # Residuals at rounding level: "force residual 2.81e-10 N (9.4e-15 ...)".
    (re.compile(r"(residual|certified|penetration) [-+0-9.e]+( N| m| N m)?( \([-+0-9.e]+"
                r"(?: of max tension)?\))?"), r"\1 <residual>"),
    (re.compile(r"moorsolve \d+\.\d+[\w.+\-]*"), "moorsolve <version>"),
    (re.compile(r"(?<![\w.])(?:/[\w.\-]+){2,}/?"), "<path>"),
)
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def _mask(line: str) -> str:
    for pattern, replacement in _MASKS:
        line = pattern.sub(replacement, line)
    return line.rstrip()


def _same_line(printed: str, shown: str) -> bool:
    """Equal text around the numbers, and each number equal to the digits shown (or to
    1e-6 relative)."""
    a, b = _mask(printed), _mask(shown)
    if _NUMBER.sub("#", a).split() != _NUMBER.sub("#", b).split():
        return False
    for x, y in zip(_NUMBER.findall(a), _NUMBER.findall(b)):
        mantissa = y.lower().split("e")[0]
        decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
        exponent = int(y.lower().split("e")[1]) if "e" in y.lower() else 0
        unit = 10.0 ** (exponent - decimals)
        if abs(float(x) - float(y)) > max(0.5 * unit * (1 + 1e-9), 1e-6 * abs(float(y))):
            return False
    return True


def compare_output(printed: str, shown: str) -> str:
    """Compare what a block printed with the output a page shows after it; return ""
    when they agree, else what differs (the first line shown that was not printed)."""
    got = [line for line in printed.splitlines() if line.strip()]
    want = [line for line in shown.splitlines() if line.strip()]
    i = 0
    for k, line in enumerate(want):
        if line.strip() == "...":
            continue
        free = k > 0 and want[k - 1].strip() == "..."
        while i < len(got) and not _same_line(got[i], line):
            if not free:
                return f"shown {line.strip()!r}, printed {got[i].strip()!r}"
            i += 1
        if i == len(got):
            return f"shown {line.strip()!r}, never printed"
        i += 1
    if i < len(got) and not (want and want[-1].strip() == "..."):
        return f"printed more than shown, from {got[i].strip()!r}"
    return ""


def _plain_moorsolve(command: str) -> bool:
    return command.startswith("moorsolve ") and not set(command) & set("|;&<>$`")


def _call_main(command: str, workdir: Path) -> tuple[int, str, str]:
    """Run ``moorsolve ...`` through :func:`moorsolve.cli.main` in ``workdir``."""
    import io

    from moorsolve.cli import main
    out, err = io.StringIO(), io.StringIO()
    with _inside(workdir), contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            status = main(shlex.split(command, comments=True)[1:])
        except SystemExit as exc:            # --version, argparse errors
            status = exc.code if isinstance(exc.code, int) else 1
    return status, out.getvalue(), err.getvalue()


@contextlib.contextmanager
def _inside(folder: Path):
    import matplotlib
    matplotlib.use("Agg")
    before = Path.cwd()
    os.chdir(folder)
    try:
        yield
    finally:
        os.chdir(before)
        import matplotlib.pyplot as plt
        plt.close("all")


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("page", help="Markdown file")
    parser.add_argument("--keep", default=None, help="run in this folder and keep it")
    args = parser.parse_args(argv)
    if args.keep:
        Path(args.keep).mkdir(parents=True, exist_ok=True)
        run(Path(args.page), Path(args.keep))
    else:
        with tempfile.TemporaryDirectory() as tmp:
            run(Path(args.page), Path(tmp))
    print(f"ran every block of {args.page}")


if __name__ == "__main__":
    main()
