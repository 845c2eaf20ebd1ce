"""Rare events from Python (`alea.form`, `sorm`, `importance_sampling`, `subset_simulation`)
against exact probabilities:

* FORM on limit states linear in the standard normal space is exact, `pf = Phi(-beta)`, also
  through a lognormal law (linear in `ln x`);
* SORM on a parabolic limit state gives Breitung's closed form, and its curvatures;
* importance sampling and subset simulation contain the exact pf in their intervals at pf 1e-5
  (linear) and 3e-6 (parabolic, exact by Gauss-Hermite quadrature); importance sampling stops
  within one round of its target coefficient of variation;
* on a symmetric parabola with two design points importance sampling warns (and indeed misses
  half the probability), subset simulation does not need a design point;
* a fitted surrogate analysed in Rust gives the same results as the same function called from
  Python (a chaos that reproduces a polynomial exactly, a grid interpolant of a multilinear
  function);
* every bad call raises a clear exception; an exception raised by the model propagates as
  itself, and Ctrl-C (SIGINT) stops an analysis.

The same cases as `crates/alea-uq/tests/reliability.rs` where they overlap."""

import math
import os
import signal
import warnings

import numpy as np
import pytest

import alea


def Phi(x):
    return 0.5 * math.erfc(-x / math.sqrt(2.0))


def normals(d):
    return [alea.Normal(0.0, 1.0)] * d


def gauss_expectation(f, n=80):
    """E[f(u)] for u ~ N(0, 1) by Gauss-Hermite (probabilists') quadrature."""
    x, w = np.polynomial.hermite_e.hermegauss(n)
    return float(np.sum(w * f(x)) / math.sqrt(2.0 * math.pi))


def parabola_exact(beta, k):
    """P(u3 >= beta + (k1 u1^2 + k2 u2^2) / 2), (u1, u2, u3) ~ N(0, I), by tensor quadrature."""
    x, w = np.polynomial.hermite_e.hermegauss(60)
    u1, u2 = np.meshgrid(x, x)
    ww = np.outer(w, w) / (2.0 * math.pi)
    phi = 0.5 * np.vectorize(math.erfc)((beta + 0.5 * (k[0] * u1**2 + k[1] * u2**2)) / math.sqrt(2.0))
    return float(np.sum(ww * phi))


# ---- FORM and SORM --------------------------------------------------------------------------


def test_form_is_exact_on_a_linear_limit_state():
    a = np.array([0.5, -1.0, 2.0])
    beta = 3.2
    g = lambda x: beta - x @ a / np.linalg.norm(a)  # noqa: E731
    r = alea.form(g, normals(3))
    assert r.method == "FORM"
    assert r.beta == pytest.approx(beta, abs=1e-7)
    assert r.pf == pytest.approx(Phi(-beta), rel=1e-8)
    assert r.design_point == pytest.approx(beta * a / np.linalg.norm(a), abs=1e-6)
    assert r.importance_factors == pytest.approx(a**2 / np.sum(a**2), abs=1e-6)
    assert r.interval is None and r.cov is None and r.warnings == []
    assert r.design_points.shape == (1, 3) and r.calls > 0
    assert r.generalised_beta == pytest.approx(beta, rel=1e-7)


def test_form_is_exact_through_a_lognormal_law():
    # ln x_i ~ N(0.1, 0.25): failure ln x1 + ln x2 >= c is linear in u, pf = Phi(-(c - 0.2) / (0.25 sqrt 2)).
    law = [alea.Lognormal(0.1, 0.25)] * 2
    c = 1.2
    r = alea.form(lambda x: np.log(x[:, 0]) + np.log(x[:, 1]), law, threshold=c)
    beta = (c - 0.2) / (0.25 * math.sqrt(2.0))
    assert r.beta == pytest.approx(beta, abs=1e-6)
    assert r.pf == pytest.approx(Phi(-beta), rel=1e-6)
    assert r.design_point == pytest.approx([math.exp(c / 2)] * 2, rel=1e-6)


