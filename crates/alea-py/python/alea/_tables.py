"""Tables of a study's results that ``summary.json`` holds beyond the statistics: the random
fields (``[[field]]``: Karhunen-Loeve eigenvalues, captured variance, modes), the parameters'
laws, and the ``[[reliability]]`` results one row per algorithm. Every number is alea-study's
(through ``alea._core``); this module only arranges them."""

from __future__ import annotations

from dataclasses import dataclass
from typing import List, Sequence

import numpy as np
import pandas as pd


@dataclass(frozen=True)
class RandomField:
    """A ``[[field]]`` of a study: its Karhunen-Loeve discretisation (Galerkin on the facets of
    its interface's side 1, or on the corners of its substructure's cells).

    Attributes
    ----------
    name, unit, description, transform : str
    interface : str
        Its interface ("" for a field over a substructure's cells).
    substructure : str
        Its substructure ("" for a field along an interface).
    variables : list of str
        The study parameters that are its KL variables ``<name>_1 ... <name>_m`` (standard
        normal).
    eigenvalues : numpy.ndarray
        ``lambda_1 >= ... >= lambda_m`` of the kept modes (of the underlying Gaussian field).
    captured_fraction : float
        ``sum_k lambda_k`` over the field's total variance ``sigma^2 |D|``.
    total_variance : float
        ``sigma^2 |D|``.
    nodes : numpy.ndarray
        ``(n, 3)`` node coordinates of its mesh.
    cells : numpy.ndarray
        Its cells by node index: ``(c, 2)`` segments (along a 2D interface) or ``(c, 3)``
        triangles (along a 3D interface, or over a 2D substructure's cells).
    modes : numpy.ndarray
        ``(m, n)``: mode ``k`` at the nodes in row ``k`` (L2-normalised on the mesh), as
        :attr:`KarhunenLoeve.modes`.
    """

    name: str
    interface: str
    substructure: str
    unit: str
    description: str
    transform: str
    variables: List[str]
    eigenvalues: np.ndarray
    captured_fraction: float
    total_variance: float
    nodes: np.ndarray
    cells: np.ndarray
    modes: np.ndarray

    @staticmethod
    def of(raw: dict, parameters: Sequence[str]) -> "RandomField":
        m = len(raw["eigenvalues"])
        first = raw["first_variable"]
        return RandomField(
            name=raw["name"],
            interface=raw["interface"],
            substructure=raw["substructure"],
            unit=raw["unit"],
            description=raw["description"],
            transform=raw["transform"],
            variables=list(parameters[first : first + m]),
            eigenvalues=raw["eigenvalues"],
            captured_fraction=raw["captured_fraction"],
            total_variance=raw["total_variance"],
            nodes=raw["nodes"],
            cells=np.asarray(raw["cells"], dtype=np.int64),
            modes=raw["modes"],
        )


def _parameter_table(raw: dict, fields: Sequence[RandomField]) -> pd.DataFrame:
    of_variable = {v: (f.name, k + 1) for f in fields for k, v in enumerate(f.variables)}
    names = list(raw["parameters"])
    return pd.DataFrame(
        {
            "law": list(raw.get("parameter_laws", [""] * len(names))),
            "unit": list(raw["parameter_units"]),
            "lo": raw.get("parameter_lo", np.full(len(names), np.nan)),
            "hi": raw.get("parameter_hi", np.full(len(names), np.nan)),
            "nominal": raw.get("parameter_nominal", np.full(len(names), np.nan)),
            "field": [of_variable.get(n, (None, 0))[0] for n in names],
            "mode": [of_variable.get(n, (None, 0))[1] for n in names],
        },
        index=pd.Index(names, name="parameter"),
    )


def _field_modes(fields: Sequence[RandomField]) -> pd.DataFrame:
    rows = []
    for f in fields:
        cumulative = 0.0
        for k, (v, lam) in enumerate(zip(f.variables, f.eigenvalues)):
            share = float(lam) / f.total_variance
            cumulative += share
            rows.append(
                {
                    "field": f.name,
                    "mode": k + 1,
                    "variable": v,
                    "eigenvalue": float(lam),
                    "variance_share": share,
                    "cumulative_share": cumulative,
                }
            )
    columns = ["field", "mode", "variable", "eigenvalue", "variance_share", "cumulative_share"]
    return pd.DataFrame(rows, columns=columns)


def _reliability_table(reliability: Sequence[dict]) -> pd.DataFrame:
    nan = float("nan")
    rows = []
    for r in reliability:
        base = {"quantity": r["quantity"], "threshold": r["threshold"], "method": r["method"]}
        best = r["design_points"][0] if r.get("design_points") else None
        beta = best["beta"] if best else nan

        def row(algorithm, pf, lo, hi, cov, evaluations, b=beta):
            rows.append(
                {
                    **base,
                    "algorithm": algorithm,
                    "pf": pf,
                    "ci_low": lo,
                    "ci_high": hi,
                    "cov": nan if cov is None else cov,
                    "evaluations": evaluations,
                    "beta": b,
                }
            )

        if best:
            row("FORM", best["pf"], nan, nan, None, r["form_evaluations"])
        if r.get("sorm"):
            row("SORM", r["sorm"]["pf_breitung"], nan, nan, None, r["sorm"]["evaluations"])
        for key, name in (("importance", "importance sampling"), ("subset", "subset simulation")):
            e = r.get(key)
            if e:
                row(name, e["pf"], e["lower"], e["upper"], e["cov"], e["evaluations"], beta if key == "importance" else nan)
        e = r.get("solver")
        if e:
            row("solver", e["pf"], e["lower"], e["upper"], e["cov"], e["runs"], e["beta"])
    columns = ["quantity", "threshold", "method", "algorithm", "pf", "ci_low", "ci_high", "cov", "evaluations", "beta"]
    return pd.DataFrame(rows, columns=columns)
