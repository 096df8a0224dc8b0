"""Read a commented CSV table shipped beside the catalogue modules."""

from __future__ import annotations

import csv
import io
from importlib import resources


def read_rows(filename: str) -> list:
    """The rows of ``filename`` (in this package) as dicts; ``#`` lines are comments."""
    text = resources.files(__package__).joinpath(filename).read_text(encoding="utf-8")
    body = "\n".join(line for line in text.splitlines() if not line.startswith("#"))
    return list(csv.DictReader(io.StringIO(body)))
