"""Laws against closed forms: moments, distribution functions, quantile round trips,
sampling moments within a few standard errors, seeded reproducibility; joint laws: the Gaussian
copula's density against the bivariate normal density and its normal-score correlation."""

import math

import numpy as np
import pytest

import alea


def norm_pdf(x):
    return math.exp(-0.5 * x * x) / math.sqrt(2 * math.pi)


def norm_cdf(x):
    return 0.5 * math.erfc(-x / math.sqrt(2))


CASES = [
    # law, exact mean, exact std
    (alea.Normal(1.0, 0.1), 1.0, 0.1),
    (alea.Uniform(150e3, 250e3), 200e3, 100e3 / math.sqrt(12)),
    (alea.Lognormal(0.2, 0.3), math.exp(0.2 + 0.045), math.sqrt((math.exp(0.09) - 1) * math.exp(0.4 + 0.09))),
    (alea.Gamma(3.0, 2.0, 1.0), 1.0 + 6.0, math.sqrt(3.0) * 2.0),
    (alea.Beta(2.0, 5.0, 0.0, 1.0), 2 / 7, math.sqrt(2 * 5 / (7**2 * 8))),
    (alea.Triangular(0.0, 1.0, 4.0), 5 / 3, math.sqrt((0 + 1 + 16 - 0 - 0 - 4) / 18)),
]


def truncated_normal_moments(mu, s, lo, hi):
    a, b = (lo - mu) / s, (hi - mu) / s
    z = norm_cdf(b) - norm_cdf(a)
    m = mu + s * (norm_pdf(a) - norm_pdf(b)) / z
    v = s * s * (1 + (a * norm_pdf(a) - b * norm_pdf(b)) / z - ((norm_pdf(a) - norm_pdf(b)) / z) ** 2)
    return m, math.sqrt(v)


CASES.append((alea.TruncatedNormal(0.3, 0.1, 0.1, 0.45), *truncated_normal_moments(0.3, 0.1, 0.1, 0.45)))


@pytest.mark.parametrize("law,mean,std", CASES, ids=lambda c: repr(c) if isinstance(c, alea.Law) else "")
def test_moments_match_closed_forms(law, mean, std):
    assert law.mean == pytest.approx(mean, rel=1e-10)
    assert law.std == pytest.approx(std, rel=1e-9)
    assert law.variance == pytest.approx(std**2, rel=1e-9)


@pytest.mark.parametrize("law,mean,std", CASES, ids=lambda c: repr(c) if isinstance(c, alea.Law) else "")
def test_quantile_inverts_cdf_and_pdf_integrates_to_cdf(law, mean, std):
    p = np.linspace(0.001, 0.999, 41)
    x = law.quantile(p)
    assert x.shape == p.shape
    np.testing.assert_allclose(law.cdf(x), p, rtol=0, atol=1e-11)
    np.testing.assert_allclose(law.sf(x), 1 - p, rtol=0, atol=1e-11)
    # cdf(b) - cdf(a) = integral of the pdf (composite Gauss-Legendre, 20 points per panel).
    a, b = law.quantile(0.05), law.quantile(0.95)
    t, w = np.polynomial.legendre.leggauss(20)
    edges = np.linspace(a, b, 41)
    if a < 1.0 < b:  # the triangular law's mode: keep the kink on a panel edge
        edges = np.sort(np.append(edges, 1.0))
    total = 0.0
    for lo, hi in zip(edges[:-1], edges[1:]):
        xs = 0.5 * (hi - lo) * t + 0.5 * (hi + lo)
        total += 0.5 * (hi - lo) * np.dot(w, law.pdf(xs))
    assert total == pytest.approx(0.9, abs=1e-10)


@pytest.mark.parametrize("law,mean,std", CASES, ids=lambda c: repr(c) if isinstance(c, alea.Law) else "")
def test_sampling_moments_within_standard_errors(law, mean, std):
    n = 100_000
    x = law.sample(n, seed=3)
    assert x.shape == (n,)
    assert abs(x.mean() - mean) < 4.5 * std / math.sqrt(n)
    np.testing.assert_array_equal(x, law.sample(n, seed=3))
    assert not np.array_equal(x, law.sample(n, seed=4))


def test_scalar_in_scalar_out_and_shapes_kept():
    n = alea.Normal()
    assert isinstance(n.cdf(0.0), float) and n.cdf(0.0) == 0.5
    assert n.pdf(np.zeros((2, 3))).shape == (2, 3)
    assert n.support == (-math.inf, math.inf)
    assert isinstance(n, alea.Law) and n.name == "normal"


def test_far_tail_truncated_normal():
    # TN(0, 1, [-40, -38]): the mean is -38 - 1/38 + O(38^-3); quadrature of the rescaled
    # density: int x phi(x) / int phi(x) on [-40, -38] with phi(x) ~ exp(-(x + 38) * 38).
    law = alea.TruncatedNormal(0.0, 1.0, -40.0, -38.0)
    t, w = np.polynomial.legendre.leggauss(60)
    xs = -39.0 + t
    dens = np.exp(-0.5 * (xs**2 - 38.0**2))
    assert law.mean == pytest.approx(np.dot(w, xs * dens) / np.dot(w, dens), rel=1e-12)


def test_bad_parameters_raise_value_errors_naming_the_field():
    with pytest.raises(ValueError, match="std must be > 0"):
        alea.Normal(0.0, -1.0)
    with pytest.raises(ValueError, match="uniform"):
        alea.Uniform(2.0, 1.0)


