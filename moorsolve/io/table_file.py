"""A load table read from a file (:mod:`moorsolve.studies.load_table` validates and
sweeps it; the study itself reads no file)."""

from __future__ import annotations

from ..errors import CaseError

__all__ = ["read_table"]


def read_table(path) -> "object":
    """A load table from a ``.csv`` or ``.parquet`` file, as a pandas DataFrame."""
    import pandas as pd
    from pathlib import Path

    p = Path(path)
    if not p.is_file():
        raise CaseError("table", f"{path}: no such file")
    try:
        if p.suffix.lower() == ".parquet":
            return pd.read_parquet(p)
        if p.suffix.lower() == ".csv":
            return pd.read_csv(p)
    except (OSError, ValueError) as err:
        raise CaseError("table", f"{path}: {err}") from None
    raise CaseError("table", f"{path}: a load table is a .csv or .parquet file")
