//! EET phase 2 with everything that does not depend on the run computed once per cell
//! (multiresolution estimator, [`crate::DomainEstimator`]).
//!
//! The local problem of cell `E` ([`super::phase2`]) with a Young's factor `alpha` reads
//! `alpha K0 v = l`, `K0 = int eps(phi)^T D0 eps(phi)` in the degree-`p + k` space, and
//! `theta_E^2 / t = alpha int (eps(v) - eps_h)^T D0 (eps(v) - eps_h)` on the same quadrature
//! rule. Cached per cell (reference materials `D0`):
//!
//! - the Cholesky factor `K0 = L L^T` (packed lower triangle);
//! - `Z = L^-1 G`, `G = int eps(phi_j)^T D0 B` (`B` the FE strain operator, `eps_h = B u_e`);
//! - `R = Ke0 - Z^T Z` (packed), `Ke0 = int B^T D0 B` the FE stiffness on the phase-2 rule,
//!   integrated pointwise as `int r^T D0 r` with `r = B - eps(phi) K0^-1 G` the part of the FE
//!   strain modes outside the local space (the difference `Ke0 - Z^T Z` of two nearly equal
//!   energies would lose the digits of `theta_E` on cells where the error is small).
//!
//! Per run, with `y = L^-1 l`: `v = L^-T y / alpha` and
//!
//! `theta_E^2 / t = alpha (|y / alpha - Z u_e|^2 + u_e^T R u_e)`,
//! `||u_h||^2_{K,E} / t = alpha (|Z u_e|^2 + u_e^T R u_e)`
//!
//! (expand `|L^T v - Z u_e|^2 = v^T K0 v - 2 v^T G u_e + u_e^T Z^T Z u_e`): the same quantities as
//! the direct path to round-off (`R` is the energy of the part of `eps_h` outside the local space,
//! zero for affine cells).
//!
//! `Z` and `R` vanish on the rigid modes of the cell, so they are stored on `2 nn - 3`
//! deformation coordinates `q` of `u_e` (`deformation`: node displacements relative to node 0,
//! the rotation measured along edge `x_0 x_1` removed): `Z u_e = Z_q q`, `u_e^T R u_e = q^T R_q q`
//! (27 x 5 and 15 numbers for a Q4 cell instead of 27 x 8 and 36), which also keeps a large rigid
//! motion of a floating substructure out of the products.
//!
//! The load vector `l`: the polynomial densities of the edges are integrated with the Gauss rule
//! exact for them (`ceil((p + k + p_edge + 1) / 2)` points: 3 for Q4/T3); edges carrying
//! prescribed-traction data (arbitrary functions) keep the direct path's `p + k + 4` points. An
//! affine body force ([`crate::AffineBody`]) uses the moments `int psi`, `int x psi`, `int y psi`
//! of the scalar basis functions `psi` (cached on first use), a general body force the phase-2
//! quadrature. The balance defect (force and moment resultants of the element loads over the
//! sum of their absolute values) uses the same rules; the absolute values of an affine body force
//! are integrated with the cell's vertex rule (a normalisation only).

use std::sync::OnceLock;

use alea_fem::reference::MAX_NODES;
use alea_fem::{Model, kinematics::point_geometry};
use alea_mesh::CellType;
use rayon::prelude::*;

use super::phase1::EdgeTractions;
use super::phase2::{ElementResult, ElementStress, Phase2Rules, add_resultant, add_stiffness};
use crate::CreError;
use crate::contribution::balance_defect;
use crate::data::{AffineBody, VectorField};
use crate::fe::{check_jacobian, gauss01, hooke, mul3};
use crate::poly::{PolyPoint, PolySpace};
use crate::topology::cell_is_curved;

/// Index of the packed lower triangle entry `(i, j)`, `j <= i`.
#[inline]
fn tri(i: usize, j: usize) -> usize {
    i * (i + 1) / 2 + j
}

/// Run-independent data of one cell.
#[derive(Clone, Debug)]
struct CellData {
    space: PolySpace,
    /// Offset of the cell's `L` (packed, `n (n + 1) / 2`), `Z` (`n x 2 nn`, row-major) and `R`
    /// (packed, `2 nn (2 nn + 1) / 2`) in the shared buffer.
    offset: usize,
    /// Number of deformation coordinates `2 nn - 3`.
    ndef: usize,
    /// The cell has a curved edge (richer phase-2 rule).
    curved: bool,
}

