//! The runs behind the narrow interface (`alea_estimate::runs`): an estimator built from a
//! `RunSource` substructure by substructure is the one built from the runs' data at once (same
//! expectations, bit for bit); the cell terms of a substructure add up to its expectation; the
//! load-factor defect is zero for affine factors under piecewise-linear interpolation and equals
//! the exact interpolation error `h^2 / 4 max |f''| / 2` for a quadratic one.

use alea_estimate::rule::Rule;
use alea_estimate::{
    EstimateError, Estimator, EstimatorOptions, InterfaceKind, InterfaceLayout, InterfaceVectors,
    Layout, Parameters, RunData, RunSource, SubLayout, SubstructureMoments, Weights, load_defect,
    sub_cell_terms, weight_moments,
};

/// Young's factor `1 + 0.5 xi`, friction 0.3.
struct Params;

impl Parameters for Params {
    fn young(&self, xi: &[f64], out: &mut [f64]) {
        out[0] = 1.0 + 0.5 * xi[0];
    }
    fn friction(&self, _xi: &[f64], _interface: usize, out: &mut [f64]) {
        out.fill(0.3);
    }
}

/// Piecewise-linear interpolation (hat functions) on runs at `0, 1/2, 1`.
struct Hats;

impl Weights for Hats {
    fn weights(&self, xi: &[f64], w: &mut Vec<(usize, f64)>) {
        w.clear();
        let x = xi[0].clamp(0.0, 1.0);
        let (k, t) = if x < 0.5 {
            (0, 2.0 * x)
        } else {
            (1, 2.0 * x - 1.0)
        };
        w.push((k, 1.0 - t));
        w.push((k + 1, t));
    }
}

/// A load factor as a function of the parameter point.
type Factor<'a> = &'a dyn Fn(&[f64]) -> f64;

const RUNS: [f64; 3] = [0.0, 0.5, 1.0];

fn layout() -> Layout {
    Layout {
        subs: vec![SubLayout {
            name: "S".into(),
            cell_offsets: vec![0, 4, 8, 12],
            admissible: true,
        }],
        interfaces: vec![InterfaceLayout {
            name: "I".into(),
            kind: InterfaceKind::Contact,
            weights: vec![0.5, 0.7],
            normals: vec![[0.0, 1.0, 0.0]; 2],
        }],
    }
}

/// Run data at `x`: samples varying with `x`; an open point, and a point open at `x = 0` and
/// closed (sticking) elsewhere, so that the interpolated fields between the first two runs
/// hold a gap and a pressure at once.
fn run_at(x: f64) -> RunData {
    let (jump0, force0) = if x == 0.0 {
        ([0.0, 0.1, 0.0], [0.0; 3])
    } else {
        ([0.0; 3], [0.1 * x, 1.0 + x, 0.0])
    };
    let h: Vec<f64> = (0..12)
        .map(|i| (1.0 + 0.3 * i as f64).sin() * (1.0 + x))
        .collect();
    let a: Vec<f64> = h
        .iter()
        .enumerate()
        .map(|(i, v)| v + 0.1 * (i as f64 * (1.0 + x)).cos())
        .collect();
    RunData {
        young: vec![1.0 + 0.5 * x],
        admissible: vec![a],
        fe: vec![h],
        jump: vec![vec![jump0, [0.0, 0.1 + x, 0.0]]],
        force: vec![vec![force0, [0.0; 3]]],
    }
}

/// The runs' data read one substructure sample at a time.
struct Source(Vec<RunData>);

impl RunSource for Source {
    type Error = EstimateError;
    fn num_runs(&self) -> usize {
        self.0.len()
    }
    fn young(&self, k: usize, s: usize) -> Result<f64, EstimateError> {
        Ok(self.0[k].young[s])
    }
    fn samples(&self, k: usize, s: usize) -> Result<(Vec<f64>, Vec<f64>), EstimateError> {
        Ok((self.0[k].admissible[s].clone(), self.0[k].fe[s].clone()))
    }
    fn interface_fields(&self, k: usize) -> (InterfaceVectors, InterfaceVectors) {
        (self.0[k].jump.clone(), self.0[k].force.clone())
    }
}

fn gauss_rule() -> Rule {
    // Two Gauss points on each of the cells [0, 1/2], [1/2, 1].
    let g = 0.5 / 3f64.sqrt();
    let points = vec![
        0.25 - 0.5 * g,
        0.25 + 0.5 * g,
        0.75 - 0.5 * g,
        0.75 + 0.5 * g,
    ];
    Rule::new(1, points, vec![0.25; 4], vec![0, 0, 1, 1]).unwrap()
}

