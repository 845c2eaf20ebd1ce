//! What the estimator returns: the terms at one parameter point ([`PointEstimate`]) and their
//! expectations per entity and in total ([`Estimate`], crate doc "Totals"), with the relative
//! indicators `i_geo`, `i_sto` (4.8)-(4.9) that keep the sign of a negative part.

/// Terms of one substructure at one point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubPoint {
    /// `e_s^2 = 1/2 ||sigma~ - sigma_h1||^2` (3.30 integrand).
    pub e2: f64,
    /// `geo_s^2 = 1/2 ||sigma~ - sigma_h2||^2` (4.2 integrand).
    pub geo2: f64,
    /// `||sigma~||^2_{K^-1}` (4.8 denominator integrand); `||sigma_h1||^2_{K^-1}` for a
    /// substructure with FE samples only.
    pub norm2: f64,
}

/// Terms of one interface at one point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct InterfacePoint {
    /// `e_I = sum_i m_i rho*(w~, F~; mu(xi))` (3.31 integrand, crate doc).
    pub e: f64,
    /// `geo_I = sum_k w_k(xi) rho_k`, the runs' own interface errors interpolated.
    pub geo: f64,
}

/// Every term at one parameter point.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PointEstimate {
    /// Per substructure.
    pub subs: Vec<SubPoint>,
    /// Per interface.
    pub interfaces: Vec<InterfacePoint>,
    /// Largest relative violation of the interface admissibility (`w~_n >= 0`, `F_n >= 0`) at
    /// this point (0 if none).
    pub violation: f64,
}

impl PointEstimate {
    /// `e^2(xi)`: the CRE of the interpolated admissible solution (3.28 integrand).
    pub fn e2(&self) -> f64 {
        self.subs.iter().map(|s| s.e2).sum::<f64>()
            + self.interfaces.iter().map(|i| i.e).sum::<f64>()
    }

    /// Space part of `e^2(xi)`.
    pub fn geo2(&self) -> f64 {
        self.subs.iter().map(|s| s.geo2).sum::<f64>()
            + self.interfaces.iter().map(|i| i.geo).sum::<f64>()
    }

    /// Stochastic part `e^2 - geo^2` at `xi`.
    pub fn sto2(&self) -> f64 {
        self.e2() - self.geo2()
    }

    /// `sum_s ||sigma~_s||^2_{K^-1}` at `xi`.
    pub fn norm2(&self) -> f64 {
        self.subs.iter().map(|s| s.norm2).sum()
    }
}

/// Expectations of one entity's terms.
#[derive(Clone, Debug, PartialEq)]
pub struct EntityEstimate {
    /// Substructure or interface name.
    pub name: String,
    /// `E[e^2]` of the entity (3.30 / 3.31).
    pub e2: f64,
    /// `E[geo^2]` (4.2 / 4.4).
    pub geo2: f64,
    /// `E[e^2] - E[geo^2]` (4.3 / 4.5).
    pub sto2: f64,
    /// Substructures: the part of `e2` from the error of the mean fields (3.32); interfaces: 0.
    pub mean2: f64,
    /// Substructures: `e2 - mean2`, the part from the fluctuations (3.32); interfaces: 0.
    pub std2: f64,
}

/// The expectations over a rule (crate doc, "Totals").
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    /// Per substructure.
    pub subs: Vec<EntityEstimate>,
    /// Per interface.
    pub interfaces: Vec<EntityEstimate>,
    /// `e~^2` (3.28).
    pub e2: f64,
    /// `I_geo^2` (4.7).
    pub geo2: f64,
    /// `I_sto^2 = e~^2 - I_geo^2` (4.6).
    pub sto2: f64,
    /// `E[sum_s ||sigma~_s||^2_{K^-1}]`.
    pub norm2: f64,
    /// Per cell tag of the rule: `(cell, int sto(xi) f(xi) dxi, int e^2 f dxi)` over the cell
    /// (probability weights), cells in increasing tag order.
    pub cells: Vec<(usize, f64, f64)>,
    /// Probability (rule weight) of the points where the interpolated interface fields violate
    /// the admissibility beyond the tolerance (the estimate is then not a bound there).
    pub violation_probability: f64,
    /// Largest relative violation over the rule.
    pub max_violation: f64,
}

/// `sign(v) (|v| / norm2)^(1/2)`: a negative squared part keeps its sign (never a silent 0).
fn rel(v: f64, norm2: f64) -> f64 {
    if norm2 > 0.0 && v.is_finite() {
        v.signum() * (v.abs() / norm2).sqrt()
    } else {
        0.0
    }
}

impl Estimate {
    /// Relative error `e~ / (E[sum ||sigma~||^2])^(1/2)`.
    pub fn relative(&self) -> f64 {
        rel(self.e2, self.norm2)
    }

    /// `i_geo` (4.8); negative (`-(|I_geo^2| / norm)^(1/2)`) if `I_geo^2 < 0`, a defect that
    /// [`Estimate::negative_parts`] names.
    pub fn i_geo(&self) -> f64 {
        rel(self.geo2, self.norm2)
    }

    /// `i_sto` (4.9); negative if `I_sto^2 < 0` (see [`Estimate::i_geo`]).
    pub fn i_sto(&self) -> f64 {
        rel(self.sto2, self.norm2)
    }

    /// Relative share of an entity's `e2` (or `geo2`, `sto2`) in the normalisation, with the
    /// sign of `v`.
    pub fn relative_of(&self, v: f64) -> f64 {
        rel(v, self.norm2)
    }

    /// The squared parts that came out negative beyond round-off (`-1e-9 e~^2`), as messages
    /// naming the entity and the part: `I_sto^2` of an entity is `E[e^2] - E[geo^2]`, which no
    /// construction keeps non-negative (e.g. a substructure whose interpolated stresses fit the
    /// interpolated displacements better than the runs' own did). Empty when there is none.
    pub fn negative_parts(&self) -> Vec<String> {
        let tol = 1e-9 * self.e2.abs().max(f64::MIN_POSITIVE);
        let mut out = Vec::new();
        for (what, list) in [
            ("substructure", &self.subs),
            ("interface", &self.interfaces),
        ] {
            for e in list {
                for (part, v) in [("e~^2", e.e2), ("I_geo^2", e.geo2), ("I_sto^2", e.sto2)] {
                    if v < -tol {
                        out.push(format!(
                            "{what} '{}': {part} = {v:.3e} < 0 ({:.2} % of e~^2)",
                            e.name,
                            100.0 * v / self.e2.abs().max(f64::MIN_POSITIVE)
                        ));
                    }
                }
            }
        }
        for (part, v) in [
            ("e~^2", self.e2),
            ("I_geo^2", self.geo2),
            ("I_sto^2", self.sto2),
        ] {
            if v < -tol {
                out.push(format!("total: {part} = {v:.3e} < 0"));
            }
        }
        out
    }
}
