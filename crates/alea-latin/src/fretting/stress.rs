//! The stress-based fretting quantities of a cycle (module doc of [`crate::fretting`]): the
//! tensile stress parallel to the surface `sigma_T` (for Ruiz's F2), the Smith-Watson-Topper
//! and the Fatemi-Socie parameters on critical planes, at the surface or regularised by a critical
//! distance.

use alea_fem::{Model, PointLocator, post};
use alea_mesh::vec3::dot;

use super::{FrettingError, V3};
use crate::{LatinSolver, RunResult};

type M3 = [[f64; 3]; 3];

/// Where the stresses of a stress-based quantity are taken.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Regularisation {
    /// The nodal (averaged) stresses at the interface node: mesh-dependent at contact edges.
    Surface,
    /// Point method: the stress at depth `L` below the surface point (2D only).
    Point(f64),
    /// Line method: the stress and strain tensors averaged over the depth `[0, L]` (2D only).
    Line(f64),
}

impl Regularisation {
    /// The critical distance, if any.
    pub fn distance(self) -> Option<f64> {
        match self {
            Regularisation::Surface => None,
            Regularisation::Point(l) | Regularisation::Line(l) => Some(l),
        }
    }

    /// Depths and weights of the averaging (one depth for the point method).
    fn depths(self) -> Vec<(f64, f64)> {
        match self {
            Regularisation::Surface => vec![(0.0, 1.0)],
            Regularisation::Point(l) => vec![(l, 1.0)],
            Regularisation::Line(l) => {
                // Composite Simpson on 16 intervals, weights normalised to a mean.
                let m = 16;
                (0..=m)
                    .map(|j| {
                        let w = if j == 0 || j == m {
                            1.0
                        } else if j % 2 == 1 {
                            4.0
                        } else {
                            2.0
                        };
                        (l * j as f64 / m as f64, w / (3.0 * m as f64))
                    })
                    .collect()
            }
        }
    }
}

/// The stress-based fields of a cycle, per interface point.
#[derive(Clone, Debug)]
pub struct StressCycle {
    /// `sigma_T = max(0, max_k t.sigma_k.t)`: the largest tensile stress parallel to the
    /// surface over the cycle.
    pub sigma_t: Vec<f64>,
    /// Smith-Watson-Topper parameter of the critical plane (stress units).
    pub swt: Vec<f64>,
    /// Unit normal of the critical plane.
    pub swt_normal: Vec<V3>,
    /// Fatemi-Socie: the shear strain range `Delta gamma / 2` on the plane of the largest one
    /// (engineering shear, so the range of the tensor component `t.eps.n`) ([`fs_of_stresses`]).
    pub fs_shear: Vec<f64>,
    /// Fatemi-Socie: the largest normal stress over the cycle on that plane.
    pub fs_normal: Vec<f64>,
    /// False at the points whose probe at the critical distance leaves the substructure (at
    /// the ends of an interface, near a corner of the body): their values are 0 and not
    /// defined. All true at the surface.
    pub probed: Vec<bool>,
}

fn tensor(s: &[f64; 6]) -> M3 {
    // [xx, yy, zz, yz, xz, xy]
    [[s[0], s[5], s[4]], [s[5], s[1], s[3]], [s[4], s[3], s[2]]]
}

/// Isotropic compliance: `eps = ((1 + nu) sigma - nu tr(sigma) I) / E`.
fn strain(s: &M3, young: f64, nu: f64) -> M3 {
    let tr = s[0][0] + s[1][1] + s[2][2];
    let mut e = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            e[i][j] = ((1.0 + nu) * s[i][j] - if i == j { nu * tr } else { 0.0 }) / young;
        }
    }
    e
}

fn quad(t: &M3, n: &V3) -> f64 {
    let mut v = 0.0;
    for i in 0..3 {
        for j in 0..3 {
            v += n[i] * t[i][j] * n[j];
        }
    }
    v
}

