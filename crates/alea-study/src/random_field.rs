//! Random fields along the contact (`[[field]]`): a Gaussian field, or its lognormal or
//! bounded transform, over the facets of an interface's side 1, discretised by the Galerkin
//! Karhunen-Loeve expansion of `alea_uq::field`:
//!
//! ```text
//! g(x) = m + sum_{k<M} sqrt(lambda_k) phi_k(x) xi_k,   u(x) = T(g(x)),
//! ```
//!
//! with `xi_k` independent standard normal. The KL variables `xi_1 .. xi_M` become study
//! parameters named `<field>_1 .. <field>_M` (appended after the `[[parameter]]`s, law
//! `normal (mean 0, std 1)`), and the field's name is a variable of the interface `mu` and `gap`
//! expressions, worth `u(x)` at the point `x` where the solver evaluates them.
//!
//! * **Mesh of the field**: the corner nodes of the side-1 facets (segments in 2D; triangles
//!   in 3D, a quadrilateral split along its first diagonal), with P1 interpolation: `u(x)` at a
//!   point of the contact is interpolated in the nearest facet (the point projected onto it,
//!   ties to the lowest facet index), so at the facets' nodes it is the nodal value exactly.
//! * **Transforms** ([`alea_uq::field::FieldTransform`]): gaussian, `u = g` with `m` = mean and
//!   `sigma` = std; lognormal, `u = exp(g)` with `sigma^2 = ln(1 + std^2 / mean^2)`, `m =
//!   ln(mean) - sigma^2 / 2` (so that `u` has the stated mean and std); bounded, `u = a + (b -
//!   a) Phi(g)` with `m = 0`, `sigma = 1` (uniform marginals on `(a, b)` when the expansion keeps
//!   all the variance).
//! * **Truncation**: a number of modes, or the fewest modes whose eigenvalues sum to a fraction
//!   `f` of `int_D sigma^2 = sigma^2 |D|`; since the `xi_k` are independent with unit variance,
//!   `int_D Var g = sum_{k<M} lambda_k`, the captured fraction reported in the summary.
//! * **Checked at load**, each with the file, line and field: names (unique, not a parameter, a
//!   define or `x, y, z, pi`; the KL variables' names free), the interface, the covariance, the
//!   correlation length (finite, > 0), the transform's keys (mean and std for gaussian and
//!   lognormal, lower < upper for bounded; the others refused), exactly one of
//!   `variance_fraction` in (0, 1] and `modes` in 1 ..= nodes, and the size of the KL problem
//!   (at most [`MAX_FIELD_NODES`] nodes: dense `n x n` matrices and an `O(n^3)` eigensolver)
//!   before anything is computed.
//! * **With a dependent `[joint]`**: the copula (or density) spans the `[[parameter]]`s only;
//!   the KL variables are a block of independent standard normal variables beside it
//!   (`alea_uq::joint::ProductJoint`), as the expansion requires.
//!
//! A point is located on a field's mesh (nearest cell, P1 weights) in `random_field/locate.rs`.

mod locate;

use std::sync::Arc;

use alea_mesh::{CellType, Mesh};
use alea_uq::field::{
    Covariance, FieldCells, FieldMesh, FieldTransform, KernelShape, KlExpansion, RandomField,
    Truncation, lognormal_gaussian_parameters,
};

use crate::field_spec::FieldSpec;
use crate::spec::ModelFile;
use crate::{Source, StudyError};

use locate::locate_on;

pub use crate::cell_field::MAX_FIELD_NODES;

/// Where a field lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FieldDomain {
    /// Along interface `i` of `[[interface]]` (the facets of its side 1).
    Interface(usize),
    /// Over the cells of substructure `s` of `[[substructure]]`.
    Substructure(usize),
}

