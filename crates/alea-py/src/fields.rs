//! Random fields: the Galerkin Karhunen-Loeve expansion of `alea_uq::field` on a mesh given as
//! NumPy arrays, and the Gaussian, lognormal and bounded fields at its nodes.

use alea_uq::field::{
    Covariance, FieldCells, FieldMesh, FieldTransform, KernelIntegration, KernelShape, KlExpansion,
    RandomField, Truncation,
};
use numpy::{PyArray1, PyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::convert::{ArrayIn, NonNegative, array1, array2, points, uq_err, value_error, vector};

/// Karhunen-Loeve expansion of a stationary Gaussian field on a P1 mesh.
///
/// `nodes`: `(n, d)` coordinates (`d` = 1 to 3, or a 1-D array of abscissae); `cells`: lists of
/// 2 node indices (segments, e.g. along a contact line), 3 (triangles) or 4 (tetrahedra); `kernel`:
/// `"exponential"`, `"squared-exponential"`, `"matern32"` or `"matern52"`; `variance` (sigma^2)
/// and `length` (one correlation length, or one per coordinate). Exactly one of
/// `variance_fraction` (keep the fewest modes whose eigenvalues reach this fraction of
/// sigma^2 |D|) and `modes` (a mode count) must be given. `integration="nodal"` interpolates the
/// kernel at the nodes as OpenTURNS's `KarhunenLoeveP1Algorithm` does (default: quadrature).
#[pyclass(frozen, module = "alea", name = "KarhunenLoeve")]
pub struct KarhunenLoeve {
    kl: KlExpansion,
    std: f64,
}

fn kernel_shape(name: &str) -> PyResult<KernelShape> {
    match name {
        "exponential" | "matern12" => Ok(KernelShape::Exponential),
        "squared-exponential" | "squared_exponential" | "gaussian" => {
            Ok(KernelShape::SquaredExponential)
        }
        "matern32" => Ok(KernelShape::Matern32),
        "matern52" => Ok(KernelShape::Matern52),
        other => Err(value_error(format!(
            "KarhunenLoeve kernel: expected \"exponential\", \"squared-exponential\", \"matern32\" or \"matern52\", got {other:?}"
        ))),
    }
}

#[pymethods]
impl KarhunenLoeve {
    #[new]
    #[pyo3(signature = (nodes, cells, kernel, variance, length, *, variance_fraction = None, modes = None, integration = "quadrature"))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        nodes: ArrayIn<'_>,
        cells: Vec<Vec<usize>>,
        kernel: &str,
        variance: f64,
        length: &Bound<'_, PyAny>,
        variance_fraction: Option<f64>,
        modes: Option<NonNegative<usize>>,
        integration: &str,
    ) -> PyResult<Self> {
        let modes = modes.map(|v| v.0);
        let d = match nodes.shape() {
            [_, d] if (1..=3).contains(d) => *d,
            [_] => 1,
            s => {
                return Err(value_error(format!(
                    "KarhunenLoeve nodes: expected shape (n, 1), (n, 2), (n, 3) or (n,), got {s:?}"
                )));
            }
        };
        let (flat, n) = points(&nodes, d, "KarhunenLoeve nodes")?;
        let coords: Vec<[f64; 3]> = (0..n)
            .map(|i| {
                let mut x = [0.0; 3];
                x[..d].copy_from_slice(&flat[i * d..(i + 1) * d]);
                x
            })
            .collect();
        let k = cells.first().map_or(0, Vec::len);
        if let Some((c, bad)) = cells.iter().enumerate().find(|(_, c)| c.len() != k) {
            return Err(value_error(format!(
                "KarhunenLoeve cells: cell {c} has {} nodes, cell 0 has {k}",
                bad.len()
            )));
        }
        let cells = match k {
            2 => FieldCells::Segments(cells.iter().map(|c| [c[0], c[1]]).collect()),
            3 => FieldCells::Triangles(cells.iter().map(|c| [c[0], c[1], c[2]]).collect()),
            4 => FieldCells::Tetrahedra(cells.iter().map(|c| [c[0], c[1], c[2], c[3]]).collect()),
            _ => {
                return Err(value_error(format!(
                    "KarhunenLoeve cells: expected a non-empty list of 2-node segments, 3-node triangles or 4-node tetrahedra, got cells of {k} nodes"
                )));
            }
        };
        let lengths: Vec<f64> = match length.extract::<f64>() {
            Ok(l) => vec![l],
            Err(_) => length.extract::<Vec<f64>>().map_err(|_| {
                value_error("KarhunenLoeve length: expected a number or a list of numbers")
            })?,
        };
        let truncation = match (variance_fraction, modes) {
            (Some(f), None) => Truncation::VarianceFraction(f),
            (None, Some(m)) => Truncation::Modes(m),
            _ => {
                return Err(value_error(
                    "KarhunenLoeve: give exactly one of variance_fraction and modes",
                ));
            }
        };
        let integration = match integration {
            "quadrature" => KernelIntegration::Quadrature,
            "nodal" => KernelIntegration::NodalInterpolation,
            other => {
                return Err(value_error(format!(
                    "KarhunenLoeve integration: expected \"quadrature\" or \"nodal\", got {other:?}"
                )));
            }
        };
        let shape = kernel_shape(kernel)?;
        let mesh = FieldMesh::new(coords, cells).map_err(uq_err)?;
        let cov = Covariance::anisotropic(shape, variance, &lengths).map_err(uq_err)?;
        let kl = py
            .detach(move || KlExpansion::galerkin_with(&mesh, &cov, truncation, integration))
            .map_err(uq_err)?;
        Ok(Self {
            kl,
            std: variance.sqrt(),
        })
    }

    /// Number of modes kept (the number of standard normal KL variables).
    #[getter]
    fn num_modes(&self) -> usize {
        self.kl.num_modes()
    }

    /// Eigenvalues kept, largest first.
    #[getter]
    fn eigenvalues<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array1(py, self.kl.eigenvalues().to_vec())
    }

    /// Modes at the nodes, shape `(num_modes, n)`; `int phi_k phi_l = delta_kl`.
    #[getter]
    fn modes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let n = self.kl.mesh().num_nodes();
        let m = self.kl.num_modes();
        let v: Vec<f64> = (0..m).flat_map(|k| self.kl.mode(k).to_vec()).collect();
        array2(py, v, m, n)
    }

    /// `sigma^2 |D|`, the sum of all exact eigenvalues.
    #[getter]
    fn total_variance(&self) -> f64 {
        self.kl.total_variance()
    }

    /// Fraction of `sigma^2 |D|` captured by the modes kept.
    #[getter]
    fn captured_fraction(&self) -> f64 {
        self.kl.captured_fraction()
    }

    /// The field at the nodes for KL variables `xi` (shape `(num_modes,)`, or `(s, num_modes)`
    /// for `s` realisations): `g = mean + sum_k sqrt(lambda_k) phi_k xi_k`, then
    /// `transform` `"gaussian"` (g), `"lognormal"` (exp g) or `"bounded"`
    /// (`lower + (upper - lower) Phi((g - mean) / sigma)`, needs `bounds=(lower, upper)`).
    #[pyo3(signature = (xi, mean = 0.0, transform = "gaussian", bounds = None))]
    fn realise<'py>(
        &self,
        py: Python<'py>,
        xi: ArrayIn<'py>,
        mean: f64,
        transform: &str,
        bounds: Option<(f64, f64)>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let transform = match (transform, bounds) {
            ("gaussian", None) => FieldTransform::Gaussian,
            ("lognormal", None) => FieldTransform::Lognormal,
            ("bounded", Some((lower, upper))) => FieldTransform::Bounded { lower, upper },
            ("bounded", None) => {
                return Err(value_error(
                    "KarhunenLoeve.realise: transform \"bounded\" needs bounds=(lower, upper)",
                ));
            }
            ("gaussian" | "lognormal", Some(_)) => {
                return Err(value_error(
                    "KarhunenLoeve.realise: bounds are only for transform \"bounded\"",
                ));
            }
            (other, _) => {
                return Err(value_error(format!(
                    "KarhunenLoeve.realise: transform must be \"gaussian\", \"lognormal\" or \"bounded\", got {other:?}"
                )));
            }
        };
        let field = RandomField::new(mean, self.std, transform, self.kl.clone()).map_err(uq_err)?;
        let m = self.kl.num_modes();
        let n = self.kl.mesh().num_nodes();
        // A 1-D array is one realisation; a 2-D array one realisation per row.
        let one = xi.shape().len() == 1;
        let (v, s) = if one {
            (vector(&xi, Some(m), "KarhunenLoeve.realise xi")?, 1)
        } else {
            points(&xi, m, "KarhunenLoeve.realise xi")?
        };
        let mut out = Vec::with_capacity(s * n);
        for r in 0..s {
            out.extend(field.at_nodes(&v[r * m..(r + 1) * m]).map_err(uq_err)?);
        }
        if one {
            Ok(array1(py, out).into_any())
        } else {
            Ok(array2(py, out, s, n)?.into_any())
        }
    }
}