/// The plane normals scanned: 2D `(cos theta, sin theta)`, `theta = pi j / n`; 3D `n`
/// Fibonacci directions on the half sphere `z >= 0`.
pub fn plane_normals(dim: usize, n: usize) -> Vec<V3> {
    let n = n.max(1);
    if dim == 2 {
        return (0..n)
            .map(|j| {
                let t = std::f64::consts::PI * j as f64 / n as f64;
                [t.cos(), t.sin(), 0.0]
            })
            .collect();
    }
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|j| {
            let z = (j as f64 + 0.5) / n as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden * j as f64;
            [r * phi.cos(), r * phi.sin(), z]
        })
        .collect()
}

/// Largest normal stress on the planes containing the surface normal `n`: 2D the in-plane
/// tangent's `t.sigma.t`, 3D the largest eigenvalue of the tangential 2x2 block.
fn parallel_stress(s: &M3, n: &V3, dim: usize) -> f64 {
    if dim == 2 {
        return quad(s, &[-n[1], n[0], 0.0]);
    }
    let (t1, t2) = tangent_basis(n);
    let (a11, a22) = (quad(s, &t1), quad(s, &t2));
    let a12 = bilinear(&t1, s, &t2);
    0.5 * (a11 + a22) + (0.25 * (a11 - a22).powi(2) + a12 * a12).sqrt()
}

/// A tangent basis `(t1, t2)` of the plane normal to the unit vector `n`.
fn tangent_basis(n: &V3) -> (V3, V3) {
    let a = if n[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let an = dot(&a, n);
    let t1 = {
        let v = [a[0] - an * n[0], a[1] - an * n[1], a[2] - an * n[2]];
        let l = dot(&v, &v).sqrt();
        [v[0] / l, v[1] / l, v[2] / l]
    };
    let t2 = [
        n[1] * t1[2] - n[2] * t1[1],
        n[2] * t1[0] - n[0] * t1[2],
        n[0] * t1[1] - n[1] * t1[0],
    ];
    (t1, t2)
}

/// `a . t . b`.
fn bilinear(a: &V3, t: &M3, b: &V3) -> f64 {
    let mut v = 0.0;
    for i in 0..3 {
        for j in 0..3 {
            v += a[i] * t[i][j] * b[j];
        }
    }
    v
}

/// Stress and strain tensors of every step at every point (`[point][step]`); `None` where a
/// probe left the mesh.
type Samples = Vec<Option<Vec<(M3, M3)>>>;

fn fem_error(sub: &str) -> impl Fn(alea_fem::FemError) -> FrettingError + '_ {
    move |source| FrettingError::Fem {
        sub: sub.to_string(),
        source,
    }
}

/// The samples at the interface nodes from the nodal (averaged) stresses.
fn surface_samples(
    model: &Model,
    sub: &str,
    nodes: &[usize],
    us: &[&[f64]],
) -> Result<Samples, FrettingError> {
    let mut cell_of = vec![usize::MAX; model.mesh.num_nodes()];
    for (c, _, cn) in model.mesh.cells() {
        for &n in cn {
            if cell_of[n] == usize::MAX {
                cell_of[n] = c;
            }
        }
    }
    let nodal: Vec<Vec<[f64; 6]>> = us
        .iter()
        .map(|u| post::nodal_stresses(model, u))
        .collect::<Result<_, _>>()
        .map_err(fem_error(sub))?;
    nodes
        .iter()
        .map(|&node| {
            let mat = model
                .material(cell_of.get(node).copied().unwrap_or(0))
                .map_err(fem_error(sub))?;
            Ok(Some(
                nodal
                    .iter()
                    .map(|s| {
                        let t = tensor(&s[node]);
                        (t, strain(&t, mat.young, mat.poisson))
                    })
                    .collect(),
            ))
        })
        .collect()
}

