#!/bin/sh
# Monte Carlo study on the model of the 2D turbine (examples/turbine-2d-wear.toml: its model and
# [solver] settings, its methods and rare-event tables replaced by one Monte Carlo method of N
# runs), solved with [solver] linear_stage forced to each of the given values (issue 41).
# Usage: scripts/condensed_bench.sh N [threads] [stages...]   (default stages: volume condensed)
# Prints wall time, user CPU and peak memory of `alea run` per stage; the studies and their
# directories go to ${TMPDIR:-/tmp}/condensed-bench.
set -eu
n=${1:?runs}
threads=${2:-2}
shift $(( $# < 2 ? $# : 2 ))
stages=${*:-volume condensed}
alea=${ALEA:-${CARGO_TARGET_DIR:-target}/release/alea}
root=$(cd "$(dirname "$0")/.." && pwd)
out=${TMPDIR:-/tmp}/condensed-bench
mkdir -p "$out"
for stage in $stages; do
  study="$out/turbine-mc-$n-$stage.toml"
  sed -n '1,/^\[\[method\]\]/p' "$root/examples/turbine-2d-wear.toml" | sed '$d' > "$study"
  cat >> "$study" <<EOT
[[method]]
type = "monte_carlo"
runs = $n
label = "Monte Carlo $n"

[solver]
tolerance = 1.4e-6
max_iterations = 5000
search_direction_factor = 1.0
search_direction_tangential = 0.25
linear_stage = "$stage"
EOT
  dir="$out/turbine-mc-$n-$stage"
  rm -rf "$dir"
  /usr/bin/time -f "$stage: N=$n threads=$threads wall %e s, user %U s, max RSS %M kB" \
    "$alea" run "$study" --dir "$dir" --threads "$threads" -q
done
