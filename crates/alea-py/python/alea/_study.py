"""Study results as pandas DataFrames and NumPy arrays.

The numbers come from ``alea._core.run_study_file`` / ``read_store`` / ``rebuild_outputs`` (the
study orchestration of the Rust crate ``alea-pipeline``, the same the ``alea`` command line
calls); this module only names and arranges them.
"""

from __future__ import annotations

import json
import os
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, List, Optional, Sequence, TextIO, Tuple, Union

import numpy as np
import pandas as pd

from . import _core
from ._tables import RandomField, _field_modes, _parameter_table, _reliability_table

PathLike = Union[str, "os.PathLike[str]"]


def _runs_frame(raw_runs: dict, parameters: Sequence[str], quantities: Sequence[str]) -> pd.DataFrame:
    """One row per run: parameters, status, converged, iterations, residual, seconds, quantities."""
    data = {}
    for j, name in enumerate(parameters):
        data[name] = raw_runs["params"][:, j]
    data["status"] = raw_runs["status"]
    data["converged"] = np.array([s == "converged" for s in raw_runs["status"]], dtype=bool)
    data["iterations"] = raw_runs["iterations"]
    data["residual"] = raw_runs["residual"]
    data["seconds"] = raw_runs["seconds"]
    for q, name in enumerate(quantities):
        data[name] = raw_runs["qois"][:, q]
    return pd.DataFrame(data)


@dataclass(frozen=True)
class Method:
    """One method of a study (design + surrogate, or Monte Carlo on the model).

    ``error`` says why the method gave no statistics, if it did not; ``left_out`` lists the
    runs it could not use (parameter point, status).
    """

    label: str
    description: str
    design_runs: int
    runs_used: int
    draws: int
    error: Optional[str]
    left_out: List[Tuple[List[float], str]]


