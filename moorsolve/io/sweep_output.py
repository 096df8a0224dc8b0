"""Sweep results written as they complete, so an interrupted sweep loses nothing.

Every row carries ``point``, its position in the grid's product order, so a resumed sweep
knows what is missing. Beside the output, ``<output>.sweep.json`` records what the file
belongs to (hashes of the case-file data and of the grid, the solver, the tolerance, the
number of points, the columns) and whether it is complete; a resume with anything else is
refused.

- ``.csv``: the header, then each finished chunk appended (Arrow's CSV writer) and flushed,
  in the order chunks complete, and synced to disk (``fsync``) at least once a second. On resume a torn last line (a crash mid-write) is dropped.
  When every point is present the file is rewritten, atomically, in product order.
- ``.parquet``: each finished chunk is its own file in ``<output>.parts/`` (written beside
  and renamed, so a part is whole or absent). When every point is present they are
  assembled into ``<output>`` in product order (one atomic rename, readable by
  ``pandas.read_parquet``) and the parts folder is removed. Until then ``<output>``
  does not exist; the parts are the crash-safe record.
"""

from __future__ import annotations

import json
import os
import shutil
import time
import uuid
from pathlib import Path

from ..errors import CaseError
from .output_files import replacing, write_text

FORMATS = (".csv", ".parquet")
#: Most seconds between two syncs of a CSV output to disk.
_SYNC_EVERY_S = 1.0
_RECORD_VERSION = 1


def check_output_path(path, field: str = "output") -> Path:
    """``path`` as a Path, if it names a .csv or .parquet file in an existing folder."""
    p = Path(path)
    if p.suffix.lower() not in FORMATS:
        raise CaseError(field, f"{str(path)!r} must end in .csv or .parquet")
    if not p.parent.resolve().is_dir():
        raise CaseError(field, f"folder {str(p.parent)!r} does not exist")
    return p


def open_sink(path, plan, *, resume: bool = False, overwrite: bool = False):
    """The writer for ``path``: checks what exists (and, on resume, that it belongs to
    ``plan``) but writes nothing until ``start()``."""
    p = check_output_path(path)
    cls = _CsvSink if p.suffix.lower() == ".csv" else _ParquetSink
    return cls(p, plan, resume=resume, overwrite=overwrite)


class _Sink:
    def __init__(self, path: Path, plan, *, resume: bool, overwrite: bool):
        self.path, self.plan = path, plan
        self.record_path = path.with_name(path.name + ".sweep.json")
        self.columns = ["point"] + plan.grid_columns() + plan.result_columns()
        self.done: set[int] = set()
        self._fresh = True
        existing = [q for q in self._owned() if q.exists()]
        if resume and existing:
            self._check_record()
            self.done = self._read_done()
            self._fresh = False
        elif existing and not overwrite:
            raise CaseError("output", f"{str(path)!r} exists; resume it (--resume) or "
                                      f"replace it (--overwrite)")

    def _owned(self) -> list[Path]:
        return [self.path, self.record_path]

    def record(self, complete: bool) -> dict:
        plan = self.plan
        return {"moorsolve_sweep": _RECORD_VERSION, "case": plan.case.name,
                "grid": plan.grid_record(),
                **plan.fingerprint(), "columns": self.columns, "complete": complete}

    def _check_record(self) -> None:
        if not self.record_path.exists():
            raise CaseError("resume", f"{str(self.path)!r} has no sweep record "
                                      f"{self.record_path.name!r}: cannot tell which case "
                                      f"and grid it was made for")
        try:
            old = json.loads(self.record_path.read_text())
        except (OSError, ValueError) as err:
            raise CaseError("resume", f"{self.record_path.name!r} is unreadable: {err}") from None
        new = self.record(False)
        for key, what in (("case_sha256", "case (the case-file data differ)"),
                          ("grid_sha256", "grid (the --set values differ)"),
                          ("solver", "solver"), ("tol", "tolerance"),
                          ("columns", "set of columns")):
            if old.get(key) != new[key]:
                raise CaseError("resume", f"{str(self.path)!r} was made for a different "
                                          f"{what}; start a new file or use --overwrite")

    def start(self) -> None:
        if self._fresh:
            for q in self._owned():
                if q.is_dir():
                    shutil.rmtree(q)
                elif q.exists():
                    q.unlink()
        write_text(self.record_path, json.dumps(self.record(False)), sync=True)
        self._open()

    def finish(self):
        frame = self._assemble()
        write_text(self.record_path, json.dumps(self.record(True)), sync=True)
        return frame


