#! /bin/bash
# One `alea serve` instance as a HyperQueue job of UM-Bridge's load balancer
# (https://github.com/UM-Bridge/umbridge, directory hpc/): copy this file over the load
# balancer's hpc/hq_scripts/job.sh and set the three paths below. The load balancer, on a login
# node, asks HyperQueue for workers (SLURM or PBS allocations, hq_scripts/allocation_queue.sh)
# as evaluation requests arrive, starts this script on them, and forwards requests to the URL
# the script writes.
#
#HQ --resource model=1
#HQ --time-request=1m
#HQ --time-limit=2h
#HQ --stdout none
#HQ --stderr none

alea=/path/to/alea                           # CHANGE ME: target/release/alea
study=/path/to/study.toml                    # CHANGE ME: the study whose model is served
load_balancer_dir=/path/to/umbridge/hpc      # CHANGE ME: where the load balancer runs

# Each instance has a study directory of its own (a directory is locked by one process);
# instances on the same study file reuse their own runs when restarted with the same job id.
dir="$(dirname "$study")/serve-$HQ_JOB_ID"
port=4242
host=$(hostname -I | awk '{print $1}')

# Every address of the node (the load balancer connects from the login node); the solver's
# threads: the CPUs this process may use (nproc follows the job's CPU binding).
"$alea" serve "$study" --dir "$dir" --host 0.0.0.0 --port "$port" --threads "$(nproc)" &

# Wait for the model to answer, then tell the load balancer where it is.
while ! curl -s "http://$host:$port/Info" > /dev/null; do
    sleep 1
done
mkdir -p "$load_balancer_dir/urls"
echo "http://$host:$port" > "$load_balancer_dir/urls/url-$HQ_JOB_ID.txt"

sleep infinity # keep the job, and so the allocation, for this server