class StudyResult:
    """The results of :func:`run`.

    Attributes
    ----------
    runs : pandas.DataFrame
        One row per distinct run: the parameters (one column each), ``status``, ``converged``,
        ``iterations`` (LATIN), ``residual`` (final error indicator), ``seconds`` and the
        quantities of interest (one column each; NaN where a run gave none).
    statistics : pandas.DataFrame
        Indexed by ``(method, quantity)``: ``mean``, ``std``, ``skewness``, ``min``, ``max``
        (of the draws on the surrogate), ``mean_ci_half_width`` (half width of the confidence
        interval of the mean from the draws alone: sampling only), quantiles ``q0.01`` ...
        ``q0.99``, ``kde_bandwidth``, ``draws`` and ``runs_used``; and what to read of the
        mean and the std, from their error budget (NaN without one): ``mean_estimate`` (the
        mean corrected by the validation runs where there are some, else ``mean``),
        ``mean_low``, ``mean_high`` (its total interval: every estimated part of the budget),
        ``std_estimate``, ``std_low``, ``std_high``. Methods that gave no statistics have no
        rows (see ``methods``).
    failure : pandas.DataFrame
        ``P(quantity > threshold)`` for every threshold of the study: columns ``method``,
        ``quantity``, ``threshold``, ``probability`` (on the draws), ``estimate`` (corrected
        by the validation runs where there are some), ``total_low``, ``total_high`` (the total
        interval of its error budget; NaN without a budget), ``sampling_low``,
        ``sampling_high`` (the Wilson interval from the draws alone: sampling only), and
        ``ci_low``, ``ci_high`` (the same sampling-only bounds, their older names).
    budget : pandas.DataFrame
        The error budget of every statistic: columns ``method``, ``quantity``, ``statistic``
        (``mean``, ``std``, ``q0.05``, ``P(> t)``...), ``value`` and its estimated error by
        source, ``mesh``, ``surrogate``, ``sampling`` and ``sliding`` (``[budget] large_sliding``:
        the change under large sliding; NaN where not estimated or not asked for), ``total``,
        and what to read: ``estimate`` (the statistic corrected by the validation runs where
        there are some, else ``value``) with its total interval ``total_low``, ``total_high``.
        How the surrogate part was estimated: ``budget_basis[(method, quantity)]``.
    budget_bases : pandas.DataFrame
        How each budget was estimated: columns ``method``, ``quantity``, ``surrogate``,
        ``mesh`` and ``sliding`` (the basis of each part, or why it was not estimated; None
        when the sliding part was not asked for), ``draws`` (Monte
        Carlo draws behind the statistics) and the surrogate's residuals at the validation
        runs, ``validation_runs``, ``validation_rms`` and ``validation_relative`` (their RMS
        over the quantity's RMS, the quantity's analogue of ``i_sto``; None without them).
    reliability : list of dict
        The ``[[reliability]]`` analyses of the study file (as in ``summary.json``): the FORM
        design points, SORM, importance sampling and subset simulation with their intervals and
        evaluation counts, warnings and errors.
    reliability_table : pandas.DataFrame
        The same, one row per analysis and algorithm: ``quantity``, ``threshold``, ``method``
        (whose surrogate), ``algorithm`` (``FORM``, ``SORM``, ``importance sampling``,
        ``subset simulation``, ``solver`` for the confirmation by runs of the solver), ``pf``,
        ``ci_low``, ``ci_high`` (NaN for FORM and SORM), ``cov``, ``evaluations`` (surrogate
        evaluations, or solver runs) and ``beta`` (FORM's reliability index).
    parameter_table : pandas.DataFrame
        Indexed by parameter: ``law`` (its description, as in ``summary.json``), ``unit``,
        ``lo``, ``hi`` (the box of the surrogates), ``nominal``, and for the Karhunen-Loeve
        variables of a random field its ``field`` and ``mode`` (1-based; None / 0 otherwise).
    fields : list of RandomField
        The study's ``[[field]]`` tables: Karhunen-Loeve eigenvalues, captured variance
        fraction, mode shapes at the nodes, and the parameters that are its KL variables.
    field_modes : pandas.DataFrame
        One row per KL mode: ``field``, ``mode``, ``variable`` (the parameter), ``eigenvalue``,
        ``variance_share`` (``lambda_k`` over the field's total variance) and
        ``cumulative_share``.
    sensitivity : pandas.DataFrame
        Sobol' indices of every parameter (studies with random fields, as ``summary.json``),
        indexed by ``(method, quantity, parameter)``: ``first``, ``total``, their standard
        errors ``first_se``, ``total_se`` (pick-freeze estimators; NaN for a chaos, whose
        indices are exact), ``estimator``, and ``field`` / ``mode`` for KL variables: the
        Sobol' indices per KL mode.
    field_sensitivity : pandas.DataFrame
        Per random field (chaos methods): ``method``, ``quantity``, ``field``, ``closed`` (the
        share of variance of its KL variables alone) and ``total``.
    samples : numpy.ndarray
        The main method's Monte Carlo draws, ``(draws, d + m)``: the parameter point of each
        draw then the quantities' values there (columns named by ``sample_columns``). The main
        method is the first one with statistics (the study's answer).
    methods : list of Method
    parameters, quantities : list of str
    units : dict
        Unit of each parameter and quantity.
    computed, resumed : int
        Runs solved by this call, and runs found already finished in the study directory.
    """

    def __init__(self, raw: dict):
        self._raw = raw
        self.title: str = raw["title"]
        self.study_file: str = raw["study_file"]
        self.study_hash: str = raw["study_hash"]
        self.directory = Path(raw["directory"])
        self.seed: int = raw["seed"]
        self.parameters: List[str] = list(raw["parameters"])
        self.quantities: List[str] = list(raw["quantities"])
        self.units = dict(zip(self.parameters, raw["parameter_units"]))
        self.units.update(zip(self.quantities, raw["quantity_units"]))
        self.computed: int = raw["computed"]
        self.resumed: int = raw["resumed"]
        self.runs = _runs_frame(raw["runs"], self.parameters, self.quantities)
        self.methods = [
            Method(
                label=m["label"],
                description=m["description"],
                design_runs=m["design_runs"],
                runs_used=m["runs_used"],
                draws=m["draws"],
                error=m["error"],
                left_out=[(list(p), s) for p, s in m["left_out"]],
            )
            for m in raw["methods"]
        ]
        self.statistics = self._statistics()
        self.failure = self._failure()
        self.budget, self.budget_basis = self._budget()
        self.budget_bases = self._budget_bases()
        self.reliability: List[dict] = json.loads(raw.get("reliability_json", "[]"))
        self.reliability_table = _reliability_table(self.reliability)
        self.fields = [RandomField.of(f, self.parameters) for f in raw.get("fields", [])]
        self.parameter_table = _parameter_table(raw, self.fields)
        self.field_modes = _field_modes(self.fields)
        self.sensitivity, self.field_sensitivity = self._sensitivity()
        main = next((m for m in raw["methods"] if m["statistics"]), None)
        self.main_method: Optional[str] = main["label"] if main is not None else None
        if main is None:
            self.samples = np.empty((0, len(self.parameters) + len(self.quantities)))
            self.sample_columns = self.parameters + self.quantities
        else:
            self.samples, self.sample_columns = self._samples(main)

    def _statistics(self) -> pd.DataFrame:
        rows = []
        for m in self._raw["methods"]:
            for s in m["statistics"]:
                row = {
                    "method": m["label"],
                    "quantity": s["quantity"],
                    "mean": s["mean"],
                    "std": s["std"],
                    "skewness": s["skewness"],
                    "min": s["min"],
                    "max": s["max"],
                    "mean_ci_half_width": s["mean_ci_half_width"],
                }
                for p, v in s["quantiles"]:
                    row[f"q{p:g}"] = v
                row["kde_bandwidth"] = s["bandwidth"]
                row["draws"] = m["draws"]
                row["runs_used"] = m["runs_used"]
                read = {b[0]: b[7:10] for b in s["budget"]}
                nan = float("nan")
                for stat in ("mean", "std"):
                    estimate, low, high = read.get(stat, (nan, nan, nan))
                    row[f"{stat}_estimate"] = estimate
                    row[f"{stat}_low"] = low
                    row[f"{stat}_high"] = high
                rows.append(row)
        if not rows:
            return pd.DataFrame(columns=["method", "quantity"]).set_index(["method", "quantity"])
        return pd.DataFrame(rows).set_index(["method", "quantity"])

    def _budget(self) -> Tuple[pd.DataFrame, dict]:
        rows, basis = [], {}
        nan = float("nan")
        for m in self._raw["methods"]:
            for s in m["statistics"]:
                if "surrogate_basis" in s:
                    basis[(m["label"], s["quantity"])] = s["surrogate_basis"]
                for (stat, value, mesh, surrogate, sampling, sliding, total, estimate, low, high) in s["budget"]:
                    rows.append(
                        {
                            "method": m["label"],
                            "quantity": s["quantity"],
                            "statistic": stat,
                            "value": value,
                            "mesh": nan if mesh is None else mesh,
                            "surrogate": nan if surrogate is None else surrogate,
                            "sampling": sampling,
                            "sliding": nan if sliding is None else sliding,
                            "total": total,
                            "estimate": estimate,
                            "total_low": low,
                            "total_high": high,
                        }
                    )
        columns = [
            "method", "quantity", "statistic", "value", "mesh", "surrogate", "sampling", "sliding", "total",
            "estimate", "total_low", "total_high",
        ]
        return pd.DataFrame(rows, columns=columns), basis

    def _budget_bases(self) -> pd.DataFrame:
        rows = [
            {
                "method": m["label"],
                "quantity": s["quantity"],
                "surrogate": s["surrogate_basis"],
                "mesh": s.get("mesh_basis"),
                "sliding": s.get("sliding_basis"),
                "draws": s.get("budget_draws"),
                # The surrogate's residuals at the validation runs (None without them).
                "validation_runs": (s.get("validation_errors") or {}).get("runs"),
                "validation_rms": (s.get("validation_errors") or {}).get("rms"),
                "validation_relative": (s.get("validation_errors") or {}).get("relative"),
            }
            for m in self._raw["methods"]
            for s in m["statistics"]
            if "surrogate_basis" in s
        ]
        return pd.DataFrame(
            rows,
            columns=[
                "method", "quantity", "surrogate", "mesh", "sliding", "draws",
                "validation_runs", "validation_rms", "validation_relative",
            ],
        )

    def _sensitivity(self) -> Tuple[pd.DataFrame, pd.DataFrame]:
        of_variable = {}
        for f in self.fields:
            for k, v in enumerate(f.variables):
                of_variable[v] = (f.name, k + 1)
        rows, field_rows = [], []
        nan = float("nan")
        for m in self._raw["methods"]:
            for s in m["statistics"]:
                text = s.get("sobol_json")
                if not text:
                    continue
                sob = json.loads(text)
                first_se = sob.get("first_se") or [nan] * len(self.parameters)
                total_se = sob.get("total_se") or [nan] * len(self.parameters)
                for j, name in enumerate(self.parameters):
                    field, mode = of_variable.get(name, (None, 0))
                    rows.append(
                        {
                            "method": m["label"],
                            "quantity": s["quantity"],
                            "parameter": name,
                            "first": sob["first"][j],
                            "total": sob["total"][j],
                            "first_se": first_se[j],
                            "total_se": total_se[j],
                            "estimator": sob["estimator"],
                            "field": field,
                            "mode": mode,
                        }
                    )
                for f in sob.get("fields", []):
                    field_rows.append(
                        {
                            "method": m["label"],
                            "quantity": s["quantity"],
                            "field": f["field"],
                            "closed": f["closed"],
                            "total": f["total"],
                        }
                    )
        columns = ["method", "quantity", "parameter", "first", "total", "first_se", "total_se", "estimator", "field", "mode"]
        sens = pd.DataFrame(rows, columns=columns).set_index(["method", "quantity", "parameter"])
        fields = pd.DataFrame(field_rows, columns=["method", "quantity", "field", "closed", "total"])
        return sens, fields

    def _failure(self) -> pd.DataFrame:
        nan = float("nan")
        rows = [
            {
                "method": m["label"],
                "quantity": s["quantity"],
                "threshold": t,
                "probability": p,
                "estimate": p if estimate is None else estimate,
                "total_low": nan if low is None else low,
                "total_high": nan if high is None else high,
                "sampling_low": lo,
                "sampling_high": hi,
                "ci_low": lo,
                "ci_high": hi,
            }
            for m in self._raw["methods"]
            for s in m["statistics"]
            for (t, p, lo, hi, estimate, low, high) in s["failure"]
        ]
        columns = [
            "method", "quantity", "threshold", "probability", "estimate", "total_low", "total_high",
            "sampling_low", "sampling_high", "ci_low", "ci_high",
        ]
        return pd.DataFrame(rows, columns=columns)

    def _samples(self, m: dict) -> Tuple[np.ndarray, List[str]]:
        values = m["samples"]
        if m["points"] is None:
            return values, list(self.quantities)
        return np.hstack([m["points"], values]), self.parameters + self.quantities

    def _method(self, method: Union[None, int, str]) -> dict:
        methods = self._raw["methods"]
        if method is None:
            method = self.main_method
        if isinstance(method, int):
            return methods[method]
        for m in methods:
            if m["label"] == method:
                return m
        raise KeyError(f"no method {method!r}; methods: {[m['label'] for m in methods]}")

    def samples_of(self, method: Union[int, str]) -> np.ndarray:
        """Draws of a method (by label or index), an array like :attr:`samples`: the parameter
        point of each draw then the quantities' values there (columns named by
        :meth:`sample_columns_of`)."""
        return self._method_samples(method)[0]

    def sample_columns_of(self, method: Union[int, str]) -> List[str]:
        """The column names of :meth:`samples_of` ``(method)``: parameters then quantities, or
        the quantities alone when the method's draws carry no parameter points."""
        return self._method_samples(method)[1]

    def _method_samples(self, method: Union[int, str]) -> Tuple[np.ndarray, List[str]]:
        m = self._method(method)
        if m["samples"] is None:
            raise ValueError(f"method {m['label']!r} gave no statistics: {m['error']}")
        return self._samples(m)

    def kde(self, quantity: str, method: Union[None, int, str] = None) -> Tuple[np.ndarray, np.ndarray]:
        """Kernel density estimate of a quantity's PDF under a method (default: the main one):
        ``(x, pdf)`` arrays."""
        m = self._method(method)
        for s in m["statistics"]:
            if s["quantity"] == quantity:
                return s["kde_x"], s["kde_pdf"]
        raise KeyError(f"no statistics of {quantity!r} for method {m['label']!r}")

    def __repr__(self) -> str:
        return (
            f"StudyResult({self.title!r}: {len(self.runs)} runs ({self.computed} computed, "
            f"{self.resumed} resumed), methods {[m.label for m in self.methods]}, "
            f"directory {str(self.directory)!r})"
        )