/// The samples at (point method) or averaged over (line method) the depths below the points.
fn depth_samples(
    model: &Model,
    sub: &str,
    probes: &[(V3, V3)],
    us: &[&[f64]],
    reg: Regularisation,
) -> Result<Samples, FrettingError> {
    let locator = PointLocator::new(&model.mesh).map_err(fem_error(sub))?;
    let depths = reg.depths();
    let tol = 1e-3 * reg.distance().unwrap_or(0.0);
    probes
        .iter()
        .map(|(x, inward)| {
            let mut acc = vec![([[0.0; 3]; 3], [[0.0; 3]; 3]); us.len()];
            for &(d, w) in &depths {
                let at = [
                    x[0] + d * inward[0],
                    x[1] + d * inward[1],
                    x[2] + d * inward[2],
                ];
                let Some(loc) = locator.locate_nearest(at, tol) else {
                    return Ok(None);
                };
                let mat = model.material(loc.cell).map_err(fem_error(sub))?;
                for (k, u) in us.iter().enumerate() {
                    let s = post::stress_at(model, loc.cell, u, loc.xi).map_err(fem_error(sub))?;
                    let t = tensor(&s);
                    let e = strain(&t, mat.young, mat.poisson);
                    for i in 0..3 {
                        for j in 0..3 {
                            acc[k].0[i][j] += w * t[i][j];
                            acc[k].1[i][j] += w * e[i][j];
                        }
                    }
                }
            }
            Ok(Some(acc))
        })
        .collect()
}

/// `sigma_T` and SWT over the cycle `cycle` (one run result per step) at the points of
/// interface `iface`, on the substructure of side `side` (0: side 1, 1: side 2), with
/// `planes` critical planes scanned.
///
/// # Errors
/// [`FrettingError::EmptyCycle`], [`FrettingError::Invalid`] (bad index or side, a critical
/// distance in 3D), [`FrettingError::CriticalDistance`], [`FrettingError::Outside`] (no point
/// has its probe inside the substructure), [`FrettingError::Fem`].
pub fn stress_cycle(
    solver: &LatinSolver,
    iface: usize,
    side: usize,
    cycle: &[&RunResult],
    reg: Regularisation,
    planes: usize,
) -> Result<StressCycle, FrettingError> {
    let first = *cycle.first().ok_or(FrettingError::EmptyCycle)?;
    if side > 1 {
        return Err(FrettingError::Invalid(format!("side {side}: 0 or 1")));
    }
    let it = first
        .interfaces
        .get(iface)
        .ok_or_else(|| FrettingError::Invalid(format!("no interface {iface}")))?;
    if it.law == "perfect" {
        return Err(FrettingError::PerfectInterface(it.name.clone()));
    }
    let s = it.subs[side];
    let sub = solver.sub_name(s);
    let model = first.scaled_model(solver.model(s), s);
    let dim = model.mesh.dim;
    if cycle
        .iter()
        .any(|r| r.displacements.get(s).map(Vec::len) != Some(model.mesh.num_nodes() * dim))
    {
        return Err(FrettingError::Mismatch(it.name.clone()));
    }
    let us: Vec<&[f64]> = cycle
        .iter()
        .map(|r| r.displacements[s].as_slice())
        .collect();
    let samples = match reg.distance() {
        None => surface_samples(&model, sub, &it.nodes[side], &us)?,
        Some(l) => {
            if !(l.is_finite() && l > 0.0) {
                return Err(FrettingError::CriticalDistance(l));
            }
            if dim != 2 {
                return Err(FrettingError::Invalid(
                    "a critical distance is implemented in 2D only".into(),
                ));
            }
            let sign = if side == 0 { -1.0 } else { 1.0 };
            let probes: Vec<(V3, V3)> = it
                .points
                .iter()
                .map(|p| (p.x, p.normal.map(|v| sign * v)))
                .collect();
            depth_samples(&model, sub, &probes, &us, reg)?
        }
    };
    let normals = plane_normals(dim, planes);
    if !samples.iter().any(Option::is_some) {
        let p = &it.points[0];
        return Err(FrettingError::Outside {
            sub: sub.to_string(),
            at: p.x,
        });
    }
    let mut out = StressCycle {
        sigma_t: Vec::with_capacity(samples.len()),
        swt: Vec::with_capacity(samples.len()),
        swt_normal: Vec::with_capacity(samples.len()),
        fs_shear: Vec::with_capacity(samples.len()),
        fs_normal: Vec::with_capacity(samples.len()),
        probed: samples.iter().map(Option::is_some).collect(),
    };
    for (p, steps) in samples.iter().enumerate() {
        let Some(steps) = steps else {
            out.sigma_t.push(0.0);
            out.swt.push(0.0);
            out.swt_normal.push(normals[0]);
            out.fs_shear.push(0.0);
            out.fs_normal.push(0.0);
            continue;
        };
        let n = it.points[p].normal;
        let st = steps
            .iter()
            .map(|(s, _)| parallel_stress(s, &n, dim))
            .fold(f64::NEG_INFINITY, f64::max);
        out.sigma_t.push(st.max(0.0));
        let (swt, normal) = swt_of(steps, &normals);
        out.swt.push(swt);
        out.swt_normal.push(normal);
        let (shear, normal_stress, _) = fs_of(steps, &normals, dim);
        out.fs_shear.push(shear);
        out.fs_normal.push(normal_stress);
    }
    Ok(out)
}

