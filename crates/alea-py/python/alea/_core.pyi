"""Type stubs of ``alea._core`` (written by ``tools/stubgen.py`` from the built module: do not
edit by hand)."""
import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt
from numpy.typing import ArrayLike

Matrix = npt.NDArray[np.float64]
Vector = npt.NDArray[np.float64]
LawLike = Union["Joint", "Law", Sequence["Law"]]

__version__: str
SOLVER: bool

class Joint:
    """
    A joint law of `d` random variables: independent marginals (`correlation=None`) or a
    Gaussian copula (Nataf) with the given correlation matrix of the normal scores. Other
    copulas: `Joint.student`, `Joint.clayton`, `Joint.gumbel`, `Joint.frank`.

    Points are `(n, d)` arrays. `to_unit` / `from_unit` are the isoprobabilistic map to
    independent uniforms on `[0, 1]^d` and back; `to_standard_normal` / `from_standard_normal`
    map to independent standard normals (the Nataf transform for the Gaussian copula).
    """
    def __init__(self, marginals: Sequence[Law], correlation: Optional[ArrayLike] = None) -> None: ...
    @property
    def bounds(self) -> Any: ...
    @staticmethod
    def clayton(marginals: Sequence[Law], theta: Any) -> Any:
        """
        Clayton copula with parameter `theta > 0` (any dimension), or `-1 < theta < 0` (negative
        dependence, two variables).
        """
        ...
    @property
    def correlation(self) -> Any: ...
    @property
    def dim(self) -> Any: ...
    @staticmethod
    def frank(marginals: Sequence[Law], theta: Any) -> Any:
        """
        Frank copula with parameter `theta != 0` (two variables).
        """
        ...
    def from_standard_normal(self, y: Any) -> Any:
        """
        Map independent standard normal points `y` to the law's space.
        """
        ...
    def from_unit(self, u: Any) -> Any:
        """
        Map unit-cube points `u` to the law's space.
        """
        ...
    @staticmethod
    def gumbel(marginals: Sequence[Law], theta: Any) -> Any:
        """
        Gumbel copula with parameter `theta >= 1` (two variables).
        """
        ...
    @property
    def kind(self) -> Any: ...
    @property
    def marginals(self) -> Any: ...
    def pdf(self, x: ArrayLike) -> Any:
        """
        Joint density at the points `x` (`(n, d)`), shape `(n,)`.
        """
        ...
    def sample(self, n: int, seed: int = 0) -> Any:
        """
        `n` independent draws, shape `(n, d)` (seeded; identical for any number of threads).
        """
        ...
    @staticmethod
    def student(marginals: Sequence[Law], correlation: ArrayLike, nu: Any) -> Any:
        """
        Student copula with correlation matrix `correlation` and `nu` degrees of freedom.
        """
        ...
    def to_standard_normal(self, x: ArrayLike) -> Any:
        """
        Map points `x` to independent standard normal variables.
        """
        ...
    def to_unit(self, x: ArrayLike) -> Any:
        """
        Map points `x` to independent uniforms on the unit cube.
        """
        ...

class KarhunenLoeve:
    """
    Karhunen-Loeve expansion of a stationary Gaussian field on a P1 mesh.

    `nodes`: `(n, d)` coordinates (`d` = 1 to 3, or a 1-D array of abscissae); `cells`: lists of
    2 node indices (segments, e.g. along a contact line), 3 (triangles) or 4 (tetrahedra); `kernel`:
    `"exponential"`, `"squared-exponential"`, `"matern32"` or `"matern52"`; `variance` (sigma^2)
    and `length` (one correlation length, or one per coordinate). Exactly one of
    `variance_fraction` (keep the fewest modes whose eigenvalues reach this fraction of
    sigma^2 |D|) and `modes` (a mode count) must be given. `integration="nodal"` interpolates the
    kernel at the nodes as OpenTURNS's `KarhunenLoeveP1Algorithm` does (default: quadrature).
    """
    def __init__(self, nodes: ArrayLike, cells: ArrayLike, kernel: str, variance: float, length: float, *, variance_fraction: Optional[float] = None, modes: Optional[int] = None, integration: str = 'quadrature') -> None: ...
    @property
    def captured_fraction(self) -> Any: ...
    @property
    def eigenvalues(self) -> Any: ...
    @property
    def modes(self) -> Any: ...
    @property
    def num_modes(self) -> Any: ...
    def realise(self, xi: ArrayLike, mean: float = 0.0, transform: str = 'gaussian', bounds: Optional[Tuple[float, float]] = None) -> Any:
        """
        The field at the nodes for KL variables `xi` (shape `(num_modes,)`, or `(s, num_modes)`
        for `s` realisations): `g = mean + sum_k sqrt(lambda_k) phi_k xi_k`, then
        `transform` `"gaussian"` (g), `"lognormal"` (exp g) or `"bounded"`
        (`lower + (upper - lower) Phi((g - mean) / sigma)`, needs `bounds=(lower, upper)`).
        """
        ...
    @property
    def total_variance(self) -> Any: ...