class StoredRuns:
    """The runs found in a study directory by :func:`open_store`.

    Attributes
    ----------
    runs : pandas.DataFrame
        As :attr:`StudyResult.runs`, in the order the runs finished.
    parameters, quantities : list of str
        From the study file if given, else from the directory's ``summary.json`` (written by
        ``alea run``) when it belongs to the same study version, else ``x1, x2, ...`` and
        ``q1, q2, ...``.
    study_hash : str
        Hash of the study file's text the store belongs to.
    """

    def __init__(self, raw: dict):
        self.directory = Path(raw["directory"])
        self.study_hash: str = raw["study_hash"]
        d = raw["runs"]["params"].shape[1]
        m = raw["runs"]["qois"].shape[1]
        if "parameters" in raw:
            self.parameters = list(raw["parameters"])
            self.quantities = list(raw["quantities"])
        else:
            self.parameters, self.quantities = _names_from_summary(self.directory, self.study_hash, d, m)
        self.runs = _runs_frame(raw["runs"], self.parameters, self.quantities)

    def __repr__(self) -> str:
        return f"StoredRuns({str(self.directory)!r}: {len(self.runs)} runs)"


def _names_from_summary(directory: Path, study_hash: str, d: int, m: int) -> Tuple[List[str], List[str]]:
    fallback = ([f"x{j + 1}" for j in range(d)], [f"q{q + 1}" for q in range(m)])
    try:
        summary = json.loads((directory / "summary.json").read_text())
    except (OSError, ValueError):
        return fallback
    if summary.get("study_hash") != study_hash:
        return fallback
    params = [p.get("name") for p in summary.get("parameters", [])]
    quantities = []
    for method in summary.get("methods", []):
        if method.get("qois"):
            quantities = [q.get("name") for q in method["qois"]]
            break
    if len(params) != d or len(quantities) != m or not all(params) or not all(quantities):
        return fallback
    return params, quantities


