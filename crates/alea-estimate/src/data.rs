//! What the estimator needs of the model (a [`Layout`], fixed for a study) and of each run
//! (a [`RunData`]), and a compact binary form of the latter for a study's store.

use alea_uq::bytes::{ByteReader, ByteWriter, BytesError};

use crate::EstimateError;

/// One substructure: the length of its sample vectors and where each cell's samples start.
#[derive(Clone, Debug, PartialEq)]
pub struct SubLayout {
    /// Name (for messages and outputs).
    pub name: String,
    /// Offset of each cell's samples (`num_cells + 1` entries; the last is the vector length).
    /// Empty when the substructure is left out entirely: it then contributes nothing.
    pub cell_offsets: Vec<usize>,
    /// True when the runs give admissible samples: the substructure has its error terms.
    /// False for a substructure with FE samples only (e.g. 3D cells whose admissible stress is
    /// not built): no error term, but its FE energy `||sigma_h1||^2` still enters the
    /// normalisation of the relative indicators (crate doc, "Substructures without admissible
    /// stress").
    pub admissible: bool,
}

impl SubLayout {
    /// Length of a sample vector (0 when the substructure is left out).
    pub fn len(&self) -> usize {
        self.cell_offsets.last().copied().unwrap_or(0)
    }

    /// True if the substructure is left out (no samples at all).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// True if the substructure has its error terms (admissible and FE samples).
    pub fn is_estimated(&self) -> bool {
        self.admissible && !self.is_empty()
    }

    /// Length of the admissible sample vectors of a run (0 without admissible samples).
    pub fn admissible_len(&self) -> usize {
        if self.admissible { self.len() } else { 0 }
    }

    /// Number of cells (0 when left out).
    pub fn num_cells(&self) -> usize {
        self.cell_offsets.len().saturating_sub(1)
    }
}

/// The behaviour of an interface, as far as the estimator is concerned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InterfaceKind {
    /// Bonded: density `w . F`, no stochastic part.
    Perfect,
    /// Unilateral contact with Coulomb friction `mu(x, xi)`.
    Contact,
}

/// One interface: lumped point weights and normals (side 1's outward normal).
#[derive(Clone, Debug, PartialEq)]
pub struct InterfaceLayout {
    /// Name.
    pub name: String,
    /// Behaviour.
    pub kind: InterfaceKind,
    /// Integration weight of each point.
    pub weights: Vec<f64>,
    /// Unit normal at each point.
    pub normals: Vec<[f64; 3]>,
}

/// The entities of the model.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// Substructures.
    pub subs: Vec<SubLayout>,
    /// Interfaces.
    pub interfaces: Vec<InterfaceLayout>,
}

/// The admissible solution of one run (module doc of the crate).
#[derive(Clone, Debug, PartialEq)]
pub struct RunData {
    /// Young's-modulus factor of each substructure in this run.
    pub young: Vec<f64>,
    /// Per substructure: samples of the admissible stress `sigma_hat` (empty when the layout
    /// has none for it).
    pub admissible: Vec<Vec<f64>>,
    /// Per substructure: samples of the FE stress `sigma_h` (same layout).
    pub fe: Vec<Vec<f64>>,
    /// Per interface and point: the jump `w_hat` (gap included) of local stage `n - 1`.
    pub jump: Vec<Vec<[f64; 3]>>,
    /// Per interface and point: the force `F_hat` on side 2 of local stage `n`.
    pub force: Vec<Vec<[f64; 3]>>,
}

