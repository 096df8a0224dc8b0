"""Output files are written whole or not at all: beside the target under a temporary name,
then renamed onto it, with the permissions a newly created file would get (``mkstemp``
alone makes them private). One owner for every file moorsolve writes, and for the YAML
layout of the case files it writes (imported MoorDyn models, optimised designs).

A case file that is an edit of another (an optimised design) is written by editing the
original text's YAML tree (ruamel.yaml, round trip): its comments, key order, flow or
block layout and quoting stay, and only the values that changed are rewritten."""

from __future__ import annotations

import contextlib
import numbers
import os
import re
import tempfile
from collections.abc import Mapping
from pathlib import Path

import yaml

from ..errors import CaseError

__all__ = ["replacing", "write_text", "write_case_yaml", "write_edited_case_yaml"]


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


def write_edited_case_yaml(original, before: Mapping, after: Mapping, path,
                           header: str = "") -> None:
    """Write the case file ``original`` with the changes from ``before`` to ``after``
    applied, keeping its comments and layout, to ``path`` atomically.

    Where every change is a new value for a scalar the file already holds (lengths, anchor
    coordinates, the name), only those scalars' text is replaced and every other byte of
    the file stays. Otherwise the file's YAML tree is edited and written again by
    ruamel.yaml (comments and key order stay; spacing inside a line may not). Either way
    the text written is read back and must hold ``after``.

    Parameters
    ----------
    original : str or path
        The case file the data came from.
    before : mapping
        Its data as loaded (``Case.source``).
    after : mapping
        The edited data; only the values that differ from ``before`` are written.
    path : str or path
        Where to write.
    header : str
        Comment lines put above the original text (a ``#`` added where a line lacks one).
    """
    import io

    from ruamel.yaml import YAML
    from ruamel.yaml.util import load_yaml_guess_indent

    text = Path(original).read_text(encoding="utf-8")
    before, after = _plain(before), _plain(after)
    _, indent, block_seq_indent = load_yaml_guess_indent(text)
    yaml_rt = YAML(typ="rt")
    yaml_rt.preserve_quotes = True
    yaml_rt.width = 4096
    yaml_rt.indent(mapping=indent or 2, sequence=(indent or 2) + (block_seq_indent or 0),
                   offset=block_seq_indent or 0)
    tree = yaml_rt.load(text)
    edits: list = []
    out = None
    if _scalar_edits(tree, before, after, edits, flow=False):
        out = _replace_tokens(text, edits, after)
    if out is None or _plain(yaml.safe_load(out)) != after:
        _apply_changes(tree, before, after)
        buffer = io.StringIO()
        yaml_rt.dump(tree, buffer)
        out = buffer.getvalue()
    lines = header.splitlines()
    preamble = "".join((line if line.startswith("#") else f"# {line}") + "\n" for line in lines)
    write_text(path, preamble + out)


def _scalar_edits(node, before, after, edits: list, flow: bool) -> bool:
    """Collect ``(line, column, new value)`` for every scalar of ``node`` that changes from
    ``before`` to ``after``; False when a change is more than a scalar's new value."""
    from ruamel.yaml.comments import CommentedMap, CommentedSeq
    if isinstance(node, CommentedMap):
        if not isinstance(after, Mapping) or not isinstance(before, Mapping):
            return False
        if set(node) != set(after) - ({"name"} if "name" not in node else set()):
            return False
        items = [(k, node[k], before.get(k, _MISSING), after[k], node.lc.value(k))
                 for k in node]
        if "name" not in node and after.get("name") != before.get("name"):
            edits.append((None, None, after["name"]))        # a new first key
    elif isinstance(node, CommentedSeq):
        if not isinstance(after, list) or not isinstance(before, list) \
                or not len(node) == len(before) == len(after):
            return False
        items = [(i, node[i], before[i], after[i], node.lc.item(i)) for i in range(len(node))]
    else:
        return False
    inner = bool(flow or node.fa.flow_style())
    for _, here, old, new, (line, col) in items:
        if _same(old, new):
            continue
        if isinstance(here, (CommentedMap, CommentedSeq)):
            if not _scalar_edits(here, old, new, edits, inner):
                return False
        elif isinstance(new, (Mapping, list)):
            return False
        else:
            edits.append((line, col, new, inner))
    return True


_FLOW_END = re.compile(r"\s*(?:[,\]}]|#|$)")
_BLOCK_END = re.compile(r"\s*(?:\s#|$)")


def _replace_tokens(text: str, edits: list, after: Mapping):
    """``text`` with each edited scalar token replaced; None where a token is not a
    one-line scalar at the place the parser reported."""
    lines = text.split("\n")
    new_name = [e for e in edits if e[0] is None]
    for line, col, value, flow in sorted((e for e in edits if e[0] is not None),
                                         key=lambda e: (e[0], e[1]), reverse=True):
        row = lines[line]
        end = _token_end(row, col, flow)
        if end is None:
            return None
        lines[line] = row[:col] + _scalar_text(value) + row[end:]
    out = "\n".join(lines)
    if new_name:
        # No name in the file: one before its first key (after its leading comments).
        body = out.split("\n")
        first = next(i for i, r in enumerate(body) if r.strip() and not r.startswith("#"))
        body.insert(first, f"name: {_scalar_text(new_name[0][2])}")
        out = "\n".join(body)
    return out


def _token_end(row: str, col: int, flow: bool):
    if col >= len(row):
        return None
    quote = row[col]
    if quote in "\"'":
        i = col + 1
        while i < len(row):
            if row[i] == "\\" and quote == '"':
                i += 2
                continue
            if row[i] == quote:
                if quote == "'" and row[i + 1: i + 2] == "'":
                    i += 2
                    continue
                return i + 1
            i += 1
        return None                                 # a quoted scalar over several lines
    match = (_FLOW_END if flow else _BLOCK_END).search(row, col)
    end = match.start() if match else len(row)
    return end if end > col else None


def _scalar_text(value) -> str:
    """``value`` as one YAML scalar token."""
    import json
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "null"
    if isinstance(value, (int, float)):
        return repr(value)
    return json.dumps(str(value), ensure_ascii=False)


def _apply_changes(node, before, after):
    """Edit the round-trip mapping ``node`` (holding ``before``) in place so it holds
    ``after``; values equal in both are left as they are written."""
    for key in [k for k in list(node) if k not in after]:
        del node[key]
    for key, new in after.items():
        old = before.get(key, _MISSING) if isinstance(before, Mapping) else _MISSING
        if key not in node:
            node[key] = new
        elif not _same(old, new):
            _edit(node, key, old, new)


def _edit(node, key, old, new):
    """Set ``node[key]`` from ``old`` to ``new``, descending into mappings and lists of
    the same length so that comments and layout inside them stay."""
    from ruamel.yaml.comments import CommentedMap, CommentedSeq
    here = node[key]
    if isinstance(new, Mapping) and isinstance(old, Mapping) and isinstance(here, CommentedMap):
        _apply_changes(here, old, new)
    elif isinstance(new, list) and isinstance(old, list) and isinstance(here, CommentedSeq) \
            and len(old) == len(new) == len(here):
        for i, (o, n) in enumerate(zip(old, new)):
            if not _same(o, n):
                _edit(here, i, o, n)
    else:
        node[key] = new


_MISSING = object()


def _same(a, b) -> bool:
    if a is _MISSING:
        return False
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b
    return a == b