class SolverNotBuilt(RuntimeError):
    """A study function (:func:`run`, :func:`open_store`, :func:`report`) was called on a
    toolkit-only build of alea (built without the cargo feature ``solver``)."""


class StudyLocked(ValueError):
    """The study directory is in use by another process (another :func:`run`, or ``alea run``:
    the command line's exit code 5). Wait for it to finish, stop it, or pass another
    ``directory=``.

    Attributes
    ----------
    directory : Path
        The study directory.
    holder : str
        Who holds its lock (process id, host, start time and command), as the message says.
    """

    def __init__(self, message: str, directory: PathLike, holder: str):
        super().__init__(message)
        self.directory = Path(directory)
        self.holder = holder


class _ProgressLine:
    """The default progress display of :func:`run`: one line on a stream (stderr), rewritten
    in place at most five times a second, as ``alea: 37/200 runs (18 %), 12 s, about 54 s
    left``; :meth:`close` ends the line."""

    def __init__(self, stream: TextIO, every: float = 0.2):
        self._stream = stream
        self._every = every
        self._start = time.monotonic()
        self._last = float("-inf")
        self._first_done: Optional[int] = None
        self._shown = False

    def __call__(self, done: int, total: int) -> None:
        now = time.monotonic()
        if self._first_done is None:
            self._first_done = done
        if done < total and now - self._last < self._every:
            return
        self._last = now
        self._stream.write("\r" + self.line(done, total, now - self._start))
        self._stream.flush()
        self._shown = True

    def line(self, done: int, total: int, elapsed: float) -> str:
        """The text shown after ``done`` of ``total`` runs and ``elapsed`` seconds."""
        percent = 100 * done // total if total else 100
        text = f"alea: {done}/{total} runs ({percent} %), {elapsed:.0f} s"
        computed = done - (self._first_done or 0)
        if 0 < computed and done < total and elapsed > 0:
            text += f", about {(total - done) * elapsed / computed:.0f} s left"
        return text + "   "

    def close(self) -> None:
        if self._shown:
            self._stream.write("\n")
            self._stream.flush()


