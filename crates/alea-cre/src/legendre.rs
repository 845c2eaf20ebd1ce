//! The 1D Legendre polynomials `P_0..=P_k` and their first two derivatives (three-term
//! recurrence `(n + 1) P_(n+1) = (2 n + 1) x P_n - n P_(n-1)`, `P'_(n+1) = P'_(n-1) + (2 n + 1)
//! P_n`): the factors of the phase-2 scalar bases in 2D ([`crate::poly`]) and 3D
//! ([`crate::solid::poly`]).

/// Values of the 1D Legendre polynomials `P_0..=P_k` at `x`.
#[inline]
pub fn legendre_values(k: usize, x: f64, p: &mut [f64]) {
    p[0] = 1.0;
    if k == 0 {
        return;
    }
    p[1] = x;
    for n in 1..k {
        let nf = n as f64;
        p[n + 1] = ((2.0 * nf + 1.0) * x * p[n] - nf * p[n - 1]) / (nf + 1.0);
    }
}

/// Values, first and second derivatives of the 1D Legendre polynomials `P_0..=P_k` at `x`.
#[inline]
pub fn legendre(k: usize, x: f64, p: &mut [f64], dp: &mut [f64], ddp: &mut [f64]) {
    p[0] = 1.0;
    dp[0] = 0.0;
    ddp[0] = 0.0;
    if k == 0 {
        return;
    }
    p[1] = x;
    dp[1] = 1.0;
    ddp[1] = 0.0;
    for n in 1..k {
        let nf = n as f64;
        p[n + 1] = ((2.0 * nf + 1.0) * x * p[n] - nf * p[n - 1]) / (nf + 1.0);
        dp[n + 1] = dp[n - 1] + (2.0 * nf + 1.0) * p[n];
        ddp[n + 1] = ddp[n - 1] + (2.0 * nf + 1.0) * dp[n];
    }
}
