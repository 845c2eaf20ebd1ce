//! Small fixed-size vector operations shared by the 2D and 3D kernels (`D = 2` or `3`), written
//! so that they perform the same floating-point operations, in the same order, as the explicit
//! component formulas they replace (`a_0 b_0 + a_1 b_1 (+ a_2 b_2)`, left to right).

/// A node's orthonormal frame (rows: its free directions first, then the constrained ones) and
/// its number of free directions.
pub type Frame<const D: usize> = ([[f64; D]; D], usize);

/// `a . b`, summed left to right.
#[inline]
pub fn dot<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    let mut s = a[0] * b[0];
    for k in 1..D {
        s += a[k] * b[k];
    }
    s
}

/// `P v` for a `D x D` matrix `P` (row by row, [`dot`]).
#[inline]
pub fn apply<const D: usize>(p: &[[f64; D]; D], v: [f64; D]) -> [f64; D] {
    std::array::from_fn(|i| dot(p[i], v))
}

/// The `D x D` identity.
pub fn identity<const D: usize>() -> [[f64; D]; D] {
    std::array::from_fn(|i| std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 }))
}

/// The first `D` components of a 3-vector (the storage of forces and points in both dimensions).
#[inline]
pub fn head<const D: usize>(v: [f64; 3]) -> [f64; D] {
    std::array::from_fn(|i| v[i])
}