class Law:
    """
    A one-dimensional probability law (base class of `Normal`, `Uniform`, ...).

    Methods work elementwise on scalars and arrays of any shape: `pdf`, `cdf`, `sf`
    (`1 - cdf`, accurate in the upper tail), `quantile`. `sample(n, seed)` draws `n` values by
    inversion from seeded streams (same result for any number of threads).
    """
    def cdf(self, x: ArrayLike) -> Any:
        """
        Distribution function `P(X <= x)`.
        """
        ...
    @property
    def mean(self) -> Any: ...
    @property
    def name(self) -> Any: ...
    def pdf(self, x: ArrayLike) -> Any:
        """
        Probability density at `x` (0 outside the support).
        """
        ...
    def quantile(self, p: ArrayLike) -> Any:
        """
        Inverse distribution function at probabilities `p` in `[0, 1]`; a probability outside
        it (or NaN) is a `ValueError` naming it, not a silent NaN.
        """
        ...
    def sample(self, n: int, seed: int = 0) -> Any:
        """
        `n` independent draws (seeded: the same `seed` gives the same draws).
        """
        ...
    def sf(self, x: ArrayLike) -> Any:
        """
        Survival function `P(X > x)`.
        """
        ...
    @property
    def std(self) -> Any: ...
    @property
    def support(self) -> Any: ...
    @property
    def variance(self) -> Any: ...

class PiecewiseLinear:
    """
    Piecewise multilinear interpolation on a regular grid of the box `[lo, hi]` with `cells[j]`
    cells in direction `j` (the thesis's stochastic finite elements; 1 to 6 variables).

    The runs are the grid's nodes in the order of `PiecewiseLinear.nodes(lo, hi, cells)`
    (first direction fastest): evaluate the model there and pass the values.
    """
    def __init__(self, lo: ArrayLike, hi: ArrayLike, cells: ArrayLike, values: ArrayLike) -> None: ...
    def mean(self, law: LawLike, order: int = 4) -> Any:
        """
        `E[q~]` under `law` (supported in the box): `sum_k E[w_k] q_k`, each `E[w_k]` integrated
        with an `order`-point Gauss-Legendre rule per cell, divided by the computed mass of the
        law on the box.
        """
        ...
    @staticmethod
    def nodes(lo: ArrayLike, hi: ArrayLike, cells: ArrayLike) -> Any:
        """
        The grid's nodes (the runs), shape `(prod(cells[j] + 1), d)`, first direction fastest.
        """
        ...
    @property
    def num_runs(self) -> Any: ...
    def predict(self, points: ArrayLike) -> Any:
        """
        Interpolated values at `points` (`(n, d)`, inside the box), shape `(n,)`.
        """
        ...
    def variance(self, law: LawLike, order: int = 4) -> Any:
        """
        `Var[q~]` under `law` (supported in the box), from `E[w_k w_l]` integrated as in `mean`.
        """
        ...
    def weights(self, points: ArrayLike) -> Any:
        """
        Dense weights `w_k(x)` at `points`, shape `(n, K)` (at most `2^d` non-zero per row).
        """
        ...

