"""``cost``: every line and anchor of a case priced from the cost basis."""

from __future__ import annotations

import json

from ..errors import CaseError
from .common import EXIT_OK, print_text


def add_commands(sub) -> None:
    p = sub.add_parser("cost", help="price every line and anchor (MoorPy 1.3 cost basis, USD)")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--material", action="append", default=[], metavar="TYPE=MATERIAL",
                   help="material of a line type that is not a catalogue line (chain, "
                        "chain_studlink, wire, polyester, nylon, hmpe); repeatable")
    p.add_argument("--price", action="append", default=[], metavar="TYPE=USD_PER_M",
                   help="a line type's price per metre instead of the basis; repeatable")
    p.add_argument("--json", action="store_true", help="print the cost as JSON")
    p.set_defaults(run=run_cost)


def _pairs(items: list, option: str, number: bool = False) -> dict:
    out = {}
    for text in items:
        name, sep, value = text.partition("=")
        if not sep or not name or not value:
            raise CaseError(option, f"{text!r}: give TYPE=VALUE")
        if number:
            try:
                value = float(value)
            except ValueError:
                raise CaseError(option, f"{text!r}: the price must be a number") from None
        out[name] = value
    return out


def run_cost(args) -> int:
    from .. import load_case
    from ..checks.cost import mooring_cost
    from ..report.cost import format_cost_table
    from ..report.text import _finite
    materials = _pairs(args.material, "--material")
    prices = _pairs(args.price, "--price", number=True)
    case = load_case(args.case)
    for option, given in (("--material", materials), ("--price", prices)):
        for name in given:
            if name not in case.line_types:
                raise CaseError(option, f"{name!r} is not a line type of the case; its line "
                                        f"types: {', '.join(case.line_types)}")
    try:
        priced = mooring_cost(case, materials=materials, prices=prices)
    except CaseError as exc:
        if exc.field.startswith("prices."):
            raise CaseError("--price", exc.detail) from None
        if not exc.field.startswith("materials."):
            raise
        name = exc.field.split(".", 1)[1]
        if name in materials:           # an unknown material: the basis's list says it
            raise CaseError("--material", exc.detail) from None
        from ..catalog.costs import line_materials
        raise CaseError("--material", f"line type {name!r} is not a catalogue line: give "
                                      f"--material {name}=MATERIAL (one of "
                                      f"{', '.join(line_materials())}) or --price "
                                      f"{name}=USD_PER_M") from None
    if args.json:
        print_text(json.dumps(_finite(priced.to_dict()), indent=2))
    else:
        print_text(format_cost_table(priced, case.name))
    return EXIT_OK
