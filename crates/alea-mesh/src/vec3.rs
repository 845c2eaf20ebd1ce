//! Algebra of 3-vectors `[f64; 3]`, shared by the crates above (finite elements, the solver,
//! the studies, the error estimators). The sums run in index order `0, 1, 2`, so results are
//! bit-for-bit those of the written-out formulas.

/// Dot product `a . b`.
#[inline]
pub fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Euclidean norm `|a|`.
#[inline]
pub fn norm(a: &[f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Cross product `a x b`.
#[inline]
pub fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Difference `a - b`.
#[inline]
pub fn sub(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a / |a|`, or `a` itself if it is zero.
#[inline]
pub fn normalise(a: [f64; 3]) -> [f64; 3] {
    let l = norm(&a);
    if l > 0.0 {
        [a[0] / l, a[1] / l, a[2] / l]
    } else {
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_of_the_basis() {
        let (x, y, z) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        assert_eq!(cross(&x, &y), z);
        assert_eq!(cross(&y, &z), x);
        assert_eq!(dot(&x, &y), 0.0);
        assert_eq!(norm(&[3.0, 4.0, 0.0]), 5.0);
        assert_eq!(sub(&z, &z), [0.0; 3]);
        assert_eq!(normalise([0.0, 0.0, 2.0]), z);
        assert_eq!(normalise([0.0; 3]), [0.0; 3]);
    }
}