class PolynomialChaos:
    """
    A polynomial chaos expansion `q~(x) = sum_a s_a Psi_a(x)` in the orthonormal polynomials of
    independent marginals, fitted to run values.

    Build it with `PolynomialChaos.regression`, `.projection` or `.lars`, or `.load` a saved
    one. Statistics come from the coefficients: `mean = s_0`, `variance = sum_{a != 0} s_a^2`,
    Sobol' indices from sums of squared coefficients.
    """
    @property
    def coefficients(self) -> Any: ...
    @property
    def condition_estimate(self) -> Any: ...
    @property
    def corrected_loo_error(self) -> Any: ...
    @property
    def dim(self) -> Any: ...
    @staticmethod
    def lars(law: LawLike, degree: int, points: ArrayLike, values: ArrayLike, q: Optional[float] = None, max_terms_fraction: float = 1.0, stop_factor: float = 2.0) -> Any:
        """
        Sparse chaos by hybrid least-angle regression (Blatman & Sudret 2011): LARS orders the
        candidate terms of the degree-`degree` basis, each prefix is scored by its corrected
        leave-one-out error and the best one is refitted by least squares.
        The path is OpenTURNS' (raw orthonormal columns, constant first): on the same points
        it keeps the same terms. `max_terms_fraction`: largest number of terms as a fraction of
        the runs (1: up to `runs - 1`); `stop_factor`: beyond 10 terms, stop once the error
        exceeds this factor times the best so far (or 0.5).
        """
        ...
    @property
    def lars_path(self) -> Any: ...
    @staticmethod
    def load(path: Union[str, os.PathLike[str]]) -> Any:
        """
        Loads a chaos saved by `save` (JSON: basis, linear map, runs).
        """
        ...
    @property
    def loo_error(self) -> Any: ...
    @property
    def mean(self) -> Any: ...
    @property
    def method(self) -> Any: ...
    @property
    def multi_indices(self) -> Any: ...
    @property
    def num_runs(self) -> Any: ...
    def predict(self, points: ArrayLike) -> Any:
        """
        Values of the expansion at `points` (`(n, d)`), shape `(n,)`.
        """
        ...
    @staticmethod
    def projection(law: LawLike, degree: int, nodes: ArrayLike, weights: Any, values: ArrayLike, q: Optional[float] = None) -> Any:
        """
        Chaos by quadrature projection, `s_a = sum_k w_k q_k Psi_a(x_k)`, on a rule with nodes
        `nodes` (`(K, d)`) and weights `weights` (`(K,)`, summing to 1; see `alea.quadrature`).
        """
        ...
    @staticmethod
    def regression(law: LawLike, degree: int, points: ArrayLike, values: ArrayLike, q: Optional[float] = None) -> Any:
        """
        Least-squares chaos on the runs `points` (`(K, d)`) with values `values` (`(K,)`): basis
        of total degree `degree` (hyperbolic with q-norm `q` if given, `0 < q <= 1`) in the
        orthonormal polynomials of the marginals of `law` (independent variables).
        """
        ...
    def save(self, path: Union[str, os.PathLike[str]]) -> Any:
        """
        Saves the chaos and its runs as JSON (every float round-trips exactly).
        """
        ...
    def sobol_first(self) -> Any:
        """
        First-order Sobol' indices, shape `(d,)`.
        """
        ...
    def sobol_index(self, variables: Sequence[int]) -> Any:
        """
        Sobol' index of exactly the group `variables` (e.g. `[0, 2]` is `S_13`); all groups sum
        to 1.
        """
        ...
    def sobol_second_order(self) -> Any:
        """
        Second-order interaction indices `S_ij`, symmetric `(d, d)` with a zero diagonal.
        """
        ...
    def sobol_total(self) -> Any:
        """
        Total Sobol' indices, shape `(d,)`.
        """
        ...
    @property
    def std(self) -> Any: ...
    @property
    def variance(self) -> Any: ...
    @property
    def warnings(self) -> Any: ...
    def weights(self, points: ArrayLike) -> Any:
        """
        Dense weights `w_k(x)` at `points` (`(n, d)`), shape `(n, K)`: `predict(x) = w @ values`
        and `w @ F` interpolates any per-run array `F` (`(K, m)`) the same way.
        """
        ...

