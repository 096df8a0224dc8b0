"""How a catenary block takes a stretch law other than Hooke's: its inputs, its bound law
and the stretch of line lying on a flat seabed.

A block of :mod:`moorsolve.physics.catenary` (or :mod:`moorsolve.physics.sloped`) for a line
with a :class:`~moorsolve.physics.stretch.StretchModel` gets the law's parameters as one
extra input ``law`` (a column of ``model.n_params``); Hooke lines keep the compliance
``ea_inv`` and their own closed forms, and their functions are built exactly as before.
"""

from __future__ import annotations

from typing import Optional

import casadi as ca

from .stretch import Law, StretchModel

__all__ = ["bind", "ground_stretch", "shared", "law_inputs", "law_tag"]


def bind(model: Optional[StretchModel], law):
    """The law ``model`` bound to its parameters ``law`` (a column or a sequence of floats or
    symbols); None for Hooke (``model`` None).

    Raises
    ------
    ValueError
        A law without its parameters.
    """
    if model is None:
        return None
    if law is None:
        raise ValueError(f"a {model.tag} line needs its law parameters (input 'law')")
    return Law(model, law if isinstance(law, (list, tuple)) else ca.vertsplit(law))


def ground_stretch(bound: Law, H, LB, HA, decay):
    """Stretch [m] of ``LB`` of line lying on a flat seabed with tension ``H`` at touchdown.

    Without friction (``decay`` None) the tension is ``H`` throughout: ``LB eps(H)``. With
    friction it falls by ``decay = mu w`` per metre toward the anchor, to ``HA`` there (or
    to zero at ``H/decay`` from touchdown): the loaded length times the mean strain, exact
    for a linear run of tension (:meth:`~moorsolve.physics.stretch.Law.mean`).
    """
    if decay is None:
        return LB * bound.strain(H)
    return ca.fmin(LB, H / decay) * bound.mean(HA, H)


def shared(outputs: list, law) -> list:
    """A block's outputs with common subexpressions merged when it has a stretch law (the
    law's pieces are picked at the same tension by several terms); Hooke's graph as built."""
    return outputs if law is None else ca.cse(outputs)


def law_inputs(model: Optional[StretchModel], names) -> tuple:
    """Input names and SX symbols of a block: ``names``, plus ``law`` for a line with the
    law ``model``; and the law's parameters as a list of symbols (None for Hooke)."""
    args = [ca.SX.sym(n) for n in names]
    if model is None:
        return list(names), args, None
    law = ca.SX.sym("law", model.n_params)
    return list(names) + ["law"], args + [law], ca.vertsplit(law)


def law_tag(elastic: bool, model: Optional[StretchModel]) -> str:
    """The part of a block function's name that says how it stretches."""
    return ("elastic" if elastic else "inextensible") + (
        f"_{model.tag}" if elastic and model is not None else "")
