//! The interface error density of one point (crate doc, "Interfaces"): `rho*` of a contact
//! point ([`contact_density`]) and of a perfect one ([`perfect_density`]).

pub(crate) fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The interface error density of a contact point (crate doc, "Interfaces"): the finite part of
/// the bipotential evaluated on the fields brought onto the admissible set, plus the work of
/// the correction,
/// `rho*(w, F) = mu F_n+ |w_t| + |w_n F_n| + w_t . P(F_t) + |w_t| |F_t - P(F_t)|`, with
/// `F_n+ = max(F_n, 0)` and `P` the projection onto the disk of radius `mu F_n+`. Non-negative,
/// continuous in `(w, F, mu)`, equal to `rho(w, F) = mu F_n |w_t| + w_n F_n + w_t . F_t` when
/// `w_n >= 0`, `F_n >= 0` and `|F_t| <= mu F_n`, and 0 exactly when the pair obeys the law.
pub fn contact_density(w: &[f64; 3], f: &[f64; 3], n: &[f64; 3], mu: f64) -> f64 {
    let (wn, fn_) = (dot(w, n), dot(f, n));
    let wt = [w[0] - wn * n[0], w[1] - wn * n[1], w[2] - wn * n[2]];
    let ft = [f[0] - fn_ * n[0], f[1] - fn_ * n[1], f[2] - fn_ * n[2]];
    let wtn = dot(&wt, &wt).sqrt();
    let ftn = dot(&ft, &ft).sqrt();
    let radius = mu * fn_.max(0.0);
    let (wt_pft, excess) = if ftn > radius {
        // P(F_t) = radius F_t / |F_t|; the correction's length is |F_t| - radius.
        (radius / ftn * dot(&wt, &ft), ftn - radius)
    } else {
        (dot(&wt, &ft), 0.0)
    };
    // Round-off can leave the sum a hair below 0 when the pair obeys the law.
    (radius * wtn + (wn * fn_).abs() + wt_pft + wtn * excess).max(0.0)
}

/// The interface error density of a perfect (bonded) point: the admissible jump is 0, so the
/// fields brought onto the admissible set carry no work and the correction's is `|w| |F|`
/// (`rho = w . F` is 0 there; `|w| |F| >= |w . F|`).
pub fn perfect_density(w: &[f64; 3], f: &[f64; 3]) -> f64 {
    dot(w, w).sqrt() * dot(f, f).sqrt()
}