class ReliabilityResult:
    """
    The outcome of `alea.form`, `sorm`, `importance_sampling` or `subset_simulation`.

    Attributes
    ----------
    method : str
        `"FORM"`, `"SORM"`, `"importance sampling"` or `"subset simulation"`.
    pf : float
        The failure probability: `Phi(-beta)` (FORM), Breitung's formula (SORM), the estimate
        (importance sampling, subset simulation).
    interval : tuple of float or None
        Its confidence interval at `level` (sampling methods; FORM and SORM are asymptotic
        approximations without one).
    level : float or None
        Confidence level of `interval`.
    cov : float or None
        Coefficient of variation of the estimator (sampling methods; None when no failure was
        drawn).
    beta : float or None
        FORM reliability index `|u*|` of the design point (negative when the median point
        fails); None for subset simulation, which needs no design point.
    generalised_beta : float
        `-Phi^-1(pf)` (infinite when `pf` is 0).
    design_point, design_point_u : ndarray or None
        The design point in the law's variables and in the standard normal space.
    importance_factors : ndarray or None
        `alpha_i^2` at the design point (sum 1).
    design_points, design_point_betas : ndarray
        Every distinct design point FORM found from its starts, `(k, d)` in the law's
        variables, smallest `beta` first, and their `beta`.
    curvatures : ndarray or None
        SORM's principal curvatures at the design point.
    pf_breitung, pf_tvedt : float or None
        SORM's two approximations.
    calls : int
        Evaluations of the model (every FORM start included).
    warnings : list of str
        Several design points, a target coefficient of variation not reached, no failure drawn
        (each also issued as a `RuntimeWarning`).
    """
    @property
    def beta(self) -> Optional[float]: ...
    @property
    def calls(self) -> int: ...
    @property
    def cov(self) -> Optional[float]: ...
    @property
    def curvatures(self) -> Optional[Vector]: ...
    @property
    def design_point(self) -> Optional[Vector]: ...
    @property
    def design_point_betas(self) -> Vector: ...
    @property
    def design_point_u(self) -> Optional[Vector]: ...
    @property
    def design_points(self) -> Matrix: ...
    @property
    def generalised_beta(self) -> float: ...
    @property
    def importance_factors(self) -> Optional[Vector]: ...
    @property
    def interval(self) -> Optional[Tuple[float, float]]: ...
    @property
    def level(self) -> Optional[float]: ...
    @property
    def method(self) -> str: ...
    @property
    def pf(self) -> float: ...
    @property
    def pf_breitung(self) -> Optional[float]: ...
    @property
    def pf_tvedt(self) -> Optional[float]: ...
    @property
    def warnings(self) -> List[str]: ...

class Beta(Law):
    """
    Beta law with shapes `alpha`, `beta` on `[lo, hi]`.
    """
    def __init__(self, alpha: float, beta: float, lo: ArrayLike = 0.0, hi: ArrayLike = 1.0) -> None: ...

class Empirical(Law):
    """
    Empirical law of data (linearly interpolated empirical distribution function).
    """
    def __init__(self, data: ArrayLike) -> None: ...

class Gamma(Law):
    """
    Gamma law with shape `k`, scale `theta` and location `loc`.
    """
    def __init__(self, shape: float, scale: float, loc: float = 0.0) -> None: ...

class Kde(Law):
    """
    A Gaussian kernel density estimate of data used as a law; `bandwidth` is `"isj"`
    (improved Sheather-Jones, the default), `"silverman"` or a number.
    """
    def __init__(self, data: ArrayLike, bandwidth: Optional[float] = None) -> None: ...
    @property
    def bandwidth(self) -> Any: ...

class Lognormal(Law):
    """
    Lognormal law: `ln X ~ N(mu, sigma^2)`. `Lognormal.from_mean_std(mean, std)` gives the law
    with those moments.
    """
    def __init__(self, mu: float, sigma: float) -> None: ...
    @staticmethod
    def from_mean_std(mean: float, std: float) -> Any:
        """
        The lognormal law of mean `mean` and standard deviation `std`.
        """
        ...

class Normal(Law):
    """
    Normal law `N(mean, std^2)`.
    """
    def __init__(self, mean: float = 0.0, std: float = 1.0) -> None: ...

class Triangular(Law):
    """
    Triangular law on `[lo, hi]` with mode `mode`.
    """
    def __init__(self, lo: ArrayLike, mode: float, hi: ArrayLike) -> None: ...

class TruncatedNormal(Law):
    """
    Normal law `N(mean, std^2)` truncated to `[lo, hi]` (bounds may be infinite; far tails are
    handled in log space).
    """
    def __init__(self, mean: float, std: float, lo: ArrayLike, hi: ArrayLike) -> None: ...

class Uniform(Law):
    """
    Uniform law on `[lo, hi]`.
    """
    def __init__(self, lo: ArrayLike, hi: ArrayLike) -> None: ...

