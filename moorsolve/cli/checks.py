"""``check`` and the Hu & Tang inverse problems (``anchor-distance``, ``chain-length``,
``uplift``)."""

from __future__ import annotations

import json

from ..errors import CaseError
from .common import (EXIT_NO_EQUILIBRIUM, EXIT_OK, bad_input, check_output, print_text,
                     tolerance_option)


def add_commands(sub) -> None:
    from ..model.scene import STANDARDS
    p = sub.add_parser("check", help="mooring checks: intact and damaged conditions")
    p.add_argument("case", help="case file (YAML)")
    p.add_argument("--standard", choices=STANDARDS, default=None,
                   help="criteria table (default: the case's checks.standard, else api-rp-2sk)")
    p.add_argument("--method", choices=("quasi_static", "dynamic"), default=None,
                   help="in a sea state, the line tension's dynamic part from the lines "
                        "re-solved at the design offset (quasi_static) or from the lines' "
                        "dynamics (dynamic; default where the case's lines are dynamic)")
    p.add_argument("--json", action="store_true", help="print the check as JSON")
    p.add_argument("--report", default=None, help="write a self-contained HTML report")
    p.add_argument("--no-damaged", action="store_true", help="intact condition only")
    p.add_argument("--end-of-life", action="store_true",
                   help="check the mooring after its design life: corroded steel, crept "
                        "fibre (the case's checks.corrosion and checks.creep)")
    tolerance_option(p)
    p.set_defaults(run=run_check)
    inverse_help = {
        "anchor-distance": "least anchor distance with no anchor uplift (Hu & Tang Tables 1, 2, 4)",
        "chain-length": "least chain for a load keeping a grounded length",
        "uplift": "anchor uplift force and angle at a given anchor distance (Hu & Tang Table 3)",
    }
    for name, text in inverse_help.items():
        p = sub.add_parser(name, help=text)
        p.add_argument("--height", required=True,
                       help="fairlead above the anchor, e.g. '20.85 m' (the water depth)")
        p.add_argument("--weight", required=True,
                       help="submerged weight per length, e.g. '0.13 t/m' or '1275 N/m'")
        load = p.add_mutually_exclusive_group(required=True)
        load.add_argument("--tension", help="fairlead tension, e.g. '1623.5 kN'")
        load.add_argument("--horizontal-tension", help="horizontal tension, e.g. '372 kN'")
        p.add_argument("--ea", default=None, help="axial stiffness (default inextensible)")
        p.add_argument("--gravity", default="9.80665",
                       help="for weights given as mass per length (Hu & Tang use 10)")
        if name == "chain-length":
            p.add_argument("--grounded", required=True, help="length to keep on the seabed")
            p.add_argument("--inboard", default="0", help="inboard length added to the order")
        if name == "uplift":
            p.add_argument("--distance", required=True, help="anchor distance, e.g. '121.06 m'")
        p.add_argument("--json", action="store_true", help="print the answer as JSON")
        p.set_defaults(run=run_inverse)


def run_check(args) -> int:
    from .. import load_case
    from ..checks import run_checks
    case = load_case(args.case)
    if args.report is not None:
        check_output(args.report, "--report", (".html", ".htm"), describe=".html")
    if args.end_of_life:
        return _run_end_of_life(args, case)
    report = run_checks(case, standard=args.standard, tol=args.tol, method=args.method,
                        damaged=False if args.no_damaged else None)
    from ..report.check_html import check_json, format_check_table, write_html_report
    if args.report is not None:
        write_html_report(report, case, args.report, case_file=args.case)
    print_text(check_json(report) if args.json else format_check_table(report))
    if args.report is not None and not args.json:
        print_text(f"wrote {args.report}")
    if not args.json and case.checks is not None and case.checks.wear is not None:
        print_text("note: the new mooring; the case gives corrosion or creep, so check it "
                   "at the end of its design life too: --end-of-life")
    return EXIT_OK if report.passed else EXIT_NO_EQUILIBRIUM


def _run_end_of_life(args, case) -> int:
    from ..checks.end_of_life import run_end_of_life
    from ..report.check_html import write_html_report
    from ..report.end_of_life import end_of_life_json, end_of_life_text
    eol = run_end_of_life(case, standard=args.standard, tol=args.tol,
                          damaged=False if args.no_damaged else None)
    if args.report is not None:
        write_html_report(eol.report, eol.case, args.report, case_file=args.case)
    print_text(end_of_life_json(eol) if args.json else end_of_life_text(eol))
    if args.report is not None and not args.json:
        print_text(f"wrote {args.report}")
    return EXIT_OK if eol.passed else EXIT_NO_EQUILIBRIUM


def run_inverse(args) -> int:
    from ..model.units import to_si, weight_per_length_to_si
    from ..studies import inverse
    try:
        gravity = to_si(args.gravity, "acceleration", "--gravity")
        if not gravity > 0:
            raise CaseError("--gravity", f"{args.gravity} must be > 0")
        kwargs = {
            "height": to_si(args.height, "length", "--height"),
            "weight": weight_per_length_to_si(args.weight, gravity, "--weight"),
            "ea": None if args.ea is None else to_si(args.ea, "force", "--ea"),
        }
        if args.tension is not None:
            kwargs["fairlead_tension"] = to_si(args.tension, "force", "--tension")
        else:
            kwargs["horizontal_tension"] = to_si(args.horizontal_tension, "force",
                                                 "--horizontal-tension")
        if args.command == "chain-length":
            kwargs["grounded_length"] = to_si(args.grounded, "length", "--grounded")
            kwargs["inboard_length"] = to_si(args.inboard, "length", "--inboard")
            function = inverse.required_chain_length
        elif args.command == "uplift":
            kwargs["anchor_distance"] = to_si(args.distance, "length", "--distance")
            function = inverse.uplift_at_distance
        else:
            function = inverse.minimum_anchor_distance
        answer = function(**kwargs)
    except ValueError as exc:      # the inverse problems' own bounds; CaseError is one too
        return bad_input(exc)
    if args.json:
        print_text(json.dumps(answer.to_dict(), indent=2))
        return EXIT_OK
    a = answer
    print_text("\n".join([
        f"anchor distance      {a.anchor_distance_m:12.4f} m",
        f"fairlead height      {a.height_m:12.4f} m",
        f"horizontal tension   {a.horizontal_tension_N / 1e3:12.4f} kN",
        (f"fairlead tension     {a.fairlead_tension_N / 1e3:12.4f} kN at "
         f"{a.fairlead_angle_deg:.5f} deg"),
        (f"line length          {a.length_m:12.4f} m (suspended {a.suspended_length_m:.4f}, "
         f"grounded {a.grounded_length_m:.4f})"),
        (f"anchor uplift        {a.anchor_vertical_N / 1e3:12.4f} kN at "
         f"{a.uplift_angle_deg:.5f} deg"),
    ] + ([f"order length         {a.order_length_m:12.4f} m"]
         if args.command == "chain-length" else [])))
    return EXIT_OK

