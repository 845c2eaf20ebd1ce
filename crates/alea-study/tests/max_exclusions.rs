//! Maximum-type quantities with exclusions, on a cantilever (10 x 2, clamped on x = 0, loaded
//! by a downward traction on x = 10): the nodal von Mises maximum sits on a clamped corner,
//! where the boundary groups `xmin` and `ymin` (or `ymax`) meet - a singular point. Leaving
//! out the clamped edge (`exclude_groups`), the nodes near the corners (`exclude_points` with
//! `exclude_radius`) or the corner nodes themselves (`exclude_nodes`) moves the maximum off
//! the excluded nodes, lowers it, and the new maximum is on no corner; the region average
//! over a disk around a corner is below the corner's nodal value and finite.

use alea_latin::LatinSolver;
use alea_study::Source;
use alea_study::qoi::QoiKind;
use alea_study::runner::Study;

const MODEL: &str = r#"
[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "rectangle"
kind = "quad4"
size = [10.0, 2.0]
cells = [40, 8]

[analysis]
type = "plane_stress"
thickness = 1.0

[[parameter]]
name = "E"
law = "uniform"
lo = 150e3
hi = 250e3

[[substructure]]
name = "beam"
young = "E"
poisson = 0.3
constraint = [ { group = "xmin", x = 0.0, y = 0.0 } ]
load = [ { group = "xmax", traction = [0.0, -10.0] } ]

[[method]]
type = "piecewise_linear"
points_per_dim = 2

[[quantity]]
name = "all"
kind = "max_von_mises"
substructure = "beam"

[[quantity]]
name = "no_clamp"
kind = "max_von_mises"
substructure = "beam"
exclude_groups = ["xmin"]

[[quantity]]
name = "no_corners"
kind = "max_von_mises"
substructure = "beam"
exclude_points = [[0.0, 0.0], [0.0, 2.0]]
exclude_radius = 0.6

[[quantity]]
name = "region"
kind = "mean_von_mises"
substructure = "beam"
point = [0.0, 0.0]
radius = 0.5
"#;

#[test]
fn exclusions_move_the_maximum_off_the_singular_corners() {
    let study = Study::from_source(Source::from_text("beam.toml", MODEL)).unwrap();
    let solver =
        LatinSolver::new(study.model.assembly.clone(), study.model.options.clone()).unwrap();
    let res = solver
        .run_shared(&study.model.parametric.run_input(&[200e3]))
        .unwrap();
    let model = res.scaled_model(solver.model(0), 0);
    let u = &res.displacements[0];
    let coords = &model.mesh.coords;
    let loc = |name: &str| {
        let q = study.qois.iter().find(|q| q.name == name).unwrap();
        q.max_location(&model, u).unwrap().unwrap()
    };
    let all = loc("all");
    let x = coords[all.node];
    assert!(x[0] == 0.0 && (x[1] == 0.0 || x[1] == 2.0), "{x:?}");
    let groups = all.junction.clone().unwrap();
    assert!(groups.0 == "xmin" || groups.1 == "xmin", "{groups:?}");
    for name in ["no_clamp", "no_corners"] {
        let m = loc(name);
        assert!(m.value < all.value, "{name}: {} vs {}", m.value, all.value);
        assert!(m.junction.is_none(), "{name}: {:?}", m.junction);
    }
    assert!(coords[loc("no_clamp").node][0] > 0.0);
    let nc = coords[loc("no_corners").node];
    for c in [[0.0, 0.0], [0.0, 2.0]] {
        assert!((nc[0] - c[0]).hypot(nc[1] - c[1]) > 0.6);
    }
    // Excluding the corner node by its number gives the next node's maximum, not on it.
    let text = format!(
        "{MODEL}\n[[quantity]]\nname = \"no_node\"\nkind = \"max_von_mises\"\nsubstructure = \"beam\"\nexclude_nodes = [{}]\n",
        all.node
    );
    let st2 = Study::from_source(Source::from_text("beam.toml", &text)).unwrap();
    let q = st2.qois.iter().find(|q| q.name == "no_node").unwrap();
    let m = q.max_location(&model, u).unwrap().unwrap();
    assert_ne!(m.node, all.node);
    assert!(m.value <= all.value);
    // The average over a disk of radius 0.5 around the corner: below the corner's value.
    let region = study.qois.iter().find(|q| q.name == "region").unwrap();
    assert!(matches!(region.kind, QoiKind::MeanVonMises { .. }));
    let mean = region.eval(&solver, &res).unwrap();
    assert!(mean > 0.0 && mean < all.value, "{mean} vs {}", all.value);
}

#[test]
fn exclusions_that_leave_nothing_or_name_nothing_are_input_errors() {
    let err = |extra: &str| {
        Study::from_source(Source::from_text(
            "beam.toml",
            &format!("{MODEL}\n[[quantity]]\nname = \"bad\"\nsubstructure = \"beam\"\n{extra}"),
        ))
        .unwrap_err()
        .to_string()
    };
    let e =
        err("kind = \"max_von_mises\"\nexclude_points = [[5.0, 1.0]]\nexclude_radius = 100.0\n");
    assert!(e.contains("no node left"), "{e}");
    let e = err("kind = \"max_von_mises\"\nexclude_groups = [\"nowhere\"]\n");
    assert!(e.contains("exclude_groups") && e.contains("nowhere"), "{e}");
    let e = err("kind = \"max_von_mises\"\nexclude_nodes = [100000]\n");
    assert!(e.contains("exclude_nodes") && e.contains("100000"), "{e}");
    let e = err("kind = \"max_von_mises\"\nexclude_points = [[5.0, 1.0]]\n");
    assert!(e.contains("exclude_radius") && e.contains("missing"), "{e}");
    let e = err("kind = \"mean_von_mises\"\nradius = 0.5\n");
    assert!(e.contains("point") && e.contains("missing"), "{e}");
    let e = err("kind = \"mean_von_mises\"\ngroup = \"xmin\"\n");
    assert!(e.contains("cell group"), "{e}");
}
