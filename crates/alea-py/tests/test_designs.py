"""Designs and quadrature rules: Latin hypercube strata, the first Sobol' points, grid order,
Gauss rules exact on the moments of their law, PC collocation at the Hermite roots."""

import math

import numpy as np
import pytest

import alea


def test_lhs_puts_one_point_in_each_stratum_of_each_marginal():
    law = alea.Joint([alea.Normal(0, 1), alea.Uniform(2, 3), alea.Lognormal(0, 1)])
    n = 64
    x = alea.lhs(law, n, seed=9)
    assert x.shape == (n, 3)
    u = law.to_unit(x)
    for j in range(3):
        assert sorted(np.floor(u[:, j] * n).astype(int)) == list(range(n))
    np.testing.assert_array_equal(x, alea.lhs(law, n, seed=9))
    xm = alea.lhs(law, n, seed=9, maximin=8)
    assert sorted(np.floor(law.to_unit(xm)[:, 0] * n).astype(int)) == list(range(n))


def test_sobol_first_points_and_monte_carlo_reproducible():
    u01 = [alea.Uniform(0, 1), alea.Uniform(0, 1)]
    x = alea.sobol(u01, 4)
    half = 0.5 / 2**32
    np.testing.assert_allclose(x[:3], [[0.5 + half] * 2, [0.75 + half, 0.25 + half], [0.25 + half, 0.75 + half]], atol=1e-15)
    a = alea.monte_carlo(u01, 10_000, seed=2)
    assert a.shape == (10_000, 2)
    np.testing.assert_array_equal(a, alea.monte_carlo(u01, 10_000, seed=2))
    assert abs(a.mean() - 0.5) < 4.5 * math.sqrt(1 / 12 / 20_000)


def test_grid_last_direction_fastest():
    g = alea.grid([0, 10], [1, 20], [2, 3])
    np.testing.assert_array_equal(g, [[0, 10], [0, 15], [0, 20], [1, 10], [1, 15], [1, 20]])


def test_gauss_rules_integrate_the_moments_of_their_law():
    # A 4-point Gauss-Hermite rule integrates x^k exactly up to k = 7: E[Z^4] = 3, E[Z^6] = 15.
    nodes, w = alea.quadrature(alea.Normal(0, 1), order=4)
    assert nodes.shape == (4, 1) and w.sum() == pytest.approx(1, abs=1e-14)
    z = nodes[:, 0]
    assert np.dot(w, z**4) == pytest.approx(3, rel=1e-13)
    assert np.dot(w, z**6) == pytest.approx(15, rel=1e-13)
    # Tensor and Smolyak rules on two uniforms: E[x^2 y^2] = 1/9 on [0, 1]^2.
    law = [alea.Uniform(0, 1), alea.Uniform(0, 1)]
    for nodes, w in [alea.quadrature(law, order=[2, 3]), alea.quadrature(law, level=4), alea.quadrature(law, level=2, nested=True)]:
        assert np.dot(w, nodes[:, 0] ** 2 * nodes[:, 1] ** 2) == pytest.approx(1 / 9, rel=1e-13)
    with pytest.raises(ValueError, match="exactly one"):
        alea.quadrature(law)


def test_pc_collocation_at_hermite_roots():
    # Degree 2: roots of He_3 = x^3 - 3x, i.e. 0 and +-sqrt(3), highest density first.
    x = alea.pc_collocation(alea.Normal(1.0, 2.0), 2, 3)
    np.testing.assert_allclose(np.sort(x[:, 0]), [1 - 2 * math.sqrt(3), 1, 1 + 2 * math.sqrt(3)], rtol=1e-13)
    assert x[0, 0] == pytest.approx(1.0, abs=1e-13)


@pytest.mark.parametrize(
    "call",
    [
        lambda law: alea.lhs(law, -5),
        lambda law: alea.monte_carlo(law, -1),
        lambda law: alea.sobol(law, -3),
        lambda law: alea.monte_carlo(law, 10, seed=-1),
        lambda law: alea.Normal(0.0, 1.0).sample(-2),
    ],
)
def test_negative_sizes_and_seeds_are_value_errors_naming_the_value(call):
    law = [alea.Normal(0.0, 1.0), alea.Uniform(0.0, 1.0)]
    with pytest.raises(ValueError, match="non-negative integer.*got -"):
        call(law)