def test_empirical_and_kde_laws_and_fit():
    data = alea.Normal(3.0, 2.0).sample(20_000, seed=1)
    emp = alea.Empirical(data)
    # Each gap between sorted values carries mass 1/(n-1) uniformly.
    xs = np.sort(data)
    assert emp.mean == pytest.approx(np.sum(xs[:-1] + xs[1:]) / (2 * (len(xs) - 1)), rel=1e-12)
    assert emp.quantile(0.3) == pytest.approx(np.quantile(data, 0.3), rel=1e-12)
    kde = alea.Kde(data)
    # The KDE law is a Gaussian mixture: variance = sample variance + h^2.
    assert kde.std == pytest.approx(math.sqrt(data.var() + kde.bandwidth**2), rel=1e-12)
    assert kde.cdf(3.0) == pytest.approx(0.5, abs=0.01)
    fits = alea.fit(data)
    assert fits[0]["family"] == "normal"
    assert fits[0]["parameters"]["mean"] == pytest.approx(3.0, abs=4.5 * 2.0 / math.sqrt(20_000))
    assert fits[0]["law"].std == pytest.approx(2.0, abs=4.5 * 2.0 / math.sqrt(40_000))


def test_gaussian_copula_density_is_the_bivariate_normal():
    rho = 0.6
    j = alea.Joint([alea.Normal(1.0, 2.0), alea.Normal(-1.0, 0.5)], correlation=[[1, rho], [rho, 1]])
    assert j.kind == "gaussian copula" and j.dim == 2
    np.testing.assert_array_equal(j.correlation, [[1, rho], [rho, 1]])
    x = np.array([[1.0, -1.0], [2.5, -0.3], [-1.0, -1.7]])
    z1, z2 = (x[:, 0] - 1.0) / 2.0, (x[:, 1] + 1.0) / 0.5
    exact = np.exp(-(z1**2 - 2 * rho * z1 * z2 + z2**2) / (2 * (1 - rho**2))) / (
        2 * math.pi * 2.0 * 0.5 * math.sqrt(1 - rho**2)
    )
    np.testing.assert_allclose(j.pdf(x), exact, rtol=1e-12)
    # Round trips of the isoprobabilistic maps.
    np.testing.assert_allclose(j.from_unit(j.to_unit(x)), x, rtol=1e-12)
    np.testing.assert_allclose(j.from_standard_normal(j.to_standard_normal(x)), x, rtol=1e-12)


def test_gaussian_copula_samples_have_the_normal_score_correlation():
    rho, n = -0.5, 50_000
    j = alea.Joint([alea.Uniform(0.0, 1.0), alea.Lognormal(0.0, 0.5)], correlation=[[1, rho], [rho, 1]])
    x = j.sample(n, seed=11)
    # Normal scores z_i = Phi^-1(F_i(x_i)): correlation rho within a Fisher-z interval.
    z = np.column_stack([
        np.array([math.sqrt(2) * _erfinv(2 * u - 1) for u in j.marginals[0].cdf(x[:, 0])]),
        np.log(x[:, 1]) / 0.5,
    ])
    r = np.corrcoef(z.T)[0, 1]
    assert abs(math.atanh(r) - math.atanh(rho)) < 4.5 / math.sqrt(n - 3)
    # Independent standard normals after the Nataf transform.
    y = j.to_standard_normal(x)
    assert abs(np.corrcoef(y.T)[0, 1]) < 4.5 / math.sqrt(n)


def _erfinv(y):
    # Newton on erf, enough for the test's normal scores.
    x = 0.0
    for _ in range(60):
        x -= (math.erf(x) - y) / (2 / math.sqrt(math.pi) * math.exp(-x * x))
    return x


def test_other_copulas_and_law_arguments():
    m = [alea.Uniform(0, 1), alea.Uniform(0, 1)]
    c = alea.Joint.clayton(m, 2.0)
    u = c.sample(20_000, seed=5)
    # Kendall's tau of the Clayton copula is theta / (theta + 2) = 0.5.
    n = 2000
    a, b = u[:n, 0], u[:n, 1]
    s = np.sign(a[:, None] - a[None, :]) * np.sign(b[:, None] - b[None, :])
    tau = s.sum() / (n * (n - 1))
    assert tau == pytest.approx(0.5, abs=0.05)
    with pytest.raises(TypeError):
        alea.monte_carlo("not a law", 10)
    with pytest.raises(ValueError, match="independent"):
        alea.PolynomialChaos.regression(c, 2, u[:50], u[:50, 0])


def test_class_names_are_the_exported_names():
    for name in ["Normal", "Uniform", "TruncatedNormal", "Lognormal", "Beta", "Gamma", "Triangular", "Empirical", "Kde", "Joint", "PolynomialChaos", "PiecewiseLinear", "Law"]:
        cls = getattr(alea, name)
        assert cls.__name__ == name and cls.__module__ == "alea"
    assert "Normal law" in alea.Normal.__doc__


@pytest.mark.parametrize("p", [[1.5], [-0.1], [0.2, float("nan")], 2.0])
def test_quantile_outside_zero_one_is_a_value_error_not_nan(p):
    with pytest.raises(ValueError, match=r"probabilities must be in \[0, 1\]"):
        alea.Normal(0.0, 1.0).quantile(p)


def test_clayton_takes_negative_theta_for_two_variables_only():
    m = [alea.Normal(0.0, 1.0), alea.Normal(0.0, 1.0)]
    j = alea.Joint.clayton(m, -0.5)
    x = alea.monte_carlo(j, 2000, seed=3)
    # Kendall's tau theta / (theta + 2) = -1/3: the draws are negatively dependent.
    assert np.corrcoef(x[:, 0], x[:, 1])[0, 1] < -0.3
    with pytest.raises(ValueError, match="theta"):
        alea.Joint.clayton(m + [alea.Normal(0.0, 1.0)], -0.5)
    with pytest.raises(ValueError, match="theta"):
        alea.Joint.clayton(m, -1.0)