/// The moments an affine body force needs, per cell (cached on first use).
#[derive(Clone, Debug)]
struct BodyMoments {
    /// Per cell: `[int psi_s, int x psi_s, int y psi_s]` for every scalar function `s`,
    /// concatenated (`3 num_scalars` values from `offsets[c]`).
    values: Vec<f64>,
    offsets: Vec<usize>,
    /// Per cell: `int 1, int x, int y, int x^2, int x y, int y^2`.
    geometry: Vec<[f64; 6]>,
}

/// Scratch buffers of one thread.
#[derive(Default)]
pub(crate) struct Scratch {
    l: Vec<f64>,
    psi: Vec<f64>,
    ue: Vec<f64>,
    zu: Vec<f64>,
}

/// Phase-2 cache of one 2D domain.
#[derive(Debug)]
pub(crate) struct Phase2Cache {
    rules: [Phase2Rules; 2],
    /// Gauss rules on `[0, 1]` by number of points (index 0 empty).
    line_rules: Vec<Vec<(f64, f64)>>,
    cells: Vec<CellData>,
    data: Vec<f64>,
    body: OnceLock<BodyMoments>,
}

impl Phase2Cache {
    /// Builds the cache of `model` (reference materials) with local degree `order + extra`.
    pub fn new(model: &Model, extra_degree: usize) -> Result<Self, CreError> {
        let mesh = &model.mesh;
        let rules = [
            Phase2Rules::new(1 + extra_degree),
            Phase2Rules::new(2 + extra_degree),
        ];
        let per: Vec<(PolySpace, Vec<f64>)> = (0..mesh.num_cells())
            .into_par_iter()
            .map(|c| cell_data(model, c, &rules))
            .collect::<Result<_, _>>()?;
        let mut cells = Vec::with_capacity(per.len());
        let mut data = Vec::with_capacity(per.iter().map(|p| p.1.len()).sum());
        for (c, (space, values)) in per.into_iter().enumerate() {
            cells.push(CellData {
                space,
                offset: data.len(),
                ndef: 2 * mesh.cell_nodes(c).len() - 3,
                curved: cell_is_curved(mesh, c),
            });
            data.extend_from_slice(&values);
        }
        let line_rules = (0..=2 + extra_degree + 4)
            .map(|n| if n == 0 { Vec::new() } else { gauss01(n) })
            .collect();
        Ok(Phase2Cache {
            rules,
            line_rules,
            cells,
            data,
            body: OnceLock::new(),
        })
    }

    /// Bytes held by the cache (affine-body moments included once computed).
    pub fn bytes(&self) -> usize {
        let body = self.body.get().map_or(0, |b| {
            8 * (b.values.len() + b.offsets.len()) + std::mem::size_of_val(&b.geometry[..])
        });
        8 * self.data.len() + std::mem::size_of_val(&self.cells[..]) + body
    }

    fn rule(&self, kind: CellType) -> &Phase2Rules {
        &self.rules[kind.order().clamp(1, 2) - 1]
    }

    fn body_moments(&self, model: &Model) -> &BodyMoments {
        self.body
            .get_or_init(|| body_moments(model, &self.cells, &self.rules))
    }

