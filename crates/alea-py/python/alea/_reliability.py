"""SORM as a function of its own: ``alea.sorm(model, law, ...)`` is ``alea.form(model, law,
second_order=True, ...)`` (one binding in ``alea._core`` serves both)."""

from __future__ import annotations

from typing import Any

from . import _core


def sorm(model: Any, law: Any, **options: Any) -> _core.ReliabilityResult:
    """SORM: second order at the FORM design point.

    ``pf`` is Breitung's formula ``Phi(-beta) prod_i (1 + beta kappa_i)^-1/2``; ``pf_tvedt`` is
    Tvedt's three-term formula and ``curvatures`` the principal curvatures of the limit state
    there. ``model``, ``law`` and the keyword options (``threshold``, ``starts``, ``tol``,
    ``max_iter``, ``step``) are those of :func:`alea.form`; so are the result and the errors,
    plus a ``ValueError`` when a curvature makes ``1 + beta kappa <= 0``. It costs FORM's calls
    and ``2 d^2 + 1`` more for the Hessian at the best design point.
    """
    return _core.form(model, law, second_order=True, **options)