def _interactive() -> bool:
    """Whether someone watches: stderr is a terminal, or the code runs in a Jupyter kernel."""
    try:
        if sys.stderr is not None and sys.stderr.isatty():
            return True
    except (AttributeError, ValueError):
        pass
    return "ipykernel" in sys.modules


def _progress_callback(progress: Union[None, bool, Callable[[int, int], None]]):
    """The callback :func:`run` hands to the study, and the display to close after it."""
    if progress is None:
        progress = _interactive()
    if progress is True:
        line = _ProgressLine(sys.stderr)
        return line, line
    if progress is False:
        return None, None
    if not callable(progress):
        raise TypeError(f"progress must be None, True, False or a callable, got {progress!r}")
    return progress, None


def _require_solver(function: str) -> None:
    if not _core.SOLVER:
        raise SolverNotBuilt(
            f"alea.{function} needs the solver (finite elements, LATIN, study store), which this "
            "build of alea leaves out: it was built with --no-default-features (the UQ toolkit "
            "only: laws, designs, surrogates, random fields). Install the full package, e.g. "
            "`pip install <alea source>/crates/alea-py` or `maturin develop --release` "
            "(default features)"
        )


def run(
    study: PathLike,
    directory: Optional[PathLike] = None,
    restart: bool = False,
    threads: Optional[int] = None,
    progress: Union[None, bool, Callable[[int, int], None]] = None,
) -> StudyResult:
    """Run (or resume) a study file and analyse every method, as ``alea run`` does.

    Parameters
    ----------
    study : path
        The study file (TOML; see docs/study-file.md).
    directory : path, optional
        The study directory holding the crash-safe store (default ``out/<file stem>``, as the
        command line). Runs already there are not run again, so calling ``run`` on a finished
        study only re-reads and re-analyses it.
    restart : bool
        Discard the runs in ``directory`` (needed when the study file changed).
    threads : int, optional
        Number of worker threads (default: all cores). Results do not depend on it.
    progress : bool or callable, optional
        ``True``: a progress line on stderr (runs done of the total, elapsed time, time left);
        ``False``: none; a callable: called as ``progress(done, total)`` at the start and after
        each finished run (from a worker thread; an exception it raises stops the study and is
        raised by ``run``). Default (None): the progress line when someone watches (stderr is a
        terminal, or in Jupyter), none otherwise.

    Returns
    -------
    StudyResult

    Raises
    ------
    ValueError
        A bad study file (the message names the file, line and field) or a failed computation.
    StudyLocked
        Another process works in ``directory`` (a ``ValueError``; the message names it).
    OSError
        The study file or directory cannot be read or written.
    KeyboardInterrupt
        Ctrl-C: no further run starts, the runs under way finish (a second or so) and every
        finished run is in the store; the next call on the same directory resumes from them.

    Writes only the store (``study.db``, with every run's fields); ``alea run`` also writes
    ``summary.json``, ``samples.csv``, mean fields and the HTML report, and :func:`report`
    writes them from the store afterwards.

    The solves run without the interpreter lock. Every finished run is committed to the store
    at once, so even killing the process (or restarting a notebook kernel) loses nothing and
    the next call resumes.
    """
    _require_solver("run")
    study = Path(study)
    if directory is None:
        directory = Path("out") / study.stem
    callback, display = _progress_callback(progress)
    try:
        raw = _core.run_study_file(str(study), str(directory), restart, threads, callback)
    finally:
        if display is not None:
            display.close()
    return StudyResult(raw)