/// A random field of a study, ready to evaluate.
#[derive(Clone, Debug)]
pub struct StudyField {
    /// Name (the variable of `mu` / `gap` expressions, or of a substructure's `young`).
    pub name: String,
    /// Where it lives.
    pub domain: FieldDomain,
    /// For a field over a substructure's cells: per cell of the substructure's mesh, the field
    /// nodes and weights of the cell's value (`u_c = sum_i w_i u_i`, the weights of a cell
    /// summing to 1: the field's mean over the cell, or its value at the cell's centroid on a
    /// grid; module `cell_field`); empty for an interface field.
    pub cell_means: Vec<Vec<(usize, f64)>>,
    /// The field: KL expansion and transform.
    pub field: RandomField,
    /// Index of its first KL variable among the study parameters.
    pub first_variable: usize,
    /// Unit of its values (for the report).
    pub unit: String,
    /// One line for the report: covariance, length, truncation.
    pub description: String,
}

impl StudyField {
    /// The interface the field lives on (`None`: over a substructure's cells).
    pub fn interface(&self) -> Option<usize> {
        match self.domain {
            FieldDomain::Interface(i) => Some(i),
            FieldDomain::Substructure(_) => None,
        }
    }

    /// Number of KL variables.
    pub fn num_variables(&self) -> usize {
        self.field.num_variables()
    }

    /// The field at the nodes of its mesh for the parameter point `theta` (all the study's
    /// parameters); `NaN` everywhere if the transform overflows (the check of a run's inputs
    /// then refuses the point, naming the interface field).
    pub fn at_nodes(&self, theta: &[f64]) -> Vec<f64> {
        let m = self.num_variables();
        let xi = theta.get(self.first_variable..self.first_variable + m);
        match xi.map(|xi| self.field.at_nodes(xi)) {
            Some(Ok(v)) => v,
            _ => vec![f64::NAN; self.field.kl().mesh().num_nodes()],
        }
    }

    /// The value on each cell of the substructure of the P1 field with nodal values `nodal`
    /// (a field over a substructure's cells; empty for an interface field).
    pub fn cell_values(&self, nodal: &[f64]) -> Vec<f64> {
        self.cell_means
            .iter()
            .map(|w| w.iter().map(|&(i, wi)| wi * nodal[i]).sum())
            .collect()
    }

    /// The P1 interpolant of the nodal values `nodal` at `x` (in the nearest cell).
    pub fn interpolate(&self, nodal: &[f64], x: [f64; 3]) -> f64 {
        self.locate(x).value(nodal)
    }

    /// Where `x` falls in the field's mesh, for interpolating any nodal values there.
    pub fn locate(&self, x: [f64; 3]) -> FieldPoint {
        locate_on(self.field.kl().mesh(), x)
    }
}

/// A point of a field's mesh: the nodes of the cell nearest to it and the P1 weights of its
/// closest point in that cell ([`StudyField::locate`]).
#[derive(Clone, Debug)]
pub struct FieldPoint {
    nodes: Vec<usize>,
    weights: Vec<f64>,
}

impl FieldPoint {
    /// The P1 interpolant of the nodal values `nodal` at the point.
    pub fn value(&self, nodal: &[f64]) -> f64 {
        self.nodes
            .iter()
            .zip(&self.weights)
            .map(|(&i, wi)| wi * nodal[i])
            .sum()
    }
}

/// The P1 mesh of the corner nodes of the facets of `group` in `mesh`.
fn facet_mesh(mesh: &Mesh, group: &str) -> Result<FieldMesh, String> {
    let facets = mesh.facet_group(group).map_err(|e| e.to_string())?;
    let mut index = std::collections::BTreeMap::new();
    let mut nodes = Vec::new();
    let mut id = |g: usize| {
        *index.entry(g).or_insert_with(|| {
            nodes.push(mesh.coords[g]);
            nodes.len() - 1
        })
    };
    let (mut segs, mut tris) = (Vec::new(), Vec::new());
    for f in facets {
        let c: Vec<usize> = f.nodes[..f.kind.num_corners()]
            .iter()
            .map(|&g| id(g))
            .collect();
        match f.kind {
            CellType::Line2 | CellType::Line3 => segs.push([c[0], c[1]]),
            _ if c.len() == 3 => tris.push([c[0], c[1], c[2]]),
            _ => {
                tris.push([c[0], c[1], c[2]]);
                tris.push([c[0], c[2], c[3]]);
            }
        }
    }
    let cells = if tris.is_empty() {
        FieldCells::Segments(segs)
    } else {
        FieldCells::Triangles(tris)
    };
    if nodes.len() > MAX_FIELD_NODES {
        return Err(format!(
            "the field's mesh has {} nodes; at most {MAX_FIELD_NODES} (the KL problem is dense)",
            nodes.len()
        ));
    }
    FieldMesh::new(nodes, cells).map_err(|e| e.to_string())
}