/// SWT of one point's steps on the critical plane among `normals`, and that plane's normal.
pub(crate) fn swt_of(steps: &[(M3, M3)], normals: &[V3]) -> (f64, V3) {
    let mut best = (0.0, normals.first().copied().unwrap_or([1.0, 0.0, 0.0]));
    for nv in normals {
        let (mut smax, mut emax, mut emin) = (f64::NEG_INFINITY, f64::NEG_INFINITY, f64::INFINITY);
        for (s, e) in steps {
            smax = smax.max(quad(s, nv));
            let en = quad(e, nv);
            emax = emax.max(en);
            emin = emin.min(en);
        }
        let v = smax.max(0.0) * 0.5 * (emax - emin);
        if v > best.0 {
            best = (v, *nv);
        }
    }
    best
}

/// SWT of a sequence of plane stress-strain states given as `[xx, yy, zz, yz, xz, xy]`
/// stresses of an isotropic material (`young`, `nu`), on the critical plane among `normals`:
/// the same formula as [`stress_cycle`], for closed-form fields.
pub fn swt_of_stresses(stresses: &[[f64; 6]], young: f64, nu: f64, normals: &[V3]) -> (f64, V3) {
    swt_of(&elastic_states(stresses, young, nu), normals)
}

/// The stress and strain tensors of stresses `[xx, yy, zz, yz, xz, xy]` of an isotropic
/// material (`young`, `nu`).
fn elastic_states(stresses: &[[f64; 6]], young: f64, nu: f64) -> Vec<(M3, M3)> {
    stresses
        .iter()
        .map(|s| {
            let t = tensor(s);
            (t, strain(&t, young, nu))
        })
        .collect()
}

/// Shear directions scanned in each plane in 3D (every 15 degrees over a half turn).
const SHEAR_DIRECTIONS: usize = 12;

