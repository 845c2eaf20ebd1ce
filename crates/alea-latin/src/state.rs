//! The local-stage state of a run (a leaf module: the solver takes it, a run's result gives
//! it, the study's store keeps it).

type V3 = [f64; 3];

/// The local-stage state `(W_hat, F_hat)` on both sides of every interface: everything a run
/// needs to start from (thesis 5.1.3).
#[derive(Clone, Debug, PartialEq)]
pub struct LocalState {
    /// `W_hat` per interface, `[side 1, side 2]`, per point.
    pub what: Vec<[Vec<V3>; 2]>,
    /// `F_hat` per interface, `[side 1, side 2]`, per point.
    pub fhat: Vec<[Vec<V3>; 2]>,
}

impl LocalState {
    /// Flattens to little-endian-friendly `f64`s: for each interface, `what[0], what[1],
    /// fhat[0], fhat[1]` point by point, 3 components each.
    pub fn to_vec(&self) -> Vec<f64> {
        let mut out = Vec::new();
        for (w, f) in self.what.iter().zip(&self.fhat) {
            for arr in [&w[0], &w[1], &f[0], &f[1]] {
                for p in arr.iter() {
                    out.extend_from_slice(p);
                }
            }
        }
        out
    }

    /// Inverse of [`LocalState::to_vec`] given the number of points of each interface.
    pub fn from_slice(points: &[usize], data: &[f64]) -> Option<Self> {
        let total: usize = points.iter().map(|n| 12 * n).sum();
        if data.len() != total {
            return None;
        }
        let mut it = data.chunks_exact(3).map(|c| [c[0], c[1], c[2]]);
        let mut what = Vec::new();
        let mut fhat = Vec::new();
        for &n in points {
            let mut take = || {
                (0..n)
                    .map(|_| it.next().unwrap_or([0.0; 3]))
                    .collect::<Vec<V3>>()
            };
            let (w0, w1, f0, f1) = (take(), take(), take(), take());
            what.push([w0, w1]);
            fhat.push([f0, f1]);
        }
        Some(LocalState { what, fhat })
    }
}