fn shape(src: &Source, f: &FieldSpec, i: usize) -> Result<KernelShape, StudyError> {
    Ok(match f.covariance.get_ref().as_str() {
        "squared_exponential" => KernelShape::SquaredExponential,
        "exponential" => KernelShape::Exponential,
        "matern32" => KernelShape::Matern32,
        "matern52" => KernelShape::Matern52,
        other => {
            return Err(src.error(
                f.covariance.span(),
                format!("field[{i}].covariance"),
                format!("unknown covariance '{other}'; expected squared_exponential, exponential, matern32 or matern52"),
            ));
        }
    })
}

/// Mean and variance of the Gaussian field and the transform, with the keys checked.
fn transform(
    src: &Source,
    f: &FieldSpec,
    i: usize,
) -> Result<(f64, f64, FieldTransform), StudyError> {
    let key = |k: &str| format!("field[{i}].{k}");
    let kind = f
        .transform
        .as_ref()
        .map_or("gaussian", |t| t.get_ref().as_str());
    let span = f.transform.as_ref().map_or(f.name.span(), |t| t.span());
    let present = [
        ("mean", f.mean.as_ref()),
        ("std", f.std.as_ref()),
        ("lower", f.lower.as_ref()),
        ("upper", f.upper.as_ref()),
    ];
    let (needed, refused): (&[&str], &[&str]) = match kind {
        "gaussian" | "lognormal" => (&["mean", "std"], &["lower", "upper"]),
        "bounded" => (&["lower", "upper"], &["mean", "std"]),
        other => {
            return Err(src.error(
                span,
                key("transform"),
                format!("unknown transform '{other}'; expected gaussian, lognormal or bounded"),
            ));
        }
    };
    for (k, v) in present {
        if refused.contains(&k)
            && let Some(v) = v
        {
            return Err(src.error(
                v.span(),
                key(k),
                format!(
                    "a {kind} field takes no '{k}' (it takes {})",
                    needed.join(" and ")
                ),
            ));
        }
        if needed.contains(&k) {
            match v {
                None => {
                    return Err(src.error(
                        span.clone(),
                        key(k),
                        format!("a {kind} field needs '{k}'"),
                    ));
                }
                Some(v) if !v.get_ref().is_finite() => {
                    return Err(src.error(
                        v.span(),
                        key(k),
                        format!("must be finite, got {}", v.get_ref()),
                    ));
                }
                _ => {}
            }
        }
    }
    let val = |v: &Option<toml::Spanned<f64>>| v.as_ref().map_or(0.0, |s| *s.get_ref());
    match kind {
        "bounded" => {
            let (a, b) = (val(&f.lower), val(&f.upper));
            if b <= a {
                let sp = f.upper.as_ref().map_or(span, |u| u.span());
                return Err(src.error(sp, key("upper"), format!("must be > lower = {a}, got {b}")));
            }
            Ok((0.0, 1.0, FieldTransform::Bounded { lower: a, upper: b }))
        }
        _ => {
            let (m, s) = (val(&f.mean), val(&f.std));
            let sp = f.std.as_ref().map_or(span.clone(), |u| u.span());
            if s <= 0.0 {
                return Err(src.error(sp, key("std"), format!("must be > 0, got {s}")));
            }
            if kind == "gaussian" {
                return Ok((m, s * s, FieldTransform::Gaussian));
            }
            let (gm, gv) = lognormal_gaussian_parameters(m, s).map_err(|e| {
                let sp = f.mean.as_ref().map_or(span.clone(), |u| u.span());
                src.error(sp, key("mean"), e.to_string())
            })?;
            Ok((gm, gv, FieldTransform::Lognormal))
        }
    }
}

