//! Hertz line contact as a ready-made assembly: a cylinder (aluminium) pressed on a flat block
//! (steel), plane strain, frictionless, half model.
//!
//! ```text
//!   y = +l  +----------------------+   upper body ("cylinder") = mirror image in y = 0
//!           |   R'  .      .   R'  |
//!   y = 0   +------+==contact==+---+   <- fine uniform square blocks [0, a] x [-a, a]
//!           |   R   '  I   '   R   |      (h = a / n), graded blocks R, B around them
//!           |     .     B     .    |
//!   y = -l  +----------------------+   lower body ("block"): clamped on y = -l
//!          x=0                      l
//! ```
//! [`ContactLayout`] builds both bodies with the multi-block generator; the cylinder's bottom
//! is flat with its curvature in the interface's initial gap `g0(x) = R - sqrt(R^2 - x^2)`
//! (coincident nodes, node-to-node pairing) or is the true circle
//! ([`ContactLayout::upper_curved`], non-matching nodes, mortar pairing).
//! Groups of each body: cell group `"body"`; facet/node groups `"contact"` (`|x| <= a` on
//! `y = 0`), `"free"` (the rest of `y = 0`), `"far"` (`y = -l` below, `y = +l` above),
//! `"far_side"` (`|x| = l`) and `"sym"` (half model).
//!
//! Reference: Johnson, *Contact Mechanics*, 1985, 4.2: `b = sqrt(4 P' R / (pi E*))`,
//! `p0 = 2 P' / (pi b)`. [`hertz_cylinder_on_block`] loads the cylinder so that `b = 1 mm` with
//! `R = 50 mm` (the test `tests/hertz.rs` checks `b` and `p0` against these).

use std::sync::Arc;

use alea_fem::{Analysis, Constraints, Loads, Material, Model};

use crate::{Assembly, InterfaceSpec, LatinError, Substructure};

use alea_mesh::generate::{Block, first_cell_grading, multiblock};
use alea_mesh::{CellType, Mesh, MeshError};

/// Mesh layout.
#[derive(Clone, Copy, Debug)]
pub struct ContactLayout {
    /// Half-length of the refined contact strip (and depth of the fine block).
    pub a: f64,
    /// Half-size of each body.
    pub l: f64,
    /// Cells across the fine block (so `h = a / n`).
    pub n: usize,
    /// Cells of the graded blocks from the fine block to the far boundary.
    pub m: usize,
    /// Whole width (`true`) or half model `x >= 0` (`false`).
    pub full: bool,
}

impl ContactLayout {
    /// Fine cell size.
    pub fn h(&self) -> f64 {
        self.a / self.n as f64
    }

    /// Grading (last / first cell) of the outer blocks so that their first cell is `h`.
    fn grading(&self) -> Result<f64, MeshError> {
        let (len, h, m) = (self.l - self.a, self.h(), self.m as i32);
        if !(len > m as f64 * h && m >= 1 && self.n >= 1) {
            return Err(MeshError::Invalid(format!(
                "contact layout: {m} outer cells over {len} would be finer than the contact \
                 strip's {h}"
            )));
        }
        Ok(first_cell_grading(len, h, self.m))
    }

    /// Blocks of the lower body, `x >= 0`.
    fn lower_half(&self) -> Result<Vec<Block>, MeshError> {
        let (a, l, n, m) = (self.a, self.l, self.n, self.m);
        let g = self.grading()?;
        let mut inner = Block::new([[0.0, -a], [a, -a], [a, 0.0], [0.0, 0.0]], [n, n])
            .group("body")
            .edge_group(2, "contact");
        let right = Block::new([[a, -a], [l, -l], [l, 0.0], [a, 0.0]], [m, n])
            .grading(g, 1.0)
            .group("body")
            .edge_group(1, "far_side")
            .edge_group(2, "free");
        let mut below = Block::new([[0.0, -l], [l, -l], [a, -a], [0.0, -a]], [n, m])
            .grading(1.0, 1.0 / g)
            .group("body")
            .edge_group(0, "far");
        if !self.full {
            inner = inner.edge_group(3, "sym");
            below = below.edge_group(3, "sym");
        }
        Ok(vec![inner, right, below])
    }

    fn blocks(&self, upper: bool) -> Result<Vec<Block>, MeshError> {
        let mut blocks = self.lower_half()?;
        if self.full {
            let mirrored: Vec<Block> = blocks.iter().map(|b| map(b, |p| [-p[0], p[1]])).collect();
            blocks.extend(mirrored);
        }
        if upper {
            blocks = blocks.iter().map(|b| map(b, |p| [p[0], -p[1]])).collect();
        }
        Ok(blocks)
    }

    /// The lower body (`y <= 0`, the flat "block").
    pub fn lower(&self) -> Result<Mesh, MeshError> {
        multiblock(&self.blocks(false)?, CellType::Quad4)
    }

    /// The upper body (`y >= 0`, the "cylinder" with its curvature in `g0`).
    pub fn upper(&self) -> Result<Mesh, MeshError> {
        multiblock(&self.blocks(true)?, CellType::Quad4)
    }