def test_form_is_exact_through_a_gaussian_copula():
    # x ~ N(0, [[1, rho], [rho, 1]]): x1 + x2 ~ N(0, 2 + 2 rho), P(x1 + x2 > c) = Phi(-c / sqrt(2 + 2 rho)).
    rho, c = 0.5, 5.0
    law = alea.Joint([alea.Normal(0.0, 1.0), alea.Normal(0.0, 1.0)], correlation=[[1.0, rho], [rho, 1.0]])
    r = alea.form(lambda x: x[:, 0] + x[:, 1], law, threshold=c)
    beta = c / math.sqrt(2.0 + 2.0 * rho)
    assert r.beta == pytest.approx(beta, abs=1e-6)
    assert r.pf == pytest.approx(Phi(-beta), rel=1e-6)
    assert r.design_point == pytest.approx([c / 2.0, c / 2.0], abs=1e-6)
    s = alea.importance_sampling(lambda x: x[:, 0] + x[:, 1], law, threshold=c)
    assert s.interval[0] <= Phi(-beta) <= s.interval[1]


def test_sorm_gives_breitungs_closed_form_on_a_parabola():
    beta, k = 3.0, (0.2, -0.1)
    g = lambda u: beta + 0.5 * (k[0] * u[:, 0] ** 2 + k[1] * u[:, 1] ** 2) - u[:, 2]  # noqa: E731
    r = alea.sorm(g, normals(3))
    breitung = Phi(-beta) / math.sqrt((1 + beta * k[0]) * (1 + beta * k[1]))
    assert r.method == "SORM"
    assert r.beta == pytest.approx(beta, abs=1e-7)
    assert r.curvatures == pytest.approx(sorted(k), abs=1e-5)
    assert r.pf == r.pf_breitung == pytest.approx(breitung, rel=1e-6)
    exact = parabola_exact(beta, k)
    # Tvedt closer than Breitung, Breitung closer than FORM (as in alea-uq's test).
    assert abs(r.pf_tvedt / exact - 1) < 0.01
    assert abs(r.pf_tvedt / exact - 1) < abs(r.pf_breitung / exact - 1) < abs(Phi(-beta) / exact - 1)
    # The Hessian costs 2 d^2 + 1 calls beyond FORM's (OpenTURNS: about 2 d^2; 4 d^2 for
    # differences of gradients).
    assert r.calls - alea.form(g, normals(3)).calls == 2 * 3**2 + 1


# ---- sampling methods ------------------------------------------------------------------------

BETA_1E5 = 4.264890793922602  # Phi(-beta) = 1e-5


def linear_4d(x):
    return BETA_1E5 - (x[:, 0] + x[:, 1] - x[:, 2] + x[:, 3]) / 2.0


def test_importance_sampling_and_subset_contain_the_exact_pf_1e5():
    exact = Phi(-BETA_1E5)
    law = normals(4)
    form_calls = alea.form(linear_4d, law).calls
    r = alea.importance_sampling(linear_4d, law, target_cov=0.05)
    lo, hi = r.interval
    assert lo <= exact <= hi, (r, exact)
    assert r.cov <= 0.05 and r.level == 0.95
    # Stops within one round (2 048 draws) of the target: about (1/0.05^2) / few draws needed.
    assert r.calls - form_calls <= 4096
    s = alea.subset_simulation(linear_4d, law)
    lo, hi = s.interval
    assert lo <= exact <= hi, (s, exact)
    assert s.beta is None and s.design_point is None and s.calls >= 2000
    assert s.cov < 0.5


def test_importance_sampling_and_subset_on_a_parabola_at_3e6():
    beta, k = 4.5, (0.2, -0.1)
    exact = parabola_exact(beta, k)
    assert 1e-6 < exact < 1e-5
    g = lambda u: beta + 0.5 * (k[0] * u[:, 0] ** 2 + k[1] * u[:, 1] ** 2) - u[:, 2]  # noqa: E731
    r = alea.importance_sampling(g, normals(3), target_cov=0.03, seed=7)
    assert r.interval[0] <= exact <= r.interval[1], (r, exact)
    assert r.cov <= 0.03
    # Subset simulation's 95 % interval, over 5 seeds: contains the exact value at least 4
    # times, and every estimate is within 3 coefficients of variation of it.
    covered = 0
    for seed in range(1, 6):
        s = alea.subset_simulation(g, normals(3), seed=seed)
        covered += s.interval[0] <= exact <= s.interval[1]
        assert abs(math.log(s.pf / exact)) <= 3 * s.cov, (s, exact)
    assert covered >= 4


