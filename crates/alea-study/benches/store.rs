//! What the store's durability costs: commits per second of run records with
//! `synchronous = NORMAL` and `FULL` (WAL journal), field data of a typical size (the 23k-dof
//! dovetail: 23 000 values) and without fields. Each commit stores its field data in the same
//! transaction as its row, as `alea run` does (`Store::commit`; `alea run` commits a group of
//! runs per transaction, `Store::commit_group`).
//!
//! Run: `cargo bench -p alea-study --bench store`

use std::time::Instant;

use alea_study::store::{Store, study_hash};

mod support;
use support::synthetic_record;

fn main() {
    let base = std::env::temp_dir().join(format!("alea-bench-store-{}", std::process::id()));
    let n = 200;
    println!("{n} commits each, median of 3 repetitions");
    println!(
        "{:>8} {:>12} {:>14} {:>12}",
        "sync", "field values", "ms per commit", "commits/s"
    );
    for values in [0usize, 23_000] {
        let mut per_level = Vec::new();
        for level in ["NORMAL", "FULL"] {
            let mut times = Vec::new();
            for rep in 0..3 {
                let dir = base.join(format!("{level}-{values}-{rep}"));
                let _ = std::fs::remove_dir_all(&dir);
                let store = Store::open(&dir, &study_hash("bench", &[]), false).unwrap();
                store.set_synchronous(level).unwrap();
                let fields = vec![0.25; values];
                let t0 = Instant::now();
                for i in 0..n {
                    let rec = synthetic_record(i, 100, 3, 4 * 3 * 200);
                    store.commit(&rec, &fields, None).unwrap();
                }
                times.push(t0.elapsed().as_secs_f64() / n as f64);
                let _ = std::fs::remove_dir_all(&dir);
            }
            times.sort_by(f64::total_cmp);
            let t = times[1];
            per_level.push(t);
            println!(
                "{level:>8} {values:>12} {:>14.3} {:>12.0}",
                1e3 * t,
                1.0 / t
            );
        }
        println!(
            "   FULL / NORMAL = {:.2} (fields of {values} values)",
            per_level[1] / per_level[0]
        );
    }
    let _ = std::fs::remove_dir_all(&base);
}