def open_store(directory: PathLike, study: Optional[PathLike] = None) -> StoredRuns:
    """Read the runs stored in a study directory, without running or recomputing anything.

    With ``study`` (the study file), the store must belong to that version of the file and the
    columns are named from it. To get the statistics of a finished study, call :func:`run` on
    it: every run is found in the store and none is solved again.

    Raises
    ------
    FileNotFoundError
        ``directory`` holds no study store.
    ValueError
        The store belongs to another version of ``study``.
    """
    _require_solver("open_store")
    raw = _core.read_store(str(directory), None if study is None else str(study))
    return StoredRuns(raw)


@dataclass
class StudyOutputs:
    """The files :func:`report` wrote into a study directory, and the warnings they carry.

    Attributes
    ----------
    report : Path or None
        ``report/report.html``, the self-contained HTML report.
    plots : list of Path
        Its plots (PNG and SVG, in ``report/``).
    summary : Path
        ``summary.json``: everything the study found, for programs.
    samples : Path or None
        ``samples.csv``: the main method's draws (unless the study file switches it off).
    fields, error_fields : Path or None
        ParaView files of the mean / std fields and of the mean error densities, when written.
    notes : list of str
        The warnings (as in ``summary.json`` and at the top of the report).
    """

    report: Optional[Path]
    plots: List[Path]
    summary: Path
    samples: Optional[Path]
    fields: Optional[Path]
    error_fields: Optional[Path]
    notes: List[str]