def test_importance_sampling_warns_on_a_symmetric_parabola_with_two_design_points():
    # u2 >= 3 - u1^2 / 2: design points (+-2, 1), beta = sqrt 5; P = E[Phi(-(3 - u1^2/2))].
    exact = gauss_expectation(lambda u: np.vectorize(Phi)(-(3.0 - 0.5 * u**2)), 200)
    g = lambda u: 3.0 - 0.5 * u[:, 0] ** 2 - u[:, 1]  # noqa: E731
    with pytest.warns(RuntimeWarning, match="design points within beta"):
        r = alea.importance_sampling(g, normals(2))
    assert len(r.warnings) == 1
    assert r.beta == pytest.approx(math.sqrt(5.0), abs=1e-5)
    betas = r.design_point_betas
    assert betas[:2] == pytest.approx([math.sqrt(5.0)] * 2, abs=1e-5)
    assert sorted(abs(r.design_points[:2, 0])) == pytest.approx([2.0, 2.0], abs=1e-4)
    # What the warning is about: sampling around one design point finds about half of pf.
    assert r.interval[1] < exact
    assert r.pf == pytest.approx(exact / 2, rel=0.15)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        s = alea.subset_simulation(g, normals(2))
    assert s.interval[0] <= exact <= s.interval[1]
    assert s.warnings == []


def test_results_do_not_depend_on_the_thread_count_or_the_call():
    a = alea.importance_sampling(linear_4d, normals(4), seed=5)
    b = alea.importance_sampling(linear_4d, normals(4), seed=5)
    assert (a.pf, a.interval, a.calls) == (b.pf, b.interval, b.calls)
    c = alea.importance_sampling(linear_4d, normals(4), seed=6)
    assert c.pf != a.pf


# ---- surrogates, analysed in Rust -----------------------------------------------------------


def cubic(x):
    return 1.0 + x[:, 0] + 0.5 * x[:, 1] + 0.2 * x[:, 0] * x[:, 1] + 0.05 * x[:, 0] ** 3


def test_a_chaos_gives_the_same_results_as_the_function_it_reproduces():
    law = alea.Joint([alea.Normal(0.0, 1.0), alea.Normal(0.5, 2.0)])
    x = alea.lhs(law, 40, seed=2)
    pc = alea.PolynomialChaos.regression(law, 3, x, cubic(x))
    t = 6.0
    for method, kw in [
        (alea.form, {}),
        (alea.sorm, {}),
        (alea.importance_sampling, {"seed": 3}),
        (alea.subset_simulation, {"seed": 3}),
    ]:
        on_pc = method(pc, law, threshold=t, **kw)
        on_predict = method(pc.predict, law, threshold=t, **kw)
        on_function = method(cubic, law, threshold=t, **kw)
        # The same arithmetic in Rust as through Python: the same numbers.
        assert on_pc.pf == on_predict.pf and on_pc.calls == on_predict.calls, method
        assert on_pc.pf == pytest.approx(on_function.pf, rel=1e-6), method
        if on_pc.interval is not None:
            assert on_pc.interval == pytest.approx(on_function.interval, rel=1e-6)
        if on_pc.design_point is not None:
            assert on_pc.design_point == pytest.approx(on_function.design_point, abs=1e-6)


def test_a_grid_interpolant_gives_the_same_results_as_the_multilinear_function():
    law = [alea.Uniform(0.0, 1.0), alea.Uniform(0.0, 2.0)]
    f = lambda x: 1.0 + x[:, 0] + 2.0 * x[:, 1] + 3.0 * x[:, 0] * x[:, 1]  # noqa: E731
    nodes = alea.PiecewiseLinear.nodes([0.0, 0.0], [1.0, 2.0], [4, 4])
    pl = alea.PiecewiseLinear([0.0, 0.0], [1.0, 2.0], [4, 4], f(nodes))
    # Exact P(f > 9): f = 1 + x + y (2 + 3x) > 9 <=> y > (8 - x) / (2 + 3x), y ~ U(0, 2).
    xs, ws = np.polynomial.legendre.leggauss(400)
    xs = 0.5 * (xs + 1.0)
    ystar = np.clip((8.0 - xs) / (2.0 + 3.0 * xs), 0.0, 2.0)
    exact = float(np.sum(0.5 * ws * (2.0 - ystar) / 2.0))
    s_pl = alea.subset_simulation(pl, law, threshold=9.0, seed=4)
    s_f = alea.subset_simulation(f, law, threshold=9.0, seed=4)
    assert s_pl.pf == pytest.approx(s_f.pf, rel=1e-9)
    assert s_pl.interval[0] <= exact <= s_pl.interval[1]
    # (FORM's default tol 1e-6 is not reached here, on the function as on the grid: the step
    # stalls at 1e-6 relative while |G| = 2e-9; 1e-5 converges.)
    f_pl = alea.form(pl, law, threshold=9.0, tol=1e-5)
    f_f = alea.form(f, law, threshold=9.0, tol=1e-5)
    assert f_pl.beta == pytest.approx(f_f.beta, abs=1e-9)
    assert f_pl.design_point == pytest.approx(f_f.design_point, abs=1e-9)