/// Fatemi-Socie's critical plane of one point's steps among `normals` (Fatemi & Socie 1988):
/// the plane of the largest shear strain range `Delta gamma / 2 = max_t (max_k t.eps_k.n -
/// min_k t.eps_k.n)` over the shear directions `t` of the plane (2D: the in-plane tangent
/// `(-n_y, n_x)`; 3D: [`SHEAR_DIRECTIONS`] directions), and on it the largest normal stress
/// `max_k n.sigma_k.n`. Planes whose range is within `1e-9` of the largest tie; the tie goes to
/// the larger normal stress (the more damaging plane). Returns `(Delta gamma / 2,
/// sigma_n,max, n)`.
pub(crate) fn fs_of(steps: &[(M3, M3)], normals: &[V3], dim: usize) -> (f64, f64, V3) {
    let directions = |n: &V3| -> Vec<V3> {
        if dim == 2 {
            return vec![[-n[1], n[0], 0.0]];
        }
        let (t1, t2) = tangent_basis(n);
        (0..SHEAR_DIRECTIONS)
            .map(|j| {
                let phi = std::f64::consts::PI * j as f64 / SHEAR_DIRECTIONS as f64;
                let (c, s) = (phi.cos(), phi.sin());
                [0, 1, 2].map(|i| c * t1[i] + s * t2[i])
            })
            .collect()
    };
    let planes: Vec<(f64, f64, V3)> = normals
        .iter()
        .map(|n| {
            let range = directions(n)
                .iter()
                .map(|t| {
                    let (lo, hi) = steps.iter().fold(
                        (f64::INFINITY, f64::NEG_INFINITY),
                        |(lo, hi), (_, e)| {
                            let g = bilinear(t, e, n);
                            (lo.min(g), hi.max(g))
                        },
                    );
                    hi - lo
                })
                .fold(0.0, f64::max);
            let sn = steps
                .iter()
                .map(|(s, _)| quad(s, n))
                .fold(f64::NEG_INFINITY, f64::max);
            (range, sn, *n)
        })
        .collect();
    let largest = planes.iter().map(|p| p.0).fold(0.0, f64::max);
    planes
        .into_iter()
        .filter(|p| p.0 >= largest * (1.0 - 1e-9))
        .fold(None, |best: Option<(f64, f64, V3)>, p| match best {
            Some(b) if b.1 >= p.1 => Some(b),
            _ => Some(p),
        })
        .unwrap_or((
            0.0,
            0.0,
            normals.first().copied().unwrap_or([1.0, 0.0, 0.0]),
        ))
}

/// Fatemi-Socie's parameter from the shear strain range and normal stress of its plane
/// ([`StressCycle::fs_shear`], [`StressCycle::fs_normal`]), with the material's normal-stress
/// sensitivity `k` and yield stress `sigma_y`: `Delta gamma / 2 (1 + k sigma_n,max / sigma_y)`,
/// the factor floored at 0 (a normal stress that closes the cracks faster than `-sigma_y / k`
/// does not make the parameter negative).
pub fn fatemi_socie(shear: f64, normal: f64, k: f64, yield_stress: f64) -> f64 {
    shear * (1.0 + k * normal / yield_stress).max(0.0)
}

