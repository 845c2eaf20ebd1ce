"""Surrogates against exact statistics: polynomial chaos of the Ishigami function (mean,
variance, first and total Sobol' indices in closed form), exact reproduction of polynomials in
the basis, LARS's corrected leave-one-out error against a held-out error, save/load, and
piecewise-multilinear interpolation with moments checked against Gauss quadrature."""

import math

import numpy as np
import pytest

import alea

A, B = 7.0, 0.1


def ishigami(x):
    return np.sin(x[:, 0]) + A * np.sin(x[:, 1]) ** 2 + B * x[:, 2] ** 4 * np.sin(x[:, 0])


# Closed forms (Ishigami & Homma 1990; Sobol' & Levitan 1999).
PI4, PI8 = math.pi**4, math.pi**8
V1 = 0.5 * (1 + B * PI4 / 5) ** 2
V2 = A**2 / 8
V13 = B**2 * PI8 * (1 / 18 - 1 / 50)
VAR = V1 + V2 + V13
MEAN = A / 2


@pytest.fixture(scope="module")
def law():
    return alea.Joint([alea.Uniform(-math.pi, math.pi)] * 3)


def test_exact_closed_forms_are_consistent():
    assert VAR == pytest.approx(A**2 / 8 + B * PI4 / 5 + B**2 * PI8 / 18 + 0.5, rel=1e-14)


def test_ishigami_projection(law):
    nodes, w = alea.quadrature(law, order=16)
    pc = alea.PolynomialChaos.projection(law, 14, nodes, w, ishigami(nodes))
    assert pc.method == "projection"
    assert pc.mean == pytest.approx(MEAN, rel=1e-10)
    assert pc.variance == pytest.approx(VAR, rel=1e-5)
    np.testing.assert_allclose(pc.sobol_first(), [V1 / VAR, V2 / VAR, 0.0], rtol=1e-5, atol=1e-10)
    np.testing.assert_allclose(pc.sobol_total(), [(V1 + V13) / VAR, V2 / VAR, V13 / VAR], rtol=1e-5)
    assert pc.sobol_index([0, 2]) == pytest.approx(V13 / VAR, rel=1e-5)
    assert pc.sobol_second_order()[0, 2] == pytest.approx(V13 / VAR, rel=1e-5)
    with pytest.raises(ValueError, match="regression"):
        pc.loo_error


def test_ishigami_regression_and_predict(law):
    x = alea.sobol(law, 2048, scramble_seed=1)
    pc = alea.PolynomialChaos.regression(law, 12, x, ishigami(x))
    assert pc.mean == pytest.approx(MEAN, rel=1e-4)
    assert pc.variance == pytest.approx(VAR, rel=1e-4)
    test = alea.monte_carlo(law, 10_000, seed=5)
    err = np.mean((pc.predict(test) - ishigami(test)) ** 2) / VAR
    assert err < 1e-7
    assert pc.loo_error < pc.corrected_loo_error < 10 * err
    # Linear in the run values: predict = weights @ values.
    w = pc.weights(test[:5])
    assert w.shape == (5, 2048)
    np.testing.assert_allclose(w @ ishigami(x), pc.predict(test[:5]), rtol=1e-9)


def test_lars_corrected_loo_tracks_the_held_out_error(law):
    x = alea.lhs(law, 200, seed=3)
    pc = alea.PolynomialChaos.lars(law, 12, x, ishigami(x))
    assert pc.method == "lars"
    test = alea.monte_carlo(law, 100_000, seed=8)
    y = ishigami(test)
    held_out = np.mean((pc.predict(test) - y) ** 2) / np.var(y)
    assert held_out / 2 < pc.corrected_loo_error < 2 * held_out
    assert pc.coefficients.shape[0] == pc.multi_indices.shape[0] < 200 // 2 + 1
    path = pc.lars_path
    assert path.shape[1] == 2 and path[:, 1].min() == pytest.approx(pc.corrected_loo_error, rel=1e-9)