def fit(data: ArrayLike, families: Optional[Sequence[str]] = None) -> Any:
    """
    Fits the usual families to `data` by maximum likelihood and ranks them by BIC (best first).

    `families`: names among `"normal"`, `"lognormal"`, `"uniform"`, `"gamma"` and
    `("beta", lo, hi)` (beta on given bounds); default: the first four. Returns a list of dicts
    with `law` (a `Law`), `family`, `parameters`, `log_likelihood`, `aic`, `bic`, `ks`
    (Kolmogorov-Smirnov statistic), `ks_pvalue` (conservative with estimated parameters) and
    `anderson_darling`.
    """
    ...

def form(model: Union[Callable[[Matrix], ArrayLike], "PolynomialChaos", "PiecewiseLinear"], law: LawLike, *, threshold: Optional[float] = None, starts: Optional[ArrayLike] = None, tol: float = 1e-06, max_iter: int = 100, step: float = 0.0001, second_order: bool = False) -> ReliabilityResult:
    """
    FORM: the first-order reliability method, `pf ~ Phi(-beta)` at the design point; with
    `second_order`, SORM there (`alea.sorm`).

    Parameters
    ----------
    model : callable, PolynomialChaos or PiecewiseLinear
        A callable takes an `(n, d)` NumPy array of points and returns `n` values (e.g.
        `lambda x: 3.0 - x[:, 0] - x[:, 1]`); at present it is called with one point at a time
        (`n = 1`). A surrogate is evaluated in Rust, without Python calls.
    law : Joint, Law or list of Law
        The law of the `d` variables (a PiecewiseLinear needs a law supported in its box).
    threshold : float, optional
        Without it, failure is `model(x) <= 0`; with it, `model(x) > threshold`.
    starts : array (k, d), optional
        FORM starting points in the standard normal space (default: the median point and `+-3`
        along every axis).
    tol, max_iter, step
        HL-RF tolerance, iteration limit and finite-difference step (standard normal space).
    second_order : bool
        SORM at the best design point: `pf` is then Breitung's formula
        `Phi(-beta) prod_i (1 + beta kappa_i)^-1/2`, with `pf_tvedt` Tvedt's three-term one and
        the principal `curvatures`, from the Hessian at the best design point (`2 d^2 + 1`
        more calls).

    Returns
    -------
    ReliabilityResult
        `pf`, `beta`, the design point, importance factors, every distinct design point, calls
        and warnings (no interval: FORM and SORM are asymptotic approximations).

    Raises
    ------
    ValueError
        A bad argument, a model value that is not finite, no FORM start converging, or (SORM)
        a curvature with `1 + beta kappa <= 0`. Any exception the callable raises propagates
        unchanged.
    """
    ...

def grid(lo: ArrayLike, hi: ArrayLike, counts: Sequence[int]) -> Matrix:
    """
    Tensor grid on the box `[lo, hi]` with `counts[j]` equispaced nodes in direction `j`
    (bounds included; one node is the centre); the last direction varies fastest.
    """
    ...

def importance_sampling(model: Union[Callable[[Matrix], ArrayLike], "PolynomialChaos", "PiecewiseLinear"], law: LawLike, *, threshold: Optional[float] = None, target_cov: float = 0.05, max_draws: int = 1000000, level: float = 0.95, seed: int = 1, starts: Optional[ArrayLike] = None) -> ReliabilityResult:
    """
    Importance sampling centred at the FORM design point, `u ~ N(u*, I)`, drawn in rounds of
    2 048 until the coefficient of variation is at most `target_cov`.

    Parameters
    ----------
    model, law, threshold, starts
        As `form` (FORM finds the design point first).
    target_cov : float
        Target coefficient of variation, in (0, 1) (default 0.05).
    max_draws : int
        Largest number of draws, >= 2048 (default 10^6; a warning if reached first).
    level : float
        Confidence level of the interval `pf +- z sd / sqrt(N)`, in (0, 1).
    seed : int
        Seed (the result does not depend on the thread count).

    Returns
    -------
    ReliabilityResult
        `pf`, `interval`, `cov`, `calls` (FORM's included), the design point(s) and warnings
        (several design points: compare with `subset_simulation`).
    """
    ...