    /// Solves the local problem of cell `c` for the run (`model`: reference materials, `alpha`
    /// the Young's factor, `u` the FE displacement) and evaluates its contribution.
    #[allow(clippy::too_many_arguments)]
    pub fn element(
        &self,
        model: &Model,
        c: usize,
        u: &[f64],
        alpha: f64,
        body: Option<&VectorField>,
        affine: Option<&AffineBody>,
        tr: &EdgeTractions,
        scratch: &mut Scratch,
    ) -> Result<ElementResult, CreError> {
        let mesh = &model.mesh;
        let kind = mesh.cell_type(c);
        let cd = &self.cells[c];
        let space = &cd.space;
        let n = space.len();
        let m = cd.ndef;
        let rule = self.rule(kind);
        let degree = rule.degree;
        let th = model.analysis.thickness();
        let Scratch { l, psi, ue, zu } = scratch;
        l.clear();
        l.resize(n, 0.0);
        psi.resize(space.num_scalars(), 0.0);
        let ctr = space.center;
        let mut res = [0.0; 3];
        let mut abs_sum = 0.0;
        // Edge loads.
        for &(e, eta) in &tr.topo.cell_edges[c] {
            let d = &tr.density[e];
            let has_data = !d.data.is_empty();
            if !has_data && d.lin.iter().flatten().all(|v| *v == 0.0) {
                continue;
            }
            let edge = &tr.topo.edges[e];
            let npts = if has_data {
                degree + 4
            } else if edge.curved {
                // `L P(s) . v(x(s))`: degree `2 + 2 degree` in `s`.
                degree + 2
            } else {
                let p_edge = 1 + edge.mid.is_some() as usize;
                (degree + p_edge + 2) / 2
            };
            for &(s, w) in &self.line_rules[npts] {
                let ep = edge.point(s);
                let x = ep.x;
                let t = if has_data {
                    tr.traction_at(e, s, &ep)
                } else {
                    let p = tr.polynomial(e, s);
                    if edge.curved {
                        let r = edge.chord() / ep.jac;
                        [r * p[0], r * p[1]]
                    } else {
                        p
                    }
                };
                let t = [eta * t[0], eta * t[1]];
                let wl = w * ep.jac;
                space.scalars([x[0], x[1]], psi);
                let wt = [wl * t[0], wl * t[1]];
                space.accumulate(l, |comp, sc| wt[comp] * psi[sc]);
                add_resultant(&mut res, &mut abs_sum, wl, x, ctr, [t[0], t[1]]);
            }
        }
        // Body force.
        if let Some(a) = affine {
            let bm = self.body_moments(model);
            let mom = &bm.values[bm.offsets[c]..bm.offsets[c + 1]];
            let ns = space.num_scalars();
            let (m0, rest) = mom.split_at(ns);
            let (mx, my) = rest.split_at(ns);
            let (b0, g) = (a.constant, a.gradient);
            space.accumulate(l, |comp, sc| {
                b0[comp] * m0[sc] + g[comp][0] * mx[sc] + g[comp][1] * my[sc]
            });
            // Resultants from the geometric moments: int b and int (x - c) x b.
            let [a0, ax, ay, axx, axy, ayy] = bm.geometry[c];
            let fb = |comp: usize| b0[comp] * a0 + g[comp][0] * ax + g[comp][1] * ay;
            // int x b_comp and int y b_comp.
            let xb = |comp: usize| b0[comp] * ax + g[comp][0] * axx + g[comp][1] * axy;
            let yb = |comp: usize| b0[comp] * ay + g[comp][0] * axy + g[comp][1] * ayy;
            res[0] += fb(0);
            res[1] += fb(1);
            res[2] += (xb(1) - ctr[0] * fb(1)) - (yb(0) - ctr[1] * fb(0));
            // Vertex rule for int |b_x| + |b_y| (scale only).
            let nodes = mesh.cell_nodes(c);
            let nv = kind.num_corners().max(1);
            let mut sum = 0.0;
            for &nd in &nodes[..nv] {
                let b = a.eval(mesh.coords[nd]);
                sum += b[0].abs() + b[1].abs();
            }
            abs_sum += a0 * sum / nv as f64;
        } else if let Some(b) = body {
            let coords = model.cell_coords(c);
            let q = rule.volume(kind, cd.curved);
            for (xi, w) in q.points.iter().zip(&q.weights) {
                let g = point_geometry(kind, &coords, *xi);
                let wd = w * g.det;
                let f = b(g.x);
                space.scalars([g.x[0], g.x[1]], psi);
                let wf = [wd * f[0], wd * f[1]];
                space.accumulate(l, |comp, sc| wf[comp] * psi[sc]);
                add_resultant(&mut res, &mut abs_sum, wd, g.x, ctr, [f[0], f[1]]);
            }
        }
        let h = space.scale;
        let balance_defect = balance_defect(&res[..2], &res[2..], h, abs_sum);
        // y = L^-1 l, in place.
        let lf = &self.data[cd.offset..cd.offset + n * (n + 1) / 2];
        for i in 0..n {
            let row = &lf[tri(i, 0)..tri(i, 0) + i + 1];
            let s: f64 = row[..i].iter().zip(&l[..i]).map(|(a, b)| a * b).sum();
            l[i] = (l[i] - s) / row[i];
        }
        let zoff = cd.offset + n * (n + 1) / 2;
        let z = &self.data[zoff..zoff + n * m];
        let r = &self.data[zoff + n * m..zoff + n * m + m * (m + 1) / 2];
        let nodes = mesh.cell_nodes(c);
        let mut coords = [[0.0; 3]; MAX_NODES];
        for (x, &nd) in coords.iter_mut().zip(nodes) {
            *x = mesh.coords[nd];
        }
        deformation(&coords[..nodes.len()], |a, k| u[2 * nodes[a] + k], ue);
        zu.clear();
        zu.extend(
            z.chunks_exact(m)
                .map(|row| row.iter().zip(ue.iter()).map(|(a, b)| a * b).sum::<f64>()),
        );
        // u^T R u.
        let mut uru = 0.0;
        for i in 0..m {
            let row = &r[tri(i, 0)..tri(i, 0) + i + 1];
            let s: f64 = row[..i].iter().zip(&ue[..i]).map(|(a, b)| a * b).sum();
            uru += ue[i] * (2.0 * s + row[i] * ue[i]);
        }
        let inv_alpha = 1.0 / alpha;
        let mut diff2 = 0.0;
        let mut zu2 = 0.0;
        for (yi, zi) in l.iter_mut().zip(zu.iter()) {
            *yi *= inv_alpha;
            let dlt = *yi - zi;
            diff2 += dlt * dlt;
            zu2 += zi * zi;
        }
        // v = L^-T (y / alpha), in place.
        for i in (0..n).rev() {
            let mut s = l[i];
            for k in i + 1..n {
                s -= lf[tri(k, i)] * l[k];
            }
            l[i] = s / lf[tri(i, i)];
        }
        let d0 = hooke(model.material(c)?, model.analysis);
        let d = d0.map(|row| row.map(|v| alpha * v));
        Ok(ElementResult {
            theta2: th * alpha * (diff2 + uru),
            energy2: th * alpha * (zu2 + uru),
            balance_defect,
            stress: ElementStress {
                space: space.clone(),
                coeffs: l.clone(),
                hooke: d,
            },
        })
    }
}