fn truncation(src: &Source, f: &FieldSpec, i: usize) -> Result<Truncation, StudyError> {
    let key = |k: &str| format!("field[{i}].{k}");
    match (&f.variance_fraction, &f.modes) {
        (Some(_), Some(m)) => Err(src.error(
            m.span(),
            key("modes"),
            "give either variance_fraction or modes, not both",
        )),
        (None, None) => Err(src.error(
            f.name.span(),
            key("variance_fraction"),
            "a field needs variance_fraction (in (0, 1]) or modes (>= 1)",
        )),
        (Some(v), None) => {
            let x = *v.get_ref();
            if !(x > 0.0 && x <= 1.0) {
                return Err(src.error(
                    v.span(),
                    key("variance_fraction"),
                    format!("must be in (0, 1], got {x}"),
                ));
            }
            Ok(Truncation::VarianceFraction(x))
        }
        (None, Some(m)) => {
            if *m.get_ref() == 0 {
                return Err(src.error(m.span(), key("modes"), "must be >= 1, got 0"));
            }
            Ok(Truncation::Modes(*m.get_ref()))
        }
    }
}

/// Checks a field's name against the names already taken.
fn check_name(src: &Source, f: &FieldSpec, i: usize, taken: &[String]) -> Result<(), StudyError> {
    let n = f.name.get_ref();
    let valid = n
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    let clash = ["x", "y", "z", "pi"].contains(&n.as_str()) || taken.contains(n);
    if !valid || clash {
        return Err(src.error(
            f.name.span(),
            format!("field[{i}].name"),
            format!("'{n}' is not a usable name (letters, digits, '_'; not x, y, z, pi, a parameter, a define or another field)"),
        ));
    }
    Ok(())
}

/// The random fields of a study file, their KL variables numbered from `first_variable`, and
/// those variables' names. `taken` are the names in use (parameters, defines).
pub(crate) fn build_fields(
    src: &Source,
    file: &ModelFile,
    taken: &[String],
    first_variable: usize,
) -> Result<(Vec<Arc<StudyField>>, Vec<String>), StudyError> {
    if file.field.is_empty() {
        return Ok((Vec::new(), Vec::new()));
    }
    let mesh =
        crate::build::build_mesh(src, &file.mesh, crate::limits::factor_layout(&file.solver))?;
    let mut taken: Vec<String> = taken.to_vec();
    let (mut fields, mut variables) = (Vec::new(), Vec::new());
    for (i, f) in file.field.iter().enumerate() {
        let key = |k: &str| format!("field[{i}].{k}");
        check_name(src, f, i, &taken)?;
        let name = f.name.get_ref().clone();
        let domain = field_domain(src, file, f, i)?;
        let shape = shape(src, f, i)?;
        let length = *f.correlation_length.get_ref();
        if !(length.is_finite() && length > 0.0) {
            return Err(src.error(
                f.correlation_length.span(),
                key("correlation_length"),
                format!("must be a finite length > 0, got {length}"),
            ));
        }
        let (mean, variance, tr) = transform(src, f, i)?;
        let trunc = truncation(src, f, i)?;
        let (fmesh, cell_means, place) = domain_mesh(src, file, &mesh, f, i, domain)?;
        if let Truncation::Modes(m) = trunc
            && m > fmesh.num_nodes()
        {
            return Err(src.error(
                f.modes.as_ref().map_or(f.name.span(), |m| m.span()),
                key("modes"),
                format!(
                    "must be at most the {} nodes of the field's mesh, got {m}",
                    fmesh.num_nodes()
                ),
            ));
        }
        let bad =
            |e: alea_uq::UqError| src.error(f.name.span(), format!("field[{i}]"), e.to_string());
        let cov = Covariance::new(shape, variance, length).map_err(bad)?;
        let kl = KlExpansion::galerkin(&fmesh, &cov, trunc).map_err(bad)?;
        let field = RandomField::new(mean, variance.sqrt(), tr, kl).map_err(bad)?;
        let m = field.num_variables();
        let unit = f.unit.clone().unwrap_or_default();
        let description = format!(
            "{} field{} {place}, {} covariance, correlation length {length}; {m} KL modes, {:.1} % of the variance, {} nodes",
            f.transform
                .as_ref()
                .map_or("gaussian", |t| t.get_ref().as_str()),
            if unit.is_empty() {
                String::new()
            } else {
                format!(" ({unit})")
            },
            f.covariance.get_ref(),
            100.0 * field.kl().captured_fraction(),
            fmesh.num_nodes(),
        );
        taken.push(name.clone());
        for v in 1..=m {
            let vname = format!("{name}_{v}");
            if taken.contains(&vname) {
                return Err(src.error(
                    f.name.span(),
                    key("name"),
                    format!("its KL variable '{vname}' is already a name of the study"),
                ));
            }
            taken.push(vname.clone());
            variables.push(vname);
        }
        fields.push(Arc::new(StudyField {
            name,
            domain,
            cell_means,
            field,
            first_variable: first_variable + variables.len() - m,
            unit,
            description,
        }));
    }
    Ok((fields, variables))
}

