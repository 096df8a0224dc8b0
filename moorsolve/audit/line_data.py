"""What the audit's per-line checks (:mod:`.lines`) read of the case: its lines as flat
arrays, made once per lines tuple, and the strain of their segments under a tension (the
case's stretch law, evaluated by :mod:`moorsolve.physics.stretch`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..concurrency import LockedLRU
from ..physics.stretch import numeric_law

__all__ = ["LineData", "line_data", "strain", "weights_in_air"]


def weights_in_air(leg_case) -> np.ndarray:
    """Per segment, its weight [N/m] above the water: its weight in air where the case
    gives it, else its weight in water."""
    return np.array([sg.line_type.weight_in_air if sg.line_type.weight_in_air is not None
                     else sg.line_type.weight_in_water for sg in leg_case.segments])


@dataclass(frozen=True)
class LineData:
    """The case's lines as flat arrays (segments of all lines end to end), made once per
    lines tuple: what the audit reads of the case, not of the result."""

    seg_off: np.ndarray        # per line: its first segment in the flat arrays
    nseg: np.ndarray
    length: np.ndarray         # per segment: unstretched length, weights [N/m]
    weight: np.ndarray
    in_air: np.ndarray
    compliance: np.ndarray     # 1/EA (0 for inextensible or a stretch law's segment)
    laws: tuple                # (flat segment, law) of segments with a stretch law
    ends: tuple                # per line: cumulative segment ends from end A
    L: np.ndarray              # per line: total unstretched length
    wsum: np.ndarray           # sum |w| * length
    wsum_ends: np.ndarray      # the same over the cumulative ends' differences
    wmax: np.ndarray
    clumps: np.ndarray         # sum of joint clump weights
    multi: np.ndarray          # more than one segment
    segments: np.ndarray       # 0, 1, ... per flat segment, and the line of each
    seg_line: np.ndarray


_DATA = LockedLRU(256)


def line_data(lines) -> LineData:
    """The :class:`LineData` of ``lines`` (a case's lines tuple), kept while it lives."""
    hit = _DATA.get(id(lines))
    if hit is not None and hit[0] is lines:
        return hit[1]
    segs = [s for line in lines for s in line.segments]
    nseg = np.array([len(line.segments) for line in lines], int)
    seg_off = np.concatenate([[0], np.cumsum(nseg)[:-1]]).astype(int)
    laws, compliance = [], np.zeros(len(segs))
    for k, s in enumerate(segs):
        law = numeric_law(s.line_type)
        if law is not None:
            laws.append((k, law))
        elif s.line_type.ea:
            compliance[k] = 1.0 / s.line_type.ea
    length = np.array([s.length for s in segs], float)
    weight = np.array([s.line_type.weight_in_water for s in segs], float)
    ends = []
    for i, line in enumerate(lines):
        lens = length[seg_off[i]:seg_off[i] + nseg[i]]
        ends.append(np.concatenate([[0.0], np.cumsum(lens)]))
    aw = np.abs(weight)
    data = LineData(
        seg_off=seg_off, nseg=nseg, length=length, weight=weight,
        in_air=np.concatenate([weights_in_air(line) for line in lines]),
        compliance=compliance, laws=tuple(laws), ends=tuple(ends),
        L=np.array([float(e[-1]) for e in ends]),
        wsum=np.array([float(np.sum(aw[o:o + m] * length[o:o + m]))
                       for o, m in zip(seg_off, nseg)]),
        wsum_ends=np.array([float(np.sum(aw[o:o + m] * np.diff(e)))
                            for o, m, e in zip(seg_off, nseg, ends)]),
        wmax=np.array([float(np.max(aw[o:o + m])) for o, m in zip(seg_off, nseg)]),
        clumps=np.array([float(sum(c.weight for c in line.joint_clumps if c is not None))
                         for line in lines]),
        multi=nseg > 1, segments=np.arange(len(segs)),
        seg_line=np.repeat(np.arange(len(lines)), nseg))
    _DATA.put(id(lines), (lines, data))
    return data


def strain(data: LineData, gseg: np.ndarray, T: np.ndarray) -> np.ndarray:
    """Strain of flat segments ``gseg`` at tensions ``T`` (the same shape)."""
    eps = data.compliance[gseg] * T
    for k, law in data.laws:
        mask = gseg == k
        if np.any(mask):
            eps[mask] = law.strain(np.maximum(T[mask], 0.0))
    return eps