impl Layout {
    /// Checks a run's data against the layout: counts, lengths, finite values, factors > 0.
    ///
    /// # Errors
    /// [`EstimateError::Invalid`] naming the first inconsistency.
    pub fn check(&self, run: &RunData) -> Result<(), EstimateError> {
        let ns = self.subs.len();
        let ni = self.interfaces.len();
        if run.young.len() != ns || run.admissible.len() != ns || run.fe.len() != ns {
            return Err(EstimateError::Invalid(format!(
                "{ns} substructures, but the run has {} Young's factors, {} admissible and {} FE sample vectors",
                run.young.len(),
                run.admissible.len(),
                run.fe.len()
            )));
        }
        if run.jump.len() != ni || run.force.len() != ni {
            return Err(EstimateError::Invalid(format!(
                "{ni} interfaces, but the run has {} jump and {} force fields",
                run.jump.len(),
                run.force.len()
            )));
        }
        for (s, sub) in self.subs.iter().enumerate() {
            let a = run.young[s];
            if !(a.is_finite() && a > 0.0) {
                return Err(EstimateError::Invalid(format!(
                    "substructure '{}': Young's factor {a}",
                    sub.name
                )));
            }
            for (what, v, len) in [
                ("admissible", &run.admissible[s], sub.admissible_len()),
                ("FE", &run.fe[s], sub.len()),
            ] {
                if v.len() != len {
                    return Err(EstimateError::Invalid(format!(
                        "substructure '{}': {what} samples of length {}, expected {len}",
                        sub.name,
                        v.len(),
                    )));
                }
                if v.iter().any(|x| !x.is_finite()) {
                    return Err(EstimateError::Invalid(format!(
                        "substructure '{}': non-finite {what} sample",
                        sub.name
                    )));
                }
            }
        }
        for (i, it) in self.interfaces.iter().enumerate() {
            let np = it.weights.len();
            if it.normals.len() != np || run.jump[i].len() != np || run.force[i].len() != np {
                return Err(EstimateError::Invalid(format!(
                    "interface '{}': {np} points, {} normals, {} jumps, {} forces",
                    it.name,
                    it.normals.len(),
                    run.jump[i].len(),
                    run.force[i].len()
                )));
            }
            if run.jump[i]
                .iter()
                .chain(&run.force[i])
                .flatten()
                .any(|x| !x.is_finite())
            {
                return Err(EstimateError::Invalid(format!(
                    "interface '{}': non-finite jump or force",
                    it.name
                )));
            }
        }
        Ok(())
    }
}

const MAGIC: &[u8; 8] = b"aleaCRE1";

impl RunData {
    /// Little-endian binary form (`alea_uq::bytes`): a magic, the counts, then every array in
    /// field order.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut w = ByteWriter::new();
        w.raw(MAGIC);
        w.u64(self.young.len() as u64).u64(self.jump.len() as u64);
        for v in self.admissible.iter().chain(&self.fe) {
            w.u64(v.len() as u64);
        }
        for v in self.jump.iter().chain(&self.force) {
            w.u64(v.len() as u64);
        }
        w.f64s(&self.young);
        for v in self.admissible.iter().chain(&self.fe) {
            w.f64s(v);
        }
        for v in self.jump.iter().chain(&self.force) {
            for p in v {
                w.f64s(p);
            }
        }
        w.into_bytes()
    }

    /// Inverse of [`RunData::to_bytes`].
    ///
    /// # Errors
    /// [`EstimateError::Invalid`] for a truncated or foreign byte string.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, EstimateError> {
        Self::read(&mut ByteReader::new(bytes)).map_err(|e| {
            EstimateError::Invalid(format!(
                "run data: truncated or not an estimator file ({e})"
            ))
        })
    }

    fn read(c: &mut ByteReader<'_>) -> Result<Self, BytesError> {
        if c.take(8)? != MAGIC {
            return Err(BytesError("no magic".into()));
        }
        // Every count is checked against the bytes left before anything is allocated.
        let ns = c.count(8)?;
        let ni = c.count(8)?;
        let sub_lens = (0..2 * ns)
            .map(|_| c.count(8))
            .collect::<Result<Vec<_>, _>>()?;
        let if_lens = (0..2 * ni)
            .map(|_| c.count(24))
            .collect::<Result<Vec<_>, _>>()?;
        let total = ns as u128
            + sub_lens.iter().map(|&n| n as u128).sum::<u128>()
            + 3 * if_lens.iter().map(|&n| n as u128).sum::<u128>();
        if total * 8 != c.remaining() as u128 {
            return Err(BytesError(format!(
                "{} bytes of values where the counts say {}",
                c.remaining(),
                total * 8
            )));
        }
        let young = c.f64s(ns)?;
        let mut admissible = Vec::with_capacity(ns);
        for &n in &sub_lens[..ns] {
            admissible.push(c.f64s(n)?);
        }
        let mut fe = Vec::with_capacity(ns);
        for &n in &sub_lens[ns..] {
            fe.push(c.f64s(n)?);
        }
        let mut points = |n: usize| -> Result<Vec<[f64; 3]>, BytesError> {
            Ok(c.f64s(3 * n)?
                .chunks_exact(3)
                .map(|v| [v[0], v[1], v[2]])
                .collect())
        };
        let jump = if_lens[..ni]
            .iter()
            .map(|&n| points(n))
            .collect::<Result<_, _>>()?;
        let force = if_lens[ni..]
            .iter()
            .map(|&n| points(n))
            .collect::<Result<_, _>>()?;
        Ok(RunData {
            young,
            admissible,
            fe,
            jump,
            force,
        })
    }
}