/// [`fs_of`] of a sequence of stresses `[xx, yy, zz, yz, xz, xy]` of an isotropic material
/// (`young`, `nu`), for closed-form fields: `(Delta gamma / 2, sigma_n,max, n)`.
pub fn fs_of_stresses(
    stresses: &[[f64; 6]],
    young: f64,
    nu: f64,
    normals: &[V3],
    dim: usize,
) -> (f64, f64, V3) {
    fs_of(&elastic_states(stresses, young, nu), normals, dim)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uniaxial `sigma_xx` between `+s1` and `-s2`: the critical plane is normal to `x` and
    /// `SWT = s1 (s1 + s2) / (2 E)` (`eps_xx = sigma_xx / E`).
    #[test]
    fn swt_of_a_uniaxial_cycle() {
        let (e, nu, s1, s2) = (200e3, 0.3, 100.0, 50.0);
        let states = [
            [s1, 0.0, 0.0, 0.0, 0.0, 0.0],
            [-s2, 0.0, 0.0, 0.0, 0.0, 0.0],
        ];
        for dim in [2, 3] {
            let normals = plane_normals(dim, if dim == 2 { 180 } else { 4000 });
            assert!(normals.iter().all(|n| (dot(n, n) - 1.0).abs() < 1e-12));
            let (swt, n) = swt_of_stresses(&states, e, nu, &normals);
            let want = s1 * (s1 + s2) / (2.0 * e);
            // 2D scans x exactly; the 3D set comes within a few degrees of it.
            let tol = if dim == 2 { 1e-12 } else { 1e-2 };
            assert!((swt - want).abs() <= tol * want, "{dim}D: {swt} vs {want}");
            assert!(n[0].abs() > 0.99, "{n:?}");
        }
    }

    /// Pure shear `tau` reversed: the critical planes are at 45 degrees, with `sigma_n = tau`,
    /// `Delta eps_n = 2 tau (1 + nu) / E`, so `SWT = tau^2 (1 + nu) / E`.
    #[test]
    fn swt_of_reversed_shear() {
        let (e, nu, tau) = (200e3, 0.3, 80.0);
        let states = [
            [0.0, 0.0, 0.0, 0.0, 0.0, tau],
            [0.0, 0.0, 0.0, 0.0, 0.0, -tau],
        ];
        let (swt, n) = swt_of_stresses(&states, e, nu, &plane_normals(2, 180));
        let want = tau * tau * (1.0 + nu) / e;
        assert!((swt - want).abs() < 1e-12 * want, "{swt} vs {want}");
        assert!((n[0].abs() - n[1].abs()).abs() < 1e-9, "{n:?}");
    }

    /// The tensile stress parallel to a surface: 2D the tangent's, 3D the largest in the
    /// tangent plane.
    #[test]
    fn parallel_stress_in_2d_and_3d() {
        let s = tensor(&[10.0, -5.0, 3.0, 0.0, 0.0, 0.0]);
        assert_eq!(parallel_stress(&s, &[0.0, 1.0, 0.0], 2), 10.0);
        assert!((parallel_stress(&s, &[0.0, 1.0, 0.0], 3) - 10.0).abs() < 1e-12);
        assert!((parallel_stress(&s, &[1.0, 0.0, 0.0], 3) - 3.0).abs() < 1e-12);
    }

    /// Fatemi-Socie under reversed shear `tau` (2D): the planes of largest shear strain range
    /// are normal to `x` and `y`, with `Delta gamma / 2 = tau / G = 2 tau (1 + nu) / E` and no
    /// normal stress; under a uniaxial cycle `+s1 / -s2` the planes at 45 degrees, with `Delta
    /// gamma / 2 = (1 + nu) (s1 + s2) / (2 E)` and `sigma_n,max = s1 / 2` (2D exactly on the
    /// one-degree scan, 3D within the Fibonacci set's few degrees).
    #[test]
    fn fatemi_socie_of_reversed_shear_and_of_a_uniaxial_cycle() {
        let (e, nu, tau) = (200e3, 0.3, 80.0);
        let shear = [
            [0.0, 0.0, 0.0, 0.0, 0.0, tau],
            [0.0, 0.0, 0.0, 0.0, 0.0, -tau],
        ];
        let (g, sn, n) = fs_of_stresses(&shear, e, nu, &plane_normals(2, 180), 2);
        let want = 2.0 * tau * (1.0 + nu) / e;
        assert!((g - want).abs() < 1e-12 * want, "{g} vs {want}");
        assert!(sn.abs() < 1e-12 * tau, "{sn}");
        assert!(
            n[0].abs() > 1.0 - 1e-12 || n[1].abs() > 1.0 - 1e-12,
            "{n:?}"
        );
        let (s1, s2) = (100.0, 50.0);
        let uni = [
            [s1, 0.0, 0.0, 0.0, 0.0, 0.0],
            [-s2, 0.0, 0.0, 0.0, 0.0, 0.0],
        ];
        let want = (1.0 + nu) * (s1 + s2) / (2.0 * e);
        for (dim, planes, tol) in [(2, 180, 1e-12), (3, 4000, 2e-3)] {
            let (g, sn, n) = fs_of_stresses(&uni, e, nu, &plane_normals(dim, planes), dim);
            assert!((g - want).abs() <= tol * want, "{dim}D: {g} vs {want}");
            assert!((sn - s1 / 2.0).abs() <= 20.0 * tol * s1, "{dim}D: {sn}");
            assert!((n[0].abs() - 0.5f64.sqrt()).abs() < 0.05, "{dim}D: {n:?}");
        }
        // The parameter: the normal stress raises it by k sigma_n / sigma_y; a compressive one
        // lowers it, not below 0.
        assert!((fatemi_socie(2.0, 50.0, 0.5, 250.0) - 2.0 * 1.1).abs() < 1e-15);
        assert_eq!(fatemi_socie(2.0, -1000.0, 0.5, 250.0), 0.0);
    }
}
