//! A linear-elastic model: a mesh, the 2D/3D analysis kind and per-cell-group materials.

use alea_mesh::Mesh;

use crate::{Analysis, FemError, Material};

/// Mesh + analysis + materials.
#[derive(Clone, Debug)]
pub struct Model {
    /// The mesh.
    pub mesh: Mesh,
    /// Plane strain / plane stress / solid.
    pub analysis: Analysis,
    materials: Vec<Material>,
    cell_material: Vec<Option<u32>>,
}

impl Model {
    /// A model with no material assigned yet.
    ///
    /// # Errors
    /// If the analysis dimension does not match the mesh, or the thickness is not positive.
    pub fn new(mesh: Mesh, analysis: Analysis) -> Result<Self, FemError> {
        if analysis.dim() != mesh.dim {
            return Err(FemError::Setup(format!(
                "a {}D mesh needs a {}D analysis, got {analysis:?}",
                mesh.dim,
                analysis.dim()
            )));
        }
        let t = analysis.thickness();
        if !(t.is_finite() && t > 0.0) {
            return Err(FemError::Setup(format!("thickness must be > 0, got {t}")));
        }
        mesh.validate()?;
        let n = mesh.num_cells();
        Ok(Model {
            mesh,
            analysis,
            materials: Vec::new(),
            cell_material: vec![None; n],
        })
    }

    /// Assigns `material` to every cell.
    pub fn set_material_all(&mut self, material: Material) -> &mut Self {
        self.materials.push(material);
        let id = (self.materials.len() - 1) as u32;
        self.cell_material.fill(Some(id));
        self
    }

    /// Assigns `material` to the cells of a group (later assignments win).
    pub fn set_material(&mut self, group: &str, material: Material) -> Result<&mut Self, FemError> {
        let cells = self.mesh.cell_group(group)?.to_vec();
        self.materials.push(material);
        let id = (self.materials.len() - 1) as u32;
        for c in cells {
            self.cell_material[c] = Some(id);
        }
        Ok(self)
    }

    /// The material of cell `c`.
    pub fn material(&self, c: usize) -> Result<&Material, FemError> {
        self.cell_material[c]
            .map(|i| &self.materials[i as usize])
            .ok_or_else(|| FemError::Setup(format!("cell {c} has no material assigned")))
    }

    /// Scales every material's Young's modulus by `factor` (used when E is a parameter).
    pub fn scale_young(&mut self, factor: f64) {
        for m in &mut self.materials {
            m.young *= factor;
        }
    }

    /// Multiplies the Young's modulus of each cell `c` by `factors[c]` (a Young's modulus
    /// varying from cell to cell, e.g. a random field): every cell gets a material of its own.
    ///
    /// # Errors
    /// If `factors` does not have one entry per cell, an entry is not finite and > 0, or a cell
    /// has no material.
    pub fn scale_young_per_cell(&mut self, factors: &[f64]) -> Result<(), FemError> {
        let n = self.mesh.num_cells();
        if factors.len() != n {
            return Err(FemError::Setup(format!(
                "{} Young's-modulus factors for {n} cells",
                factors.len()
            )));
        }
        if let Some(c) = factors.iter().position(|f| !(f.is_finite() && *f > 0.0)) {
            return Err(FemError::Setup(format!(
                "Young's-modulus factor of cell {c} must be finite and > 0, got {}",
                factors[c]
            )));
        }
        let mut materials = Vec::with_capacity(n);
        for (c, f) in factors.iter().enumerate() {
            let mut m = *self.material(c)?;
            m.young *= f;
            materials.push(m);
        }
        self.materials = materials;
        self.cell_material = (0..n as u32).map(Some).collect();
        Ok(())
    }

    /// The model of some of its cells: `mesh` is the sub-mesh of cells `cells` of this
    /// model's mesh (`cells[new] = old`, as [`alea_mesh::Mesh::extract_with_cells`] gives),
    /// each keeping its material (module `alea_latin::split`).
    ///
    /// # Errors
    /// If `cells` does not have one entry per cell of `mesh`, or names a cell this model does
    /// not have.
    pub fn restricted(&self, mesh: Mesh, cells: &[usize]) -> Result<Model, FemError> {
        if cells.len() != mesh.num_cells() {
            return Err(FemError::Setup(format!(
                "{} cells mapped for a mesh of {}",
                cells.len(),
                mesh.num_cells()
            )));
        }
        if let Some(&c) = cells.iter().find(|&&c| c >= self.cell_material.len()) {
            return Err(FemError::Setup(format!("cell {c} is not in the model")));
        }
        let cell_material = cells.iter().map(|&c| self.cell_material[c]).collect();
        Ok(Model {
            mesh,
            analysis: self.analysis,
            materials: self.materials.clone(),
            cell_material,
        })
    }

    /// Checks that every cell has a material.
    pub fn check(&self) -> Result<(), FemError> {
        if let Some(c) = self.cell_material.iter().position(|m| m.is_none()) {
            return Err(FemError::Setup(format!(
                "cell {c} ({}) has no material assigned",
                self.mesh.cell_type(c)
            )));
        }
        Ok(())
    }

    /// Coordinates of the nodes of cell `c`.
    pub fn cell_coords(&self, c: usize) -> Vec<[f64; 3]> {
        let mut out = Vec::new();
        self.cell_coords_into(c, &mut out);
        out
    }

    /// [`Model::cell_coords`] into `out` (cleared first), for loops over cells that reuse one
    /// buffer.
    pub fn cell_coords_into(&self, c: usize, out: &mut Vec<[f64; 3]>) {
        out.clear();
        out.extend(self.mesh.cell_nodes(c).iter().map(|&n| self.mesh.coords[n]));
    }
}