def test_a_grid_interpolant_needs_a_law_inside_its_box():
    pl = alea.PiecewiseLinear([0.0], [1.0], [4], np.linspace(0.0, 1.0, 5))
    with pytest.raises(ValueError, match="outside the PiecewiseLinear grid"):
        alea.form(pl, alea.Normal(0.5, 0.1), threshold=0.9)


# ---- bad calls ------------------------------------------------------------------------------


class ModelError(Exception):
    pass


def test_an_exception_of_the_model_propagates_as_itself_and_stops_the_analysis():
    calls = []

    def g(x):
        calls.append(len(x))
        if len(calls) == 5:
            raise ModelError("boom at call 5")
        return 3.0 - x[:, 0]

    for method in (alea.form, alea.sorm, alea.importance_sampling, alea.subset_simulation):
        calls.clear()
        with pytest.raises(ModelError, match="boom at call 5"):
            method(g, normals(2))
        assert len(calls) == 5, method  # not called again after raising
        assert set(calls) == {1}


@pytest.mark.parametrize(
    "bad, error, match",
    [
        (lambda x: np.full(len(x), np.nan), ValueError, "returned NaN at the point"),
        (lambda x: np.full(len(x), np.inf), ValueError, "returned inf"),
        (lambda x: 1.0, ValueError, "vectorised"),
        (lambda x: np.zeros((len(x), 2)), ValueError, r"shape \[1, 2\]"),
        (lambda x: ["a"] * len(x), TypeError, "must return an array of n numbers"),
        (lambda x: None, TypeError, "returned None"),
    ],
    ids=["nan", "inf", "scalar", "two-columns", "strings", "none"],
)
def test_a_model_returning_no_finite_values_is_refused(bad, error, match):
    for method in (alea.form, alea.importance_sampling, alea.subset_simulation):
        with pytest.raises(error, match=match):
            method(bad, normals(2))


def test_ctrl_c_stops_an_analysis():
    # Python's own handler, whatever the process inherited: a shell starts background jobs
    # with SIGINT ignored, and Python then keeps it ignored (no KeyboardInterrupt at all).
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        _ctrl_c_stops_an_analysis()
    finally:
        signal.signal(signal.SIGINT, previous)


def _ctrl_c_stops_an_analysis():
    calls = []

    def g(x):
        calls.append(1)
        if len(calls) == 50:
            os.kill(os.getpid(), signal.SIGINT)
        return 20.0 - x[:, 0]  # never fails: subset simulation would run all its levels

    with pytest.raises(KeyboardInterrupt):
        alea.subset_simulation(g, normals(2), max_levels=1000)
    assert len(calls) < 100_000


CHAOS_LAW = [alea.Normal(0.0, 1.0)] * 2


def chaos():
    x = alea.lhs(CHAOS_LAW, 20, seed=1)
    return alea.PolynomialChaos.regression(CHAOS_LAW, 2, x, x[:, 0] + x[:, 1])


