//! Edge curves prepared for evaluation between their end corners: validation of each
//! [`Curve`] kind and its parametrisation `u in [0, 1]`.

use std::f64::consts::PI;

use super::block::{Curve, CurveFn};
use crate::MeshError;

/// A curve ready for evaluation between known ends (also the pieces of the composite curves
/// of [`crate::generate::shapes`]).
pub(crate) enum Prepared {
    Line([f64; 2], [f64; 2]),
    Arc {
        c: [f64; 2],
        r: f64,
        th0: f64,
        sweep: f64,
    },
    Poly {
        pts: Vec<[f64; 2]>,
        cum: Vec<f64>,
    },
    Spline {
        pts: Vec<[f64; 2]>,
        knots: Vec<f64>,
    },
    Param(CurveFn),
}

pub(super) fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
}

pub(super) fn lerp(a: [f64; 2], b: [f64; 2], u: f64) -> [f64; 2] {
    [a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1])]
}

pub(super) fn finite2(p: [f64; 2]) -> bool {
    p[0].is_finite() && p[1].is_finite()
}

impl Prepared {
    pub(super) fn new(
        curve: &Curve,
        a: [f64; 2],
        b: [f64; 2],
        what: &str,
    ) -> Result<Self, MeshError> {
        let bad = |m: String| MeshError::Invalid(format!("{what}: {m}"));
        Ok(match curve {
            Curve::Line => Prepared::Line(a, b),
            Curve::Arc {
                center,
                radius,
                ccw,
            } => {
                if !(radius.is_finite() && *radius > 0.0 && finite2(*center)) {
                    return Err(bad(format!(
                        "arc needs a finite centre and a positive radius, got {center:?}, {radius}"
                    )));
                }
                for (p, name) in [(a, "start"), (b, "end")] {
                    let d = dist(p, *center);
                    if (d - radius).abs() > 1e-7 * radius {
                        return Err(bad(format!(
                            "arc {name} corner {p:?} is at distance {d} from the centre {center:?}, not at the radius {radius}"
                        )));
                    }
                }
                let th0 = (a[1] - center[1]).atan2(a[0] - center[0]);
                let th1 = (b[1] - center[1]).atan2(b[0] - center[0]);
                let d = (th1 - th0).rem_euclid(2.0 * PI);
                if d < 1e-12 || 2.0 * PI - d < 1e-12 {
                    return Err(bad("arc ends coincide".into()));
                }
                let sweep = if *ccw { d } else { d - 2.0 * PI };
                Prepared::Arc {
                    c: *center,
                    r: *radius,
                    th0,
                    sweep,
                }
            }
            Curve::ArcThrough(m) => {
                // Circumcentre of a, m, b.
                let (ax, ay) = (a[0], a[1]);
                let (bx, by) = (m[0], m[1]);
                let (cx, cy) = (b[0], b[1]);
                let d = 2.0 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by));
                let scale = dist(a, *m).max(dist(*m, b)).max(dist(a, b));
                if !finite2(*m) || d.abs() <= 1e-12 * scale * scale {
                    return Err(bad(format!(
                        "arc through {m:?} is degenerate (the three points are collinear or coincide)"
                    )));
                }
                let sa = ax * ax + ay * ay;
                let sb = bx * bx + by * by;
                let sc = cx * cx + cy * cy;
                let ux = (sa * (by - cy) + sb * (cy - ay) + sc * (ay - by)) / d;
                let uy = (sa * (cx - bx) + sb * (ax - cx) + sc * (bx - ax)) / d;
                let c = [ux, uy];
                let r = dist(a, c);
                let ang = |p: [f64; 2]| (p[1] - uy).atan2(p[0] - ux);
                let th0 = ang(a);
                let dab = (ang(b) - th0).rem_euclid(2.0 * PI);
                let dam = (ang(*m) - th0).rem_euclid(2.0 * PI);
                let sweep = if dam < dab { dab } else { dab - 2.0 * PI };
                Prepared::Arc { c, r, th0, sweep }
            }
            Curve::Polyline(inner) => {
                let mut pts = vec![a];
                pts.extend(inner.iter().copied());
                pts.push(b);
                if pts.iter().any(|&p| !finite2(p)) {
                    return Err(bad("polyline point is not finite".into()));
                }
                let mut cum = vec![0.0];
                for w in pts.windows(2) {
                    let l = dist(w[0], w[1]);
                    if l <= 0.0 {
                        return Err(bad("polyline has two coincident consecutive points".into()));
                    }
                    cum.push(cum.last().copied().unwrap_or(0.0) + l);
                }
                Prepared::Poly { pts, cum }
            }
            Curve::Spline(inner) => {
                let mut pts = vec![a];
                pts.extend(inner.iter().copied());
                pts.push(b);
                if pts.iter().any(|&p| !finite2(p)) {
                    return Err(bad("spline point is not finite".into()));
                }
                let n = pts.len();
                let first = lerp(pts[1], pts[0], 2.0);
                let last = lerp(pts[n - 2], pts[n - 1], 2.0);
                let mut all = vec![first];
                all.extend(pts);
                all.push(last);
                let mut knots = vec![0.0];
                for w in all.windows(2) {
                    let l = dist(w[0], w[1]).sqrt();
                    if l <= 0.0 {
                        return Err(bad("spline has two coincident consecutive points".into()));
                    }
                    knots.push(knots.last().copied().unwrap_or(0.0) + l);
                }
                Prepared::Spline { pts: all, knots }
            }
            Curve::Param(f) => {
                let scale = dist(a, b).max(1e-300);
                for (u, p, name) in [(0.0, a, "start"), (1.0, b, "end")] {
                    let q = f(u);
                    if !finite2(q) || dist(p, q) > 1e-6 * scale {
                        return Err(bad(format!(
                            "parametric curve gives {q:?} at u = {u}, but the {name} corner is {p:?}"
                        )));
                    }
                }
                Prepared::Param(f.clone())
            }
        })
    }

    /// Length of a line or an arc (`None` for the other curves, whose parametrisation does not
    /// need it).
    pub(crate) fn length(&self) -> Option<f64> {
        match self {
            Prepared::Line(a, b) => Some((b[0] - a[0]).hypot(b[1] - a[1])),
            Prepared::Arc { r, sweep, .. } => Some(r * sweep.abs()),
            Prepared::Poly { .. } | Prepared::Spline { .. } | Prepared::Param(_) => None,
        }
    }

    /// The point of parameter `u in [0, 1]`.
    pub(crate) fn eval(&self, u: f64) -> [f64; 2] {
        match self {
            Prepared::Line(a, b) => lerp(*a, *b, u),
            Prepared::Arc { c, r, th0, sweep } => {
                let th = th0 + u * sweep;
                [c[0] + r * th.cos(), c[1] + r * th.sin()]
            }
            Prepared::Poly { pts, cum } => {
                let total = cum[cum.len() - 1];
                let l = (u * total).clamp(0.0, total);
                let i = cum.partition_point(|&c| c <= l).clamp(1, cum.len() - 1) - 1;
                let w = (l - cum[i]) / (cum[i + 1] - cum[i]);
                lerp(pts[i], pts[i + 1], w)
            }
            Prepared::Spline { pts, knots } => {
                // Real segments are between pts[1] .. pts[n-2] (the ends are ghosts).
                let n = pts.len();
                let (k1, kn) = (knots[1], knots[n - 2]);
                let t = (k1 + u * (kn - k1)).clamp(k1, kn);
                let i = (knots.partition_point(|&k| k <= t).clamp(2, n - 2)) - 1; // segment i..i+1
                let (t0, t1, t2, t3) = (knots[i - 1], knots[i], knots[i + 1], knots[i + 2]);
                let (p0, p1, p2, p3) = (pts[i - 1], pts[i], pts[i + 1], pts[i + 2]);
                // Barry-Goldman pyramidal evaluation.
                let mix =
                    |p: [f64; 2], q: [f64; 2], ta: f64, tb: f64| lerp(p, q, (t - ta) / (tb - ta));
                let a1 = mix(p0, p1, t0, t1);
                let a2 = mix(p1, p2, t1, t2);
                let a3 = mix(p2, p3, t2, t3);
                let b1 = mix(a1, a2, t0, t2);
                let b2 = mix(a2, a3, t1, t3);
                mix(b1, b2, t1, t2)
            }
            Prepared::Param(f) => f(u),
        }
    }
}
