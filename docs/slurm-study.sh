#!/bin/bash
# A study on a Slurm cluster: 8 nodes x 8 ranks, 4 cores per rank (alea's solver threads).
# Build once on a login node with the cluster's MPI loaded:
#   module load openmpi            # or your site's MPI module (mpicc must be on the PATH)
#   cargo build --release --features mpi
# Then: sbatch docs/slurm-study.sh path/to/study.toml
#SBATCH --job-name=alea-study
#SBATCH --nodes=8
#SBATCH --ntasks-per-node=8
#SBATCH --cpus-per-task=4
#SBATCH --time=12:00:00
#SBATCH --output=alea-%j.out
set -euo pipefail
module load openmpi 2>/dev/null || true

STUDY=${1:?usage: sbatch slurm-study.sh study.toml [study directory]}
# On a shared filesystem: rank 0 writes the store and the outputs there; a rerun of this same
# script resumes from it (with any node count) and recomputes no committed run.
DIR=${2:-$SLURM_SUBMIT_DIR/out/$(basename "$STUDY" .toml)}

# One rank per task; each rank uses its task's cores for its solver threads.
srun --cpu-bind=cores target/release/alea run "$STUDY" --dir "$DIR" --threads "$SLURM_CPUS_PER_TASK" -q
# Without srun's PMI support: mpirun -np "$SLURM_NTASKS" target/release/alea run ...