class _CsvSink(_Sink):
    def _read_done(self) -> set[int]:
        if not self.path.exists():
            return set()
        header, lines = self._lines()
        # Drop a torn last line and duplicates: the file keeps whole rows only.
        write_text(self.path, header + "".join(lines.values()), sync=True)
        return set(lines)

    def _lines(self):
        text = self.path.read_text(encoding="utf-8")
        parts = text.splitlines(keepends=True)
        expected = self._header()
        if not parts or parts[0] != expected:
            raise CaseError("resume", f"{str(self.path)!r} does not start with this sweep's "
                                      f"header")
        lines = {}
        self._rows_in_file = len(parts) - 1
        for line in parts[1:]:
            if not line.endswith("\n"):
                break                           # torn by an interruption
            head = line.split(",", 1)[0]
            if head.isdigit() and int(head) < self.plan.n_points:
                lines.setdefault(int(head), line)
        return expected, lines

    def _header(self) -> str:
        import pandas as pd
        return pd.DataFrame(columns=self.columns).to_csv(index=False, lineterminator="\n")

    def _open(self) -> None:
        if not self.path.exists():
            write_text(self.path, self._header(), sync=True)
        self._file = open(self.path, "ab")
        self._synced = time.monotonic()

    def write(self, frame) -> None:
        # Arrow's CSV writer (C++, floats in their shortest exact form) rather than
        # pandas' per-cell formatting, which cost more than solving the rows.
        import pyarrow as pa
        import pyarrow.csv as pa_csv

        table = pa.Table.from_pandas(frame.reset_index(), preserve_index=False)
        pa_csv.write_csv(table, self._file, pa_csv.WriteOptions(
            include_header=False, quoting_style="needed"))
        self._file.flush()          # whole rows in the file if this process is killed
        # On disk at most a second later if the machine goes down (an fsync per chunk
        # cost seconds on a 100,000-row table).
        now = time.monotonic()
        if now - self._synced >= _SYNC_EVERY_S:
            os.fsync(self._file.fileno())
            self._synced = now

    def _assemble(self):
        import pandas as pd
        os.fsync(self._file.fileno())
        self._file.close()
        header, lines = self._lines()
        order = list(lines)
        if len(lines) == self.plan.n_points and (order != sorted(order)
                                                 or self._rows_in_file != len(lines)):
            write_text(self.path, header + "".join(lines[i] for i in sorted(lines)),
                       sync=True)
        dtypes = self.plan.column_types()
        frame = pd.read_csv(self.path, index_col="point", engine="pyarrow",
                            dtype={c: dtypes[c] for c in self.columns if c != "point"})
        for column, kind in dtypes.items():
            if kind is str and column in frame:
                frame[column] = frame[column].fillna("").astype(object)
        return frame.sort_index()


class _ParquetSink(_Sink):
    @property
    def parts(self) -> Path:
        return self.path.with_name(self.path.name + ".parts")

    def _owned(self) -> list[Path]:
        return [self.path, self.record_path, self.parts]

    def _read_done(self) -> set[int]:
        import pyarrow.parquet as pq
        done = set()
        files = [self.path] if self.path.exists() else sorted(self.parts.glob("part-*.parquet"))
        for f in files:
            done.update(int(i) for i in pq.read_table(f, columns=["point"])["point"].to_pylist())
        return done

    def _open(self) -> None:
        if not self.path.exists():           # a finished file has no parts
            self.parts.mkdir(exist_ok=True)

    def write(self, frame) -> None:
        first = int(frame.index.min())
        target = self.parts / f"part-{first:09d}-{uuid.uuid4().hex[:8]}.parquet"
        with replacing(target) as tmp:
            frame.to_parquet(tmp)

    def _assemble(self):
        import pandas as pd
        if self.path.exists() and not self.parts.exists():
            return pd.read_parquet(self.path)
        import pyarrow as pa
        import pyarrow.compute as pc
        import pyarrow.parquet as pq

        files = sorted(self.parts.glob("part-*.parquet"))
        if not files:
            return None
        # Assembled in Arrow (no round trip through pandas and back for every part).
        table = pa.concat_tables([pq.read_table(f) for f in files])
        if len(table) < self.plan.n_points:
            return table.to_pandas()
        if len(pc.unique(table["point"])) < len(table):       # a resume wrote a part twice
            frame = table.to_pandas()
            table = pa.Table.from_pandas(frame[~frame.index.duplicated()])
        table = table.sort_by("point")
        with replacing(self.path) as tmp:
            pq.write_table(table, tmp)
        shutil.rmtree(self.parts)
        return table.to_pandas()