#[test]
fn an_estimator_from_a_run_source_is_the_one_from_the_runs_data() {
    let runs: Vec<RunData> = RUNS.iter().map(|&x| run_at(x)).collect();
    let points: Vec<Vec<f64>> = RUNS.iter().map(|&x| vec![x]).collect();
    let options = EstimatorOptions::default();
    let direct = Estimator::new(layout(), &runs, &points, &Params, options).unwrap();
    let source = Source(runs);
    let built = Estimator::from_runs(layout(), &source, &points, &Params, options).unwrap();
    let rule = gauss_rule();
    let a = direct.expectation(&rule, &Hats, &Params);
    let b = built.expectation(&rule, &Hats, &Params);
    assert_eq!(a, b);
    assert!(a.subs[0].e2 > 0.0 && a.interfaces[0].e2 > 0.0);
    // The cell terms add up to the substructure's expectation.
    let moments = weight_moments(&rule, &Hats, &Params, 1, RUNS.len());
    let cells = sub_cell_terms(&source, 0, &layout().subs[0].cell_offsets, &moments[0]).unwrap();
    assert_eq!(cells.len(), 3);
    let total: f64 = cells.iter().map(|c| c.1).sum();
    let geo: f64 = cells.iter().map(|c| c.0).sum();
    assert!(
        (total - a.subs[0].e2).abs() <= 1e-12 * a.subs[0].e2,
        "{total} vs {}",
        a.subs[0].e2
    );
    assert!((geo - a.subs[0].geo2).abs() <= 1e-12 * a.subs[0].geo2.max(1e-300));
}

#[test]
fn samples_of_the_wrong_length_are_refused_not_a_panic() {
    let mut runs: Vec<RunData> = RUNS.iter().map(|&x| run_at(x)).collect();
    runs[1].fe[0].pop();
    let points: Vec<Vec<f64>> = RUNS.iter().map(|&x| vec![x]).collect();
    let source = Source(runs);
    let built = Estimator::from_runs(
        layout(),
        &source,
        &points,
        &Params,
        EstimatorOptions::default(),
    );
    assert!(matches!(built, Err(EstimateError::Invalid(_))));
    let moments = weight_moments(&gauss_rule(), &Hats, &Params, 1, RUNS.len());
    let offsets = &layout().subs[0].cell_offsets;
    let cells = sub_cell_terms(&source, 0, offsets, &moments[0]);
    assert!(matches!(cells, Err(EstimateError::Invalid(_))), "{cells:?}");
    // Moments of another number of runs.
    let good = Source(RUNS.iter().map(|&x| run_at(x)).collect());
    let two = SubstructureMoments {
        inv_alpha: vec![1.0; 4],
        one: vec![1.0; 4],
        alpha: vec![1.0; 4],
    };
    assert!(matches!(
        sub_cell_terms(&good, 0, offsets, &two),
        Err(EstimateError::Invalid(_))
    ));
}

#[test]
fn load_defect_is_the_interpolation_error_of_the_load_factors() {
    let points: Vec<Vec<f64>> = RUNS.iter().map(|&x| vec![x]).collect();
    // Midpoints of the two cells: the largest interpolation error of x^2 is h^2 / 4 with h = 1/2
    // (|f''| / 2 = 1), 1/16, relative to max |f| = 1 at the runs.
    let rule = Rule::equal_weights(1, vec![0.25, 0.75, 0.1]).unwrap();
    let affine = load_defect(&rule, &Hats, &points, [|x: &[f64]| 2.0 + 3.0 * x[0]]);
    assert!(affine <= 1e-15, "{affine}");
    let quadratic = load_defect(&rule, &Hats, &points, [|x: &[f64]| x[0] * x[0]]);
    assert!((quadratic - 1.0 / 16.0).abs() <= 1e-15, "{quadratic}");
    // A factor that vanishes at every run is skipped; the worst factor counts.
    let cubic = |x: &[f64]| x[0] * (1.0 - x[0]) * (x[0] - 0.5);
    assert_eq!(load_defect(&rule, &Hats, &points, [cubic]), 0.0);
    let both: [Factor; 2] = [&|x| 2.0 + 3.0 * x[0], &|x| 4.0 * x[0] * x[0]];
    let worst = load_defect(&rule, &Hats, &points, both);
    assert!((worst - 1.0 / 16.0).abs() <= 1e-15, "{worst}");
}
