"""Write docs/case-file-reference.md from the case-file schema: ``python
docs/make_case_reference.py``.

The page is generated, never edited by hand: every section of
:mod:`moorsolve.model.schema` with each key's unit, default, allowed values and meaning.
tests/model/test_schema.py fails when the committed page differs from :func:`render`.
"""

from __future__ import annotations

import pathlib

from moorsolve.model import schema

PAGE = pathlib.Path(__file__).resolve().parent / "case-file-reference.md"

INTRO = """\
# Case-file reference

Every key a case file may hold, section by section: its unit (SI; a value may carry any
unit of that kind, `"81 mm"`, `"372 kN"`, `"0.13 t/m"`), its default (*required*: it must be
given; *none*: absent means the feature is off), the values allowed and what it means.
A key not listed is refused with a message naming it and the keys allowed. How the sections
fit together, with examples, is in [Case files](case-files.md).

This page is generated from the schema the validators read (`moorsolve/model/schema/`),
so it lists exactly what moorsolve accepts; `python docs/make_case_reference.py` rewrites
it, and a test fails when it is stale.
"""


def _value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, (tuple, list)):
        return "[" + ", ".join(_value(v) for v in value) + "]"
    return str(value)


def _default(spec) -> str:
    if spec.default is schema.REQUIRED:
        return "*required*"
    if spec.default is schema.NONE:
        return "*none*"
    return f"`{_value(spec.default)}`" if not isinstance(spec.default, str) or \
        spec.default in spec.choices else _value(spec.default)


def _allowed(spec) -> str:
    parts = []
    if spec.choices:
        parts.append(" \\| ".join(f"`{_value(c)}`" for c in spec.choices))
    if spec.shape:
        parts.append(f"`{spec.shape}`")
    if spec.range:
        parts.append(spec.range)
    if spec.section:
        parts.append(", ".join(f"[{n}](#{n})" for n in spec.section.split("|")))
    if not parts and spec.kind in schema.TYPES and spec.kind not in ("any", "mapping"):
        parts.append(schema.TYPES[spec.kind])
    return "; ".join(parts).replace("|", "\\|").replace("\\\\|", "\\|")


def _cell(text: str) -> str:
    return text.replace("\n", " ")


def render() -> str:
    """The reference page's Markdown."""
    out = [INTRO]
    for sec in schema.SECTIONS.values():
        out.append(f"## `{sec.where}` {{#{sec.name}}}\n")
        out.append(f"{sec.doc}\n")
        out.append("| key | unit | default | allowed | meaning |")
        out.append("|---|---|---|---|---|")
        for key, spec in sec.keys.items():
            unit = spec.unit or ("-" if spec.kind == "dimensionless" else "")
            if spec.kind == "weight":
                unit = "N/m (or kg/m)"
            out.append(f"| `{key}` | {unit} | {_cell(_default(spec))} | "
                       f"{_cell(_allowed(spec))} | {_cell(spec.doc)} |")
        out.append("")
    return "\n".join(out)


def main() -> None:
    PAGE.write_text(render(), encoding="utf-8")
    print(f"wrote {PAGE}")


if __name__ == "__main__":
    main()