def report(directory: PathLike) -> StudyOutputs:
    """Rebuild every output of a study directory from its store, as ``alea report DIR`` does.

    Writes the statistics and error estimates into ``summary.json``, the main method's draws
    into ``samples.csv``, the mean / std fields and the HTML report (``report/report.html``
    with its plots), computing no run: for a study run by :func:`run` (which writes only the
    store), or one the command line ran with ``report = false`` or stopped before its outputs.
    Runs missing from the store (a study stopped early) are left out, with a note. Nor does it
    solve the error budget's paired solves (``[budget] refined_mesh``, ``large_sliding``):
    :func:`run` stores them; without them the part is "not estimated", with a note. The output
    files are the command line's, byte for byte.

    Returns
    -------
    StudyOutputs
        The files written and the warnings.

    Raises
    ------
    ValueError
        ``directory`` is not a study directory, its mesh file changed, or no run converged / no
        method produced statistics (the outputs are written first); :class:`StudyLocked` (a
        ``ValueError``) when another process works in it.
    OSError
        A file cannot be read or written.
    """
    _require_solver("report")
    raw = _core.rebuild_outputs(str(directory))

    def path(p: Optional[str]) -> Optional[Path]:
        return None if p is None else Path(p)

    return StudyOutputs(
        report=path(raw["report"]),
        plots=[Path(p) for p in raw["plots"]],
        summary=Path(raw["summary"]),
        samples=path(raw["samples"]),
        fields=path(raw["fields"]),
        error_fields=path(raw["error_fields"]),
        notes=list(raw["notes"]),
    )