/// The deformation coordinates `q` (`2 nn - 3` values, into `out`) of the nodal displacements
/// `u(a, k)` of a cell with node coordinates `coords`: with `d_a = u_a - u_0`, `e` the unit
/// vector of `x_1 - x_0`, `e_perp = (-e_y, e_x)` and the rotation `w = d_1 . e_perp / |x_1 - x_0|`:
/// `q = [d_1 . e, d_2 - w J (x_2 - x_0), ..., d_(nn-1) - w J (x_(nn-1) - x_0)]` (`J` the rotation
/// by a right angle). `u_e = rigid + T q` with `T` mapping `q_0` to `e` at node 1 and `q_a` to
/// node `a`: an operator that vanishes on rigid modes acts on `u_e` as its restriction `A T` on
/// `q`.
pub(crate) fn deformation(
    coords: &[[f64; 3]],
    u: impl Fn(usize, usize) -> f64,
    out: &mut Vec<f64>,
) {
    let (x0, x1) = (coords[0], coords[1]);
    let t = [x1[0] - x0[0], x1[1] - x0[1]];
    let len = (t[0] * t[0] + t[1] * t[1]).sqrt();
    let e = [t[0] / len, t[1] / len];
    let u0 = [u(0, 0), u(0, 1)];
    let d1 = [u(1, 0) - u0[0], u(1, 1) - u0[1]];
    let w = (-e[1] * d1[0] + e[0] * d1[1]) / len;
    out.clear();
    out.push(d1[0] * e[0] + d1[1] * e[1]);
    for (a, x) in coords.iter().enumerate().skip(2) {
        let r = [x[0] - x0[0], x[1] - x0[1]];
        out.push(u(a, 0) - u0[0] + w * r[1]);
        out.push(u(a, 1) - u0[1] - w * r[0]);
    }
}