def lhs(law: LawLike, n: int, seed: int = 0, maximin: Optional[int] = None) -> Matrix:
    """
    Latin hypercube of `n` points of `law`: one point per stratum of probability `1/n` in each
    direction, mapped through the law's isoprobabilistic map (so dependent laws work too).
    `maximin=k` keeps the best of `k` hypercubes for the smallest pairwise distance.
    """
    ...

def monte_carlo(law: LawLike, n: int, seed: int = 0) -> Matrix:
    """
    `n` independent draws of `law` (a `Joint`, a `Law` or a list of `Law`s), shape `(n, d)`.
    Seeded: the same `seed` gives the same points for any number of threads.
    """
    ...

def pc_collocation(law: LawLike, degree: int, n: int) -> Matrix:
    """
    `n` collocation points for a chaos of degree `degree` (Berveiller, Sudret & Lemaire): the
    roots of the degree `degree + 1` orthonormal polynomial of each marginal, tensorised, the
    `n` of highest density first. `law`: independent variables.
    """
    ...

def quadrature(law: LawLike, order: Optional[int] = None, level: Optional[int] = None, nested: bool = False) -> Tuple[Matrix, Vector]:
    """
    A quadrature rule for the independent variables of `law`: `(nodes (n, d), weights (n,))`,
    weights summing to 1 (expectations under the law).

    Exactly one of: `order` (tensor Gauss rule, an int or one per variable); `level` (Smolyak
    sparse grid on Gauss rules, `level >= d`, exact for total degree `2 (level - d) + 1`); or
    `level` with `nested=True` (Smolyak on nested Clenshaw-Curtis / Genz-Keister rules, uniform
    and normal variables, `level >= 0`).
    """
    ...

def read_store(directory: Union[str, os.PathLike[str]], study: Optional[Union[str, os.PathLike[str]]] = None) -> Dict[str, Any]:
    """
    Reads the runs stored in a study directory without running anything. With `study` (the
    study file), the store must hold that version of it and names come from it.
    """
    ...

def rebuild_outputs(directory: Union[str, os.PathLike[str]]) -> Dict[str, Any]:
    """
    Rebuilds every output of a study directory from its store, computing no run (as
    `alea report DIR`); returns the files written and the warnings (see the `alea` package's
    `report`).
    """
    ...

def run_study_file(path: Union[str, os.PathLike[str]], directory: Union[str, os.PathLike[str]], restart: bool = False, threads: Optional[int] = None, progress: Optional[Callable[..., Any]] = None) -> Dict[str, Any]:
    """
    Runs (or resumes) the study file `path` in the study directory `directory` and analyses
    every method; returns a dict of arrays (see the `alea` package's `run`).
    """
    ...

def sobol(law: LawLike, n: int, scramble_seed: Optional[int] = None) -> Matrix:
    """
    First `n` points of the Sobol' sequence (Joe-Kuo directions, up to 40 variables) mapped
    through `law`; scrambled (linear matrix scramble and digital shift) when `scramble_seed` is
    given.
    """
    ...

def subset_simulation(model: Union[Callable[[Matrix], ArrayLike], "PolynomialChaos", "PiecewiseLinear"], law: LawLike, *, threshold: Optional[float] = None, samples_per_level: int = 2000, p0: float = 0.1, rho: float = 0.8, max_levels: int = 30, level: float = 0.95, seed: int = 1) -> ReliabilityResult:
    """
    Subset simulation (Au & Beck 2001): nested failure domains at the `p0` quantile of each
    level, conditional samples by the preconditioned Crank-Nicolson random walk.

    Parameters
    ----------
    model, law, threshold
        As `form`.
    samples_per_level : int
        Samples per level `N` (default 2000); `p0 N` must be a whole number dividing `N`.
    p0 : float
        Conditional probability of the intermediate levels, in (0, 0.5] (default 0.1).
    rho : float
        Correlation of the random-walk proposal, in [0, 1) (default 0.8).
    max_levels : int
        Largest number of levels, >= 1 (default 30; if the failure domain is not reached, `pf`
        is 0, the interval `(0, p0^max_levels)` and a warning says so).
    level : float
        Confidence level of the interval `pf exp(+- z cov)`, in (0, 1).
    seed : int
        Seed (the result does not depend on the thread count).

    Returns
    -------
    ReliabilityResult
        `pf`, `interval`, `cov`, `calls` (no design point).
    """
    ...
