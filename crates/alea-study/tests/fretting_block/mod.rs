//! The study file of the fretting-cycle tests (`fretting_cycle.rs`, `fretting_cycle_large.rs`):
//! a 40 x 20 mm block of steel on a 40 x 20 mm aluminium base, plane strain, Coulomb contact
//! with `mu` uniform on [0.3, 0.35], solver tolerance 1e-9, a Monte Carlo method.

/// The block on the base, its top loaded by `top` (loads and/or constraint), with the
/// interface's `sliding`, then `steps`, `cycle` and `quantities`; `title`, and `runs` Monte
/// Carlo runs.
pub fn block_on_base(
    title: &str,
    top: &str,
    sliding: &str,
    steps: &str,
    cycle: &str,
    quantities: &str,
    runs: usize,
) -> String {
    format!(
        r#"
[study]
title = "{title}"
seed = 3

[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "stacked_blocks"
kind = "quad4"
params = {{ width = 40.0, h_lower = 20.0, h_upper = 20.0, n_x = 20, n_lower = 10, n_upper = 10 }}

[analysis]
type = "plane_strain"
thickness = 1.0

[[parameter]]
name = "mu"
law = "uniform"
lo = 0.3
hi = 0.35

[[substructure]]
name = "base"
cells = "lower"
young = 70e3
poisson = 0.3
constraint = [ {{ group = "lower_bottom", x = 0.0, y = 0.0 }} ]

[[substructure]]
name = "block"
cells = "upper"
young = 210e3
poisson = 0.3
{top}

[[interface]]
name = "contact"
side1 = ["base", "lower_top"]
side2 = ["block", "upper_bottom"]
law = "coulomb"
mu = "mu"
sliding = "{sliding}"

[solver]
tolerance = 1e-9

{steps}

{cycle}

{quantities}

[[method]]
type = "monte_carlo"
runs = {runs}
"#
    )
}