/// The columns of `T` ([`deformation`]): for each `q` entry, the nodal displacement vector
/// (`2 nn`) it stands for.
fn deformation_basis(coords: &[[f64; 3]]) -> Vec<Vec<f64>> {
    let nn = coords.len();
    let (x0, x1) = (coords[0], coords[1]);
    let t = [x1[0] - x0[0], x1[1] - x0[1]];
    let len = (t[0] * t[0] + t[1] * t[1]).sqrt();
    let mut cols = Vec::with_capacity(2 * nn - 3);
    let mut c0 = vec![0.0; 2 * nn];
    c0[2] = t[0] / len;
    c0[3] = t[1] / len;
    cols.push(c0);
    for k in 4..2 * nn {
        let mut c = vec![0.0; 2 * nn];
        c[k] = 1.0;
        cols.push(c);
    }
    cols
}

/// A quadrature point of the set-up: weight, strains of the local basis and of the FE basis.
type StrainPoint = (f64, Vec<[f64; 3]>, Vec<[f64; 3]>);

/// The cached data of cell `c`: its space and `[L (packed), Z_q, R_q (packed)]`.
fn cell_data(
    model: &Model,
    c: usize,
    rules: &[Phase2Rules; 2],
) -> Result<(PolySpace, Vec<f64>), CreError> {
    let mesh = &model.mesh;
    let kind = mesh.cell_type(c);
    let rules = &rules[kind.order().clamp(1, 2) - 1];
    let coords = model.cell_coords(c);
    let nn = coords.len();
    let m = 2 * nn;
    let d = hooke(model.material(c)?, model.analysis);
    let space = PolySpace::new(rules.degree, &coords);
    let n = space.len();
    let rule = rules.volume(kind, cell_is_curved(mesh, c));
    let mut k = vec![0.0; n * n];
    let mut g = vec![0.0; n * m];
    let mut p = PolyPoint::default();
    let mut db = vec![[0.0; 3]; n];
    // Per point: weight, strains of the local basis and of the FE basis (second pass).
    let mut points: Vec<StrainPoint> = Vec::with_capacity(rule.len());
    for (xi, w) in rule.points.iter().zip(&rule.weights) {
        let geo = point_geometry(kind, &coords, *xi);
        check_jacobian(&geo, c, kind)?;
        let wd = w * geo.det;
        space.eval(geo.x, false, &mut p);
        add_stiffness(&mut k, wd, &p.eps, &d, &mut db);
        // FE strain operator columns: eps(N_a e_x) = [gx, 0, gy], eps(N_a e_y) = [0, gy, gx].
        let mut bm = vec![[0.0; 3]; m];
        for a in 0..nn {
            let [gx, gy, _] = geo.grad[a];
            bm[2 * a] = [gx, 0.0, gy];
            bm[2 * a + 1] = [0.0, gy, gx];
        }
        for (j, col) in bm.iter().enumerate() {
            for i in 0..n {
                g[i * m + j] += wd * (db[i][0] * col[0] + db[i][1] * col[1] + db[i][2] * col[2]);
            }
        }
        points.push((wd, p.eps.clone(), bm));
    }
    // Cholesky K0 = L L^T (upper triangle of k holds K0).
    let mut lp = vec![0.0; n * (n + 1) / 2];
    for j in 0..n {
        let mut dj = k[j * n + j];
        for q in 0..j {
            dj -= lp[tri(j, q)] * lp[tri(j, q)];
        }
        if !(dj > 0.0) || !dj.is_finite() {
            return Err(CreError::LocalSolve { cell: c });
        }
        let dj = dj.sqrt();
        lp[tri(j, j)] = dj;
        for i in j + 1..n {
            let mut s = k[j * n + i];
            for q in 0..j {
                s -= lp[tri(i, q)] * lp[tri(j, q)];
            }
            lp[tri(i, j)] = s / dj;
        }
    }
    // Z = L^-1 G, column by column.
    let mut z = g;
    for col in 0..m {
        for i in 0..n {
            let mut s = z[i * m + col];
            for q in 0..i {
                s -= lp[tri(i, q)] * z[q * m + col];
            }
            z[i * m + col] = s / lp[tri(i, i)];
        }
    }
    // W = L^-T Z = K0^-1 G: the local-space projection of each FE strain mode.
    let mut wp = z.clone();
    for col in 0..m {
        for i in (0..n).rev() {
            let mut s = wp[i * m + col];
            for q in i + 1..n {
                s -= lp[tri(q, i)] * wp[q * m + col];
            }
            wp[i * m + col] = s / lp[tri(i, i)];
        }
    }
    // R = Ke0 - Z^T Z = int r^T D r with the pointwise residual r = B - eps(phi) W of the
    // projection (the energy of the FE strain modes outside the local space), integrated
    // pointwise: no cancellation of the two (nearly equal) energies.
    let mut r = vec![0.0; m * (m + 1) / 2];
    let mut res = vec![[0.0; 3]; m];
    for (wd, eps, bm) in &points {
        for (j, rj) in res.iter_mut().enumerate() {
            let mut v = bm[j];
            for (i, e) in eps.iter().enumerate() {
                let wij = wp[i * m + j];
                v[0] -= e[0] * wij;
                v[1] -= e[1] * wij;
                v[2] -= e[2] * wij;
            }
            *rj = v;
        }
        for j in 0..m {
            let s = mul3(&d, &res[j]);
            for i in j..m {
                r[tri(i, j)] += wd * (res[i][0] * s[0] + res[i][1] * s[1] + res[i][2] * s[2]);
            }
        }
    }
    // Restriction to the deformation coordinates: Z_q = Z T, R_q = T^T R T.
    let basis = deformation_basis(&coords);
    let md = basis.len();
    let full = |i: usize, j: usize| if i >= j { r[tri(i, j)] } else { r[tri(j, i)] };
    let mut out = lp;
    for i in 0..n {
        let row = &z[i * m..(i + 1) * m];
        for col in &basis {
            out.push(row.iter().zip(col).map(|(a, b)| a * b).sum());
        }
    }
    for (i, ci) in basis.iter().enumerate() {
        for cj in &basis[..=i] {
            let mut v = 0.0;
            for (a, &x) in ci.iter().enumerate() {
                if x != 0.0 {
                    v += x * (0..m).map(|b| full(a, b) * cj[b]).sum::<f64>();
                }
            }
            out.push(v);
        }
    }
    debug_assert_eq!(md, m - 3);
    Ok((space, out))
}

