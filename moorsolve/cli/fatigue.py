"""``moorsolve fatigue``: line-end fatigue over the case's scatter diagram."""

from __future__ import annotations

import json

from .common import (EXIT_NO_EQUILIBRIUM, EXIT_OK, IMAGE_EXTENSIONS, check_output,
                     print_text, save_figure, solver_option, tolerance_option)


def add_commands(sub) -> None:
    p = sub.add_parser("fatigue", help="fatigue damage and life of every line end over the "
                                       "scatter diagram of checks.fatigue")
    p.add_argument("case", help="case file (YAML) with checks.fatigue")
    p.add_argument("--json", action="store_true", help="print the fatigue result as JSON")
    p.add_argument("--method", choices=("narrow_band", "dirlik"),
                   help="damage from the tension spectrum (default: the case's)")
    p.add_argument("--series", metavar="FILE.csv",
                   help="count tension records by rainflow instead: a CSV with time_s and "
                        "LINE.anchor / LINE.fairlead columns [N], scaled to the design life")
    p.add_argument("--plot", metavar="FILE", help="draw the damage per sea state "
                                                  "(.png, .pdf or .svg)")
    solver_option(p)
    tolerance_option(p)
    p.set_defaults(run=run_fatigue)


def run_fatigue(args) -> int:
    from .. import load_case, solve
    from ..life.fatigue import fatigue

    if args.plot:
        check_output(args.plot, "--plot", IMAGE_EXTENSIONS)
        if args.series is not None:
            from ..errors import CaseError
            raise CaseError("--plot", "draws the damage per sea state: a tension record "
                                      "(--series) has none")
    case = load_case(args.case)
    if args.series is not None:
        from ..io.table_file import read_table
        from ..life.series import series_fatigue
        fr = series_fatigue(case, read_table(args.series))
    else:
        result = solve(case, solver=args.solver, tol=args.tol)
        fr = fatigue(result, method=args.method)
    if args.plot:
        from ..plot.fatigue import plot_damage_per_sea_state

        def draw():
            import matplotlib.pyplot as plt
            fig, ax = plt.subplots(figsize=(10, 5.5), layout="constrained")
            plot_damage_per_sea_state(fr, ax=ax)
            return fig

        save_figure(draw, args.plot)
    print_text(json.dumps(fr.to_dict(), indent=2) if args.json else repr(fr))
    return EXIT_OK if fr.passed else EXIT_NO_EQUILIBRIUM
