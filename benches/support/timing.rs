//! Timing helpers shared by the crates' benchmarks (each bench includes this file with
//! `#[path]`; nothing here is part of a library).

/// CPU seconds used so far by all threads of the process (sum of `/proc/self/task/*/schedstat`
/// run times; threads that have exited are not counted, rayon's pool threads persist); NaN
/// where `/proc` cannot be read.
pub fn cpu_seconds() -> f64 {
    let Ok(dir) = std::fs::read_dir("/proc/self/task") else {
        return f64::NAN;
    };
    dir.filter_map(|e| e.ok())
        .filter_map(|e| std::fs::read_to_string(e.path().join("schedstat")).ok())
        .filter_map(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .sum::<f64>()
        * 1e-9
}

/// Runs `f` inside a rayon pool of `threads` threads.
pub fn with_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
        .install(f)
}
