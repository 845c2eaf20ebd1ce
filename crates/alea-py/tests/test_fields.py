"""Random fields: the Karhunen-Loeve expansion of the exponential kernel against its closed form
(Ghanem-Spanos), mass-orthonormal modes, the transforms, and every bad call a ValueError."""

import math

import numpy as np
import pytest

import alea


def exact_exponential(a, length, count):
    """Largest eigenvalues of exp(-|x - y| / L) on [-a, a]: even roots of c cos - w sin, odd
    roots of w cos + c sin, lambda = 2 c / (w^2 + c^2) with c = 1 / L."""
    c = 1.0 / length

    def bisect(f, lo, hi):
        flo = f(lo)
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if (f(mid) > 0) == (flo > 0):
                lo = mid
            else:
                hi = mid
        return 0.5 * (lo + hi)

    lam = []
    for i in range(count):
        w = bisect(lambda w: c * math.cos(w * a) - w * math.sin(w * a), (i * math.pi + 1e-12) / a, ((i + 0.5) * math.pi - 1e-12) / a)
        lam.append(2 * c / (w * w + c * c))
        w = bisect(lambda w: w * math.cos(w * a) + c * math.sin(w * a), ((i + 0.5) * math.pi + 1e-12) / a, ((i + 1) * math.pi - 1e-12) / a)
        lam.append(2 * c / (w * w + c * c))
    return np.array(sorted(lam, reverse=True)[:count])


def line(cells, a=1.0):
    x = np.linspace(-a, a, cells + 1)
    return x, [[i, i + 1] for i in range(cells)]


def test_exponential_eigenvalues_match_the_closed_form_and_modes_are_orthonormal():
    x, cells = line(100)
    kl = alea.KarhunenLoeve(x, cells, "exponential", 1.0, 1.0, modes=20)
    exact = exact_exponential(1.0, 1.0, 20)
    assert np.max(np.abs(kl.eigenvalues - exact) / exact) < 1e-3
    # P1 mass matrix on the uniform mesh.
    h = x[1] - x[0]
    n = len(x)
    mass = np.zeros((n, n))
    for i, j in cells:
        mass[np.ix_([i, j], [i, j])] += h / 6 * np.array([[2, 1], [1, 2]])
    gram = kl.modes @ mass @ kl.modes.T
    np.testing.assert_allclose(gram, np.eye(20), atol=1e-10)
    assert kl.modes.shape == (20, n)
    assert kl.total_variance == pytest.approx(2.0, rel=1e-14)


def test_variance_fraction_and_realisations():
    x, cells = line(200, a=5.0)
    kl = alea.KarhunenLoeve(x.reshape(-1, 1), cells, "matern52", 0.05**2, 2.0, variance_fraction=0.95)
    assert kl.captured_fraction >= 0.95
    m = kl.num_modes
    xi = np.random.default_rng(3).standard_normal((4, m))
    g = kl.realise(xi, mean=0.3)
    assert g.shape == (4, len(x))
    expected = 0.3 + (xi * np.sqrt(kl.eigenvalues)) @ kl.modes
    np.testing.assert_allclose(g, expected, atol=1e-14)
    np.testing.assert_allclose(kl.realise(xi, mean=0.3, transform="lognormal"), np.exp(g), rtol=1e-14)
    b = kl.realise(xi, mean=0.3, transform="bounded", bounds=(0.1, 0.5))
    assert np.all((b > 0.1) & (b < 0.5))
    np.testing.assert_allclose(kl.realise(np.zeros(m), mean=0.3, transform="bounded", bounds=(0.1, 0.5)), 0.3, atol=1e-14)


def test_triangles_and_anisotropic_lengths():
    nodes = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0.5]], dtype=float)
    tris = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]
    kl = alea.KarhunenLoeve(nodes, tris, "squared-exponential", 2.0, [0.5, 2.0], modes=3)
    assert kl.modes.shape == (3, 5)
    assert np.all(np.diff(kl.eigenvalues) <= 0)


def test_tetrahedra_of_a_cube():
    # The unit cube in 6 Kuhn tetrahedra (paths from (0,0,0) to (1,1,1) one axis at a time).
    nodes = np.array([[i & 1, (i >> 1) & 1, (i >> 2) & 1] for i in range(8)], dtype=float)
    tets = []
    for order in ([0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]):
        mask, t = 0, [0]
        for axis in order:
            mask |= 1 << axis
            t.append(mask)
        tets.append(t)
    kl = alea.KarhunenLoeve(nodes, tets, "squared-exponential", 1.0, 5.0, modes=2)
    assert kl.modes.shape == (2, 8)
    # A nearly constant kernel on a unit volume: the first eigenvalue holds almost all of the
    # variance sigma^2 |D| = 1.
    assert abs(kl.total_variance - 1.0) < 1e-12
    assert 0.95 < kl.eigenvalues[0] <= 1.0


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(modes=3, variance_fraction=0.9), "exactly one"),
        (dict(), "exactly one"),
        (dict(modes=0), "modes"),
        (dict(variance_fraction=1.5), "variance fraction"),
        (dict(modes=3, integration="simpson"), "integration"),
    ],
)
def test_bad_truncation_settings_raise(kwargs, message):
    x, cells = line(10)
    with pytest.raises(ValueError, match=message):
        alea.KarhunenLoeve(x, cells, "exponential", 1.0, 1.0, **kwargs)


def test_bad_meshes_kernels_and_calls_raise():
    x, cells = line(10)
    with pytest.raises(ValueError, match="kernel"):
        alea.KarhunenLoeve(x, cells, "cauchy", 1.0, 1.0, modes=2)
    with pytest.raises(ValueError, match="variance"):
        alea.KarhunenLoeve(x, cells, "exponential", -1.0, 1.0, modes=2)
    with pytest.raises(ValueError, match="correlation length"):
        alea.KarhunenLoeve(x, cells, "exponential", 1.0, 0.0, modes=2)
    with pytest.raises(ValueError, match="length"):
        alea.KarhunenLoeve(x, cells, "exponential", 1.0, "long", modes=2)
    with pytest.raises(ValueError, match="node 11"):
        alea.KarhunenLoeve(x, cells + [[10, 11]], "exponential", 1.0, 1.0, modes=2)
    with pytest.raises(ValueError, match="cell 1 has 3 nodes"):
        alea.KarhunenLoeve(x, [[0, 1], [1, 2, 3]], "exponential", 1.0, 1.0, modes=2)
    with pytest.raises(ValueError, match="degenerate"):
        alea.KarhunenLoeve(np.zeros(3), [[0, 1], [1, 2]], "exponential", 1.0, 1.0, modes=2)
    with pytest.raises(ValueError, match="finite"):
        alea.KarhunenLoeve([0.0, np.nan], [[0, 1]], "exponential", 1.0, 1.0, modes=1)
    with pytest.raises(ValueError, match="variance fraction"):
        alea.KarhunenLoeve(x[:3], cells[:2], "exponential", 1.0, 0.1, variance_fraction=0.999)
    kl = alea.KarhunenLoeve(x, cells, "exponential", 1.0, 1.0, modes=2)
    with pytest.raises(ValueError, match="length 2"):
        kl.realise([0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="finite"):
        kl.realise([np.inf, 0.0])
    with pytest.raises(ValueError, match="bounds"):
        kl.realise([0.0, 0.0], transform="bounded")
    with pytest.raises(ValueError, match="upper - lower"):
        kl.realise([0.0, 0.0], transform="bounded", bounds=(1.0, 0.0))
    with pytest.raises(ValueError, match="transform"):
        kl.realise([0.0, 0.0], transform="uniform")