/// The interface or substructure a field names (exactly one of the two).
fn field_domain(
    src: &Source,
    file: &ModelFile,
    f: &FieldSpec,
    i: usize,
) -> Result<FieldDomain, StudyError> {
    let key = |k: &str| format!("field[{i}].{k}");
    match (&f.interface, &f.substructure) {
        (Some(_), Some(s)) => Err(src.error(
            s.span(),
            key("substructure"),
            "give either interface or substructure, not both",
        )),
        (None, None) => Err(src.error(
            f.name.span(),
            key("interface"),
            "a field needs interface (a field along the contact) or substructure (over its cells)",
        )),
        (Some(it), None) => {
            let name = it.get_ref();
            let k = file
                .interface
                .iter()
                .position(|s| s.name.get_ref() == name)
                .ok_or_else(|| {
                    let names: Vec<&str> = file
                        .interface
                        .iter()
                        .map(|s| s.name.get_ref().as_str())
                        .collect();
                    src.error(
                        it.span(),
                        key("interface"),
                        format!("unknown interface '{name}'; defined: {}", names.join(", ")),
                    )
                })?;
            Ok(FieldDomain::Interface(k))
        }
        (None, Some(sb)) => {
            let name = sb.get_ref();
            let k = file
                .substructure
                .iter()
                .position(|s| s.name.get_ref() == name)
                .ok_or_else(|| {
                    let names: Vec<&str> = file
                        .substructure
                        .iter()
                        .map(|s| s.name.get_ref().as_str())
                        .collect();
                    src.error(
                        sb.span(),
                        key("substructure"),
                        format!(
                            "unknown substructure '{name}'; defined: {}",
                            names.join(", ")
                        ),
                    )
                })?;
            Ok(FieldDomain::Substructure(k))
        }
    }
}