    /// The upper body with its true curved bottom: the cylinder of radius `r` touching `y = 0`
    /// at `x = 0`. The nodes of [`ContactLayout::upper`] are moved up by
    /// `g(x) (1 - y / l)`, `g(x) = r - sqrt(r^2 - x^2)`, so the bottom nodes lie on the circle,
    /// the top `y = l` stays flat and the cells shear by at most `g'(l) = l / sqrt(r^2 - l^2)`.
    pub fn upper_curved(&self, r: f64) -> Result<Mesh, MeshError> {
        if !(self.l < r) {
            return Err(MeshError::Invalid(format!(
                "contact layout: the body (half-size {}) must be narrower than the cylinder \
                 (radius {r})",
                self.l
            )));
        }
        let mut m = self.upper()?;
        for x in m.coords.iter_mut() {
            let g = r - (r * r - x[0] * x[0]).sqrt();
            x[1] += g * (1.0 - x[1] / self.l);
        }
        Ok(m)
    }
}

/// A straight-edged block with its corners mapped by a reflection (the generator re-orders
/// clockwise blocks, gradings and edge groups included).
fn map(b: &Block, f: impl Fn([f64; 2]) -> [f64; 2]) -> Block {
    let mut out = b.clone();
    out.corners = b.corners.map(f);
    out
}

/// The Hertz sample: the assembly and Hertz's half-width and peak pressure.
#[derive(Clone, Debug)]
pub struct HertzCase {
    /// Block (substructure 0) and cylinder (substructure 1), interface 0 `"contact"` (Coulomb,
    /// mu 0; side 1 the block).
    pub assembly: Assembly,
    /// Hertz's contact half-width `b` (mm).
    pub half_width: f64,
    /// Hertz's peak pressure `p0` (MPa).
    pub peak_pressure: f64,
}

/// The steel block / aluminium cylinder of `tests/hertz.rs` (R = 50 mm, `b` = 1 mm), with `n`
/// cells across the fine strip of half-length `a = 2.1 b` (`n = 50`: `h ~ b / 24`, 24 544
/// dof) and `0.7 n` graded cells outward; `curved`: the cylinder meshed with its true bottom
/// and `4 n / 5` cells across the strip (mortar), else flat faces with the curvature in `g0`.
pub fn hertz_cylinder_on_block(n: usize, curved: bool) -> Result<HertzCase, LatinError> {
    let (e1, nu1, e2, nu2, r) = (210e3, 0.3, 70e3, 0.33, 50.0);
    let e_star = 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
    let p_total = std::f64::consts::PI * e_star / (4.0 * r);
    let b = (4.0 * p_total * r / (std::f64::consts::PI * e_star)).sqrt();
    let lay = ContactLayout {
        a: 2.1,
        l: 25.0,
        n,
        m: (7 * n).div_ceil(10).max(1),
        full: false,
    };
    let mesh_err = |sub: &str| {
        let sub = sub.to_string();
        move |source| LatinError::Mesh {
            sub: sub.clone(),
            source,
        }
    };
    let fem_err = |sub: &str| {
        let sub = sub.to_string();
        move |source| LatinError::Fem {
            sub: sub.clone(),
            source,
        }
    };
    let model = |mesh, e, nu, name: &str| -> Result<Model, LatinError> {
        let mut m =
            Model::new(mesh, Analysis::PlaneStrain { thickness: 1.0 }).map_err(fem_err(name))?;
        m.set_material_all(Material::new(e, nu, 0.0).map_err(fem_err(name))?);
        Ok(m)
    };
    let block = {
        let m = model(lay.lower().map_err(mesh_err("block"))?, e1, nu1, "block")?;
        let mut c = Constraints::new();
        c.fix_component(&m.mesh, "sym", 0, 0.0)
            .map_err(fem_err("block"))?;
        c.clamp(&m.mesh, "far").map_err(fem_err("block"))?;
        Substructure {
            name: "block".into(),
            model: m,
            constraints: c,
            load_cases: vec![],
        }
    };
    let cylinder = {
        let mesh = if curved {
            ContactLayout {
                n: (4 * n).div_ceil(5),
                ..lay
            }
            .upper_curved(r)
        } else {
            lay.upper()
        }
        .map_err(mesh_err("cylinder"))?;
        let m = model(mesh, e2, nu2, "cylinder")?;
        let mut c = Constraints::new();
        c.fix_component(&m.mesh, "sym", 0, 0.0)
            .map_err(fem_err("cylinder"))?;
        let load = 0.5 * p_total / lay.l;
        let mut loads = Loads::new(&m);
        loads
            .traction(&m, "far", move |_, _| [0.0, -load, 0.0])
            .map_err(fem_err("cylinder"))?;
        Substructure {
            name: "cylinder".into(),
            model: m,
            constraints: c,
            load_cases: vec![loads.f],
        }
    };
    let mut iface = InterfaceSpec::coulomb("contact", 0, "contact", 1, "contact", 0.0);
    if !curved {
        iface.gap = Arc::new(move |x: [f64; 3]| r - (r * r - x[0] * x[0]).sqrt());
    }
    Ok(HertzCase {
        assembly: Assembly {
            subs: vec![block, cylinder],
            interfaces: vec![iface],
        },
        half_width: b,
        peak_pressure: 2.0 * p_total / (std::f64::consts::PI * b),
    })
}
