"""Output files are written whole or not at all: beside the target under a temporary name,
then renamed onto it, with the permissions a newly created file would get (``mkstemp``
alone makes them private). One owner for every file moorsolve writes, and for the YAML
layout of the case files it writes (imported MoorDyn models, optimised designs)."""

from __future__ import annotations

import contextlib
import numbers
import os
import tempfile
from collections.abc import Mapping
from pathlib import Path

import yaml

from ..errors import CaseError

__all__ = ["replacing", "write_text", "write_case_yaml"]


@contextlib.contextmanager
def replacing(path, suffix: str = "", *, field: str = "-o"):
    """Yield a temporary path beside ``path``; when the block ends without error, the
    temporary file replaces ``path``. On error nothing is left behind. A missing folder is
    a CaseError naming ``field`` (the option that gave the path)."""
    path = Path(path)
    if not path.resolve().parent.is_dir():
        raise CaseError(field, f"folder {str(path.resolve().parent)!r} does not exist")
    fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=suffix or path.suffix,
                               dir=path.resolve().parent)
    os.close(fd)
    try:
        yield tmp
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def write_text(path, text: str, *, sync: bool = False, field: str = "-o") -> None:
    """Write ``text`` (UTF-8, newlines as given) to ``path`` atomically; ``sync`` also
    flushes it to the disk before the rename (files that record finished work)."""
    with replacing(path, field=field) as tmp:
        with open(tmp, "w", encoding="utf-8", newline="") as handle:
            handle.write(text)
            if sync:
                handle.flush()
                os.fsync(handle.fileno())


def _plain(node):
    """numpy scalars and tuples to the plain types YAML's safe dumper knows."""
    if isinstance(node, Mapping):
        return {str(k): _plain(v) for k, v in node.items()}
    if isinstance(node, (list, tuple)):
        return [_plain(v) for v in node]
    if isinstance(node, numbers.Integral) and not isinstance(node, bool):
        return int(node)
    if isinstance(node, numbers.Real) and not isinstance(node, bool):
        return float(node)
    return node


def _flow_lists(dumper, data):
    """Short lists of scalars (points, options, table rows) in flow style, everything else
    block style: the layout of the shipped case files."""
    flow = (len(data) <= 4 and all(isinstance(v, (int, float, str, bool, type(None)))
                                   for v in data)
            and sum(len(str(v)) for v in data) < 60)
    return dumper.represent_sequence("tag:yaml.org,2002:seq", data, flow_style=flow)


class _CaseDumper(yaml.SafeDumper):
    pass


_CaseDumper.add_representer(list, _flow_lists)


def write_case_yaml(data: Mapping, path, header: str = "") -> None:
    """Write case-file ``data`` as YAML to ``path`` atomically, after ``header`` (comment
    lines; a ``#`` is added where a line lacks one)."""
    text = yaml.dump(_plain(data), Dumper=_CaseDumper, sort_keys=False, allow_unicode=True,
                     width=100)
    lines = header.splitlines()
    preamble = "".join((line if line.startswith("#") else f"# {line}") + "\n" for line in lines)
    write_text(path, preamble + text)
