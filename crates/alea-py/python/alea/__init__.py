"""alea: uncertainty quantification for elastic assemblies with frictional contact.

A thin Python layer over the Rust library (the extension module ``alea._core``): every number
is computed by the Rust crates ``alea-uq`` and ``alea-study``; this package only arranges them
as NumPy arrays and pandas DataFrames.

Studies
    ``run(study_file)`` runs (or resumes) a study file and returns a :class:`StudyResult`
    (``.runs``, ``.statistics``, ``.failure``, ``.samples``, the error budget ``.budget`` and
    its ``.budget_bases``, ``.reliability_table``, the random fields ``.fields`` /
    ``.field_modes`` and the Sobol' indices per parameter and KL mode ``.sensitivity``); ``open_store(directory)`` reads
    the runs of a study directory without running anything; ``report(directory)`` writes its
    outputs (``summary.json``, ``samples.csv``, fields, the HTML report) as ``alea report``.
    A toolkit-only build (cargo ``--no-default-features``: no solver, ``SOLVER`` false) raises
    :class:`SolverNotBuilt` from these three; everything below works in both builds.
Laws
    ``Normal``, ``Uniform``, ``TruncatedNormal``, ``Lognormal``, ``Beta``, ``Gamma``,
    ``Triangular``, ``Empirical``, ``Kde`` (all subclasses of ``Law``: ``pdf``, ``cdf``,
    ``sf``, ``quantile``, ``sample``, ``mean``, ``std``); ``fit(data)``; ``Joint`` (independent
    or Gaussian copula; ``Joint.student``, ``.clayton``, ``.gumbel``, ``.frank``).
Designs
    ``monte_carlo``, ``lhs``, ``sobol``, ``grid``, ``pc_collocation``, ``quadrature``: arrays
    of shape ``(n, d)``.
Surrogates
    ``PolynomialChaos.regression / .projection / .lars / .load`` and ``PiecewiseLinear``:
    ``predict(points)``, ``weights(points)``, ``mean``, ``variance``, Sobol' indices, corrected
    leave-one-out error.

Random fields
    ``KarhunenLoeve(nodes, cells, kernel, variance, length, variance_fraction=... | modes=...)``:
    Galerkin Karhunen-Loeve expansion on a P1 mesh (segments or triangles); ``eigenvalues``,
    ``modes``, ``realise(xi, mean, transform="gaussian" | "lognormal" | "bounded")``.

Rare events
    ``form``, ``sorm``, ``importance_sampling``, ``subset_simulation``: ``P(g(X) <= 0)``, or
    ``P(q(X) > threshold)``, for a Python callable (vectorised: an ``(n, d)`` array of points in,
    ``n`` values out) or a fitted ``PolynomialChaos`` / ``PiecewiseLinear`` (evaluated in Rust,
    no Python calls); a :class:`ReliabilityResult` with ``pf``, ``interval``, ``cov``, ``beta``,
    the design point(s), ``calls`` and ``warnings``.

Wherever a law is expected, a ``Joint``, a single ``Law`` or a list of ``Law`` objects
(independent variables) may be given. Random routines take a ``seed`` and give the same result
whatever the number of threads.
"""

from ._core import (
    Beta,
    Empirical,
    Gamma,
    Joint,
    KarhunenLoeve,
    Kde,
    Law,
    Lognormal,
    Normal,
    PiecewiseLinear,
    PolynomialChaos,
    ReliabilityResult,
    SOLVER,
    Triangular,
    TruncatedNormal,
    Uniform,
    __version__,
    fit,
    form,
    grid,
    importance_sampling,
    lhs,
    monte_carlo,
    pc_collocation,
    quadrature,
    sobol,
    subset_simulation,
)
from ._study import (
    SolverNotBuilt,
    StoredRuns,
    StudyLocked,
    StudyOutputs,
    StudyResult,
    open_store,
    report,
    run,
)
from ._reliability import sorm
from ._tables import RandomField

__all__ = [
    "Beta",
    "Empirical",
    "Gamma",
    "Joint",
    "KarhunenLoeve",
    "Kde",
    "Law",
    "Lognormal",
    "Normal",
    "PiecewiseLinear",
    "PolynomialChaos",
    "RandomField",
    "ReliabilityResult",
    "SOLVER",
    "SolverNotBuilt",
    "StoredRuns",
    "StudyLocked",
    "StudyOutputs",
    "StudyResult",
    "Triangular",
    "TruncatedNormal",
    "Uniform",
    "__version__",
    "fit",
    "form",
    "grid",
    "importance_sampling",
    "lhs",
    "monte_carlo",
    "open_store",
    "pc_collocation",
    "quadrature",
    "report",
    "run",
    "sobol",
    "sorm",
    "subset_simulation",
]