@pytest.mark.parametrize(
    "call, error, match",
    [
        (lambda: alea.form(chaos(), normals(3), threshold=1.0), ValueError, "PolynomialChaos has 2 variables, the law 3"),
        (lambda: alea.form(3.0, normals(2)), TypeError, "must be a callable"),
        (lambda: alea.form(linear_4d, "normal"), TypeError, "expected a list of alea laws"),
        (lambda: alea.form(linear_4d, normals(4), threshold=float("nan")), ValueError, "threshold must be a finite number, got NaN"),
        (lambda: alea.form(linear_4d, normals(4), threshold=float("inf")), ValueError, "threshold"),
        (lambda: alea.form(linear_4d, normals(4), starts=[[0.0, 0.0]]), ValueError, r"starts: expected an array of shape \(n, 4\)"),
        (lambda: alea.form(linear_4d, normals(4), starts=[[0.0, 0.0, np.nan, 0.0]]), ValueError, "starts: entry 2 is NaN"),
        (lambda: alea.form(linear_4d, normals(4), tol=0.0), ValueError, "tol must be > 0"),
        (lambda: alea.form(linear_4d, normals(4), step=-1e-4), ValueError, "step must be > 0"),
        (lambda: alea.form(linear_4d, normals(4), max_iter=0), ValueError, "max_iter must be an integer >= 1, got 0"),
        (lambda: alea.form(linear_4d, normals(4), max_iter=2.5), TypeError, "max_iter must be an integer"),
        (lambda: alea.form(lambda x: np.ones(len(x)), normals(2)), ValueError, "FORM: no start converged"),
        (lambda: alea.sorm(lambda u: 1.0 - 0.9 * u[:, 0] ** 2 - u[:, 1], normals(2), starts=[[0.0, 0.0]]), ValueError, "1 \\+ beta kappa <= 0"),
        (lambda: alea.importance_sampling(linear_4d, normals(4), target_cov=0.0), ValueError, "target_cov must be in \\(0, 1\\), got 0"),
        (lambda: alea.importance_sampling(linear_4d, normals(4), target_cov=1.0), ValueError, "target_cov"),
        (lambda: alea.importance_sampling(linear_4d, normals(4), target_cov=float("nan")), ValueError, "target_cov"),
        (lambda: alea.importance_sampling(linear_4d, normals(4), max_draws=100), ValueError, "max_draws must be an integer >= 2048, got 100"),
        (lambda: alea.importance_sampling(linear_4d, normals(4), max_draws=-5), ValueError, "max_draws must be an integer >= 2048, got -5"),
        (lambda: alea.importance_sampling(linear_4d, normals(4), max_draws=10**40), ValueError, "too large"),
        (lambda: alea.importance_sampling(linear_4d, normals(4), level=1.5), ValueError, "level must be in \\(0, 1\\)"),
        (lambda: alea.importance_sampling(linear_4d, normals(4), seed=-1), ValueError, "non-negative"),
        (lambda: alea.importance_sampling(linear_4d, normals(4), seed=10**30), ValueError, "non-negative integer within range"),
        (lambda: alea.subset_simulation(linear_4d, normals(4), samples_per_level=0), ValueError, "samples_per_level must be an integer >= 1, got 0"),
        (lambda: alea.subset_simulation(linear_4d, normals(4), samples_per_level=-10), ValueError, "samples_per_level must be an integer >= 1, got -10"),
        (lambda: alea.subset_simulation(linear_4d, normals(4), samples_per_level=1001), ValueError, "must be a whole number >= 1 dividing"),
        (lambda: alea.subset_simulation(linear_4d, normals(4), samples_per_level=5), ValueError, "must be a whole number >= 1 dividing"),
        (lambda: alea.subset_simulation(linear_4d, normals(4), p0=0.7), ValueError, "p0 must be in \\(0, 0.5\\]"),
        (lambda: alea.subset_simulation(linear_4d, normals(4), rho=1.0), ValueError, "rho must be in \\[0, 1\\)"),
        (lambda: alea.subset_simulation(linear_4d, normals(4), max_levels=0), ValueError, "max_levels must be an integer >= 1"),
    ],
    ids=lambda v: None,
)
def test_every_bad_call_raises_a_clear_exception(call, error, match):
    with pytest.raises(error, match=match):
        call()


def test_subset_simulation_says_when_it_does_not_reach_the_failure_domain():
    with pytest.warns(RuntimeWarning, match="did not reach the failure domain in 2 levels"):
        s = alea.subset_simulation(lambda x: 10.0 - x[:, 0], normals(1), max_levels=2)
    assert s.pf == 0.0 and s.interval == (0.0, pytest.approx(0.01)) and s.cov is None


def test_importance_sampling_says_when_max_draws_comes_before_its_target():
    with pytest.warns(RuntimeWarning, match=r"stopped at max_draws \(2048 draws\)"):
        r = alea.importance_sampling(linear_4d, normals(4), target_cov=0.001, max_draws=2048)
    assert r.cov > 0.001 and r.interval[0] <= Phi(-BETA_1E5) <= r.interval[1]
