//! A study file shared by the load-time tests of laws and joint laws: a 10 x 2 mm plate in
//! plane stress, clamped on its left edge and pulled by 1 MPa on its right one, with the
//! given `[[parameter]]` / `[joint]` tables, Young's modulus `young` (an expression of the
//! parameters), its tip displacement as the quantity and a 4-run Monte Carlo method.

/// The study file's text.
pub fn plate_study(title: &str, laws: &str, young: &str) -> String {
    format!(
        r#"
[study]
title = "{title}"

[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "rectangle"
kind = "quad4"
size = [10.0, 2.0]
cells = [2, 1]

[analysis]
type = "plane_stress"

{laws}

[[substructure]]
name = "plate"
young = "{young}"
poisson = 0.0
constraint = [ {{ group = "xmin", x = 0.0 }}, {{ group = "ymin", y = 0.0 }} ]
load = [ {{ group = "xmax", traction = [1.0, 0.0] }} ]

[[quantity]]
name = "tip"
kind = "displacement"
substructure = "plate"
point = [10.0, 2.0]
component = 0

[[method]]
type = "monte_carlo"
runs = 4
"#
    )
}