/// The field's P1 mesh, its cell means (a substructure field) and where it lives in words.
#[allow(clippy::type_complexity)]
fn domain_mesh(
    src: &Source,
    file: &ModelFile,
    mesh: &Mesh,
    f: &FieldSpec,
    i: usize,
    domain: FieldDomain,
) -> Result<(FieldMesh, Vec<Vec<(usize, f64)>>, String), StudyError> {
    let key = |k: &str| format!("field[{i}].{k}");
    let sub_mesh =
        |s: &crate::spec::SubstructureSpec, err: &dyn Fn(String) -> StudyError| match &s.cells {
            Some(c) => mesh
                .extract(&[c.get_ref().as_str()])
                .map(|m| m.0)
                .map_err(|e| err(e.to_string())),
            None => Ok(mesh.clone()),
        };
    match domain {
        FieldDomain::Interface(k) => {
            if let Some(g) = &f.grid {
                return Err(src.error(
                    g.span(),
                    key("grid"),
                    "grid is for a field over a substructure's cells; a field along an interface lives on its facets",
                ));
            }
            let side = &file.interface[k].side1;
            let [sub, group] = side.get_ref();
            let side_err = |m: String| src.error(side.span(), format!("interface[{k}].side1"), m);
            let s = file
                .substructure
                .iter()
                .find(|s| s.name.get_ref() == sub)
                .ok_or_else(|| side_err(format!("unknown substructure '{sub}'")))?;
            let sm = sub_mesh(s, &side_err)?;
            let span = f.interface.as_ref().map_or(f.name.span(), |s| s.span());
            let fmesh = facet_mesh(&sm, group).map_err(|m| src.error(span, key("interface"), m))?;
            let place = format!("on interface '{}'", file.interface[k].name.get_ref());
            Ok((fmesh, Vec::new(), place))
        }
        FieldDomain::Substructure(k) => {
            let s = &file.substructure[k];
            let span = f.substructure.as_ref().map_or(f.name.span(), |s| s.span());
            let err = |m: String| src.error(span.clone(), key("substructure"), m);
            let sm = sub_mesh(s, &err)?;
            let (fmesh, means) = match &f.grid {
                None => crate::cell_field::on_corners(&sm).map_err(err)?,
                Some(g) => crate::cell_field::on_grid(&sm, g.get_ref())
                    .map_err(|m| src.error(g.span(), key("grid"), m))?,
            };
            let place = match &f.grid {
                None => format!("over the cells of substructure '{}'", s.name.get_ref()),
                Some(g) => format!(
                    "over the cells of substructure '{}' (on a {} grid)",
                    s.name.get_ref(),
                    g.get_ref()
                        .iter()
                        .map(|n| n.to_string())
                        .collect::<Vec<_>>()
                        .join(" x ")
                ),
            };
            Ok((fmesh, means, place))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// P1 interpolation reproduces a linear function inside the cells, at the projection of a
    /// point off the surface, and at the closest boundary point of a point beyond the mesh.
    #[test]
    fn interpolation_is_exact_for_linear_functions_and_projects_onto_the_nearest_cell() {
        let lin = |p: &[f64; 3]| 1.0 + 2.0 * p[0] - 3.0 * p[1] + 0.5 * p[2];
        // Two triangles of the unit square in the plane z = 0.
        let nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let nodal: Vec<f64> = nodes.iter().map(lin).collect();
        let tri = FieldMesh::new(nodes, FieldCells::Triangles(vec![[0, 1, 2], [0, 2, 3]])).unwrap();
        for (x, want) in [
            ([0.3, 0.1, 0.0], [0.3, 0.1, 0.0]),
            ([0.2, 0.7, 0.0], [0.2, 0.7, 0.0]),
            ([0.6, 0.4, 0.25], [0.6, 0.4, 0.0]),
            ([1.5, 0.5, 0.0], [1.0, 0.5, 0.0]),
            ([-1.0, -1.0, 0.0], [0.0, 0.0, 0.0]),
        ] {
            let v = locate_on(&tri, x).value(&nodal);
            assert!(
                (v - lin(&want)).abs() < 1e-12,
                "{x:?}: {v} vs {}",
                lin(&want)
            );
        }
        // A polyline along a 45-degree flank.
        let nodes: Vec<[f64; 3]> = (0..5).map(|i| [i as f64, i as f64, 0.0]).collect();
        let nodal: Vec<f64> = nodes.iter().map(lin).collect();
        let seg = FieldMesh::new(
            nodes,
            FieldCells::Segments((0..4).map(|i| [i, i + 1]).collect()),
        )
        .unwrap();
        for (x, want) in [
            ([1.25, 1.25, 0.0], [1.25, 1.25, 0.0]),
            ([2.0, 3.0, 0.0], [2.5, 2.5, 0.0]),
            ([9.0, 9.0, 0.0], [4.0, 4.0, 0.0]),
        ] {
            let v = locate_on(&seg, x).value(&nodal);
            assert!(
                (v - lin(&want)).abs() < 1e-12,
                "{x:?}: {v} vs {}",
                lin(&want)
            );
        }
    }
}
