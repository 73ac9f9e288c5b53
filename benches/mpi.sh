#!/usr/bin/env bash
# The overhead of MPI on this machine. Alternates, REPS times, the default
# binary on 2 threads, the MPI binary as one rank on 2 threads (K = 1) and as two ranks
# of one thread each, bound to a core each (K = 2), on
#   - measure: 10⁷ photons on the Cornell cone's scene (surface Cone);
#   - solve: the cornell-cone example with its own budget, no pictures or report;
# and prints each run's seconds (measure: its trace's `seconds`; solve: the search's
# `seconds` of result.json) as CSV: what,binary,k,rep,seconds.
#
#   PLAIN=… MPI=… benches/mpi.sh [REPS]      # REPS defaults to 3
set -euo pipefail
cd "$(dirname "$0")/.."
reps=${1:-3}
: "${PLAIN:?the default binary}" "${MPI:?the binary built with --features mpi}"
mpirun=(mpirun --allow-run-as-root)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene=examples/cornell-cone/cornell.dae
problem=examples/cornell-cone/problem.xml
seconds() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["seconds"])' "$1"; }
echo "what,binary,k,rep,seconds"
for rep in $(seq "$reps"); do
  for run in plain mpi1 mpi2; do
    case $run in
      plain) cmd=("$PLAIN") k=1 threads=2 ;;
      mpi1) cmd=("${mpirun[@]}" -np 1 --bind-to none "$MPI") k=1 threads=2 ;;
      mpi2) cmd=("${mpirun[@]}" -np 2 --bind-to core "$MPI") k=2 threads=1 ;;
    esac
    "${cmd[@]}" measure "$scene" -s Cone -n 10000000 --threads $threads --json > "$work/m.json" 2>/dev/null
    echo "measure,${run%[12]},$k,$rep,$(seconds "$work/m.json")"
    rm -rf "$work/out"
    "${cmd[@]}" solve "$problem" -o "$work/out" --threads $threads --no-images --no-report --json > /dev/null 2>&1
    echo "solve,${run%[12]},$k,$rep,$(seconds "$work/out/result.json")"
  done
done