def test_regression_is_exact_on_polynomials_of_the_basis():
    law = [alea.Normal(0, 1), alea.Normal(0, 1)]
    x = alea.lhs(law, 30, seed=1)
    y = 1 + 2 * x[:, 0] + 3 * x[:, 0] * x[:, 1]
    pc = alea.PolynomialChaos.regression(law, 2, x, y)
    assert pc.mean == pytest.approx(1, abs=1e-12)
    assert pc.variance == pytest.approx(4 + 9, rel=1e-12)
    np.testing.assert_allclose(pc.sobol_first(), [4 / 13, 0], atol=1e-12)
    np.testing.assert_allclose(pc.sobol_total(), [1, 9 / 13], atol=1e-12)
    assert pc.warnings == []


def test_save_and_load_round_trip(law, tmp_path):
    x = alea.lhs(law, 300, seed=2)
    pc = alea.PolynomialChaos.regression(law, 6, x, ishigami(x))
    path = tmp_path / "pc.json"
    pc.save(path)
    back = alea.PolynomialChaos.load(path)
    np.testing.assert_array_equal(back.coefficients, pc.coefficients)
    np.testing.assert_array_equal(back.predict(x[:10]), pc.predict(x[:10]))
    assert back.corrected_loo_error == pc.corrected_loo_error
    with pytest.raises(OSError):
        alea.PolynomialChaos.load(tmp_path / "missing.json")


def test_shape_errors_are_value_errors(law):
    x = alea.lhs(law, 50, seed=1)
    with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
        alea.PolynomialChaos.regression(law, 2, x[:, :2], ishigami(x))
    with pytest.raises(ValueError, match="length 50"):
        alea.PolynomialChaos.regression(law, 2, x, ishigami(x)[:-1])
    y = ishigami(x)
    y[3] = np.nan
    with pytest.raises(ValueError, match="finite"):
        alea.PolynomialChaos.regression(law, 2, x, y)


def gauss_box(f, lo, hi, n=12):
    """Tensor Gauss-Legendre integral over a 2-D box."""
    t, w = np.polynomial.legendre.leggauss(n)
    xs = 0.5 * (hi[0] - lo[0]) * t + 0.5 * (hi[0] + lo[0])
    ys = 0.5 * (hi[1] - lo[1]) * t + 0.5 * (hi[1] + lo[1])
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    W = np.outer(w, w) * 0.25 * (hi[0] - lo[0]) * (hi[1] - lo[1])
    return np.sum(W * f(X, Y))


def test_piecewise_linear_exact_on_bilinear_functions_and_moments():
    lo, hi, cells = [0.0, 1.0], [2.0, 2.0], [4, 3]
    f = lambda x, y: 1 + x + 2 * y + 3 * x * y
    nodes = alea.PiecewiseLinear.nodes(lo, hi, cells)
    assert nodes.shape == (5 * 4, 2)
    np.testing.assert_array_equal(nodes[:3], [[0, 1], [0.5, 1], [1, 1]])  # first direction fastest
    pl = alea.PiecewiseLinear(lo, hi, cells, f(nodes[:, 0], nodes[:, 1]))
    test = alea.monte_carlo([alea.Uniform(0, 2), alea.Uniform(1, 2)], 100, seed=1)
    np.testing.assert_allclose(pl.predict(test), f(test[:, 0], test[:, 1]), rtol=1e-13)
    # Moments under a law supported in the box: truncated normals, against tensor Gauss.
    law = alea.Joint([alea.TruncatedNormal(1.0, 0.5, 0.0, 2.0), alea.TruncatedNormal(1.5, 1.0, 1.0, 2.0)])
    pdf = lambda x, y: np.asarray(law.pdf(np.column_stack([x.ravel(), y.ravel()]))).reshape(x.shape)
    mean = gauss_box(lambda x, y: f(x, y) * pdf(x, y), lo, hi, 40)
    m2 = gauss_box(lambda x, y: f(x, y) ** 2 * pdf(x, y), lo, hi, 40)
    assert pl.mean(law, order=8) == pytest.approx(mean, rel=1e-10)
    assert pl.variance(law, order=8) == pytest.approx(m2 - mean**2, rel=1e-8)
    with pytest.raises(ValueError, match="outside"):
        pl.predict([[3.0, 1.5]])
    with pytest.raises(ValueError, match="support"):
        pl.mean([alea.Normal(1, 1), alea.Uniform(1, 2)])
    w = pl.weights(test[:4])
    assert ((w != 0).sum(axis=1) <= 4).all()