/// The moments of the scalar basis functions and the geometric moments of every cell, on the
/// phase-2 rule.
fn body_moments(model: &Model, cells: &[CellData], rules: &[Phase2Rules; 2]) -> BodyMoments {
    let mesh = &model.mesh;
    let per: Vec<(Vec<f64>, [f64; 6])> = cells
        .par_iter()
        .enumerate()
        .map(|(c, cd)| {
            let kind = mesh.cell_type(c);
            let rules = &rules[kind.order().clamp(1, 2) - 1];
            let rule = rules.volume(kind, cd.curved);
            let coords = model.cell_coords(c);
            let ns = cd.space.num_scalars();
            let mut mom = vec![0.0; 3 * ns];
            let mut geo = [0.0; 6];
            let mut psi = vec![0.0; ns];
            for (xi, w) in rule.points.iter().zip(&rule.weights) {
                let g = point_geometry(kind, &coords, *xi);
                let wd = w * g.det;
                let [x, y, _] = g.x;
                cd.space.scalars([x, y], &mut psi);
                for (s, v) in psi.iter().enumerate() {
                    mom[s] += wd * v;
                    mom[ns + s] += wd * x * v;
                    mom[2 * ns + s] += wd * y * v;
                }
                for (gk, v) in geo.iter_mut().zip([1.0, x, y, x * x, x * y, y * y]) {
                    *gk += wd * v;
                }
            }
            (mom, geo)
        })
        .collect();
    let mut values = Vec::with_capacity(per.iter().map(|p| p.0.len()).sum());
    let mut offsets = vec![0];
    let mut geometry = Vec::with_capacity(per.len());
    for (mom, geo) in per {
        values.extend_from_slice(&mom);
        offsets.push(values.len());
        geometry.push(geo);
    }
    BodyMoments {
        values,
        offsets,
        geometry,
    }
}
