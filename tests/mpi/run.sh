#!/usr/bin/env bash
# The same solve on an MPI job of K ranks, bit-identical to one process.
# Runs measure, map and solve (two examples) with `mpirun -np 1/2/3` of a binary built
# with `--features mpi` and with the default binary, and compares their outputs with
# the timing fields left out; then the faults: a rank that cannot load the scene, a
# rank killed in the middle of a solve (whose files `--resume` continues with another
# K, as the default binary continues them).
#
#   tests/mpi/run.sh            # builds both binaries in target/release first
#   PLAIN=… MPI=… tests/mpi/run.sh   # or takes them as built
#
# Needs Open MPI (Debian: openmpi-bin libopenmpi-dev libclang-dev) and python3.
# About a minute on two cores once built.
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$(pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ -z "${PLAIN:-}" ] || [ -z "${MPI:-}" ]; then
  cargo build --release --quiet
  cp target/release/invlight "$work/plain"
  cargo build --release --quiet --features mpi
  cp target/release/invlight "$work/mpi"
  PLAIN="$work/plain" MPI="$work/mpi"
fi
mpirun=(mpirun --allow-run-as-root --oversubscribe --bind-to none)
export OMPI_MCA_rmaps_base_oversubscribe=1
fail() { echo "FAIL: $*" >&2; exit 1; }

# Outputs without their timing fields: solutions.csv without `seconds` and `elapsed`,
# JSON without `seconds` and `build_seconds`.
strip() {
  python3 - "$1" <<'EOF'
import csv, json, sys
path = sys.argv[1]
if path.endswith(".csv"):
    rows = list(csv.reader(open(path, newline="")))
    drop = {i for i, name in enumerate(rows[0]) if name in ("seconds", "elapsed")}
    for row in rows:
        print(",".join(x for i, x in enumerate(row) if i not in drop))
else:
    doc = json.load(open(path))
    def clean(x):
        if isinstance(x, dict):
            return {k: clean(v) for k, v in x.items() if k not in ("seconds", "build_seconds")}
        if isinstance(x, list):
            return [clean(v) for v in x]
        return x
    print(json.dumps(clean(doc), indent=1, sort_keys=True))
EOF
}

same() {  # same FILE_A FILE_B WHAT
  cmp -s <(strip "$1") <(strip "$2") || {
    diff <(strip "$1") <(strip "$2") | head -20 >&2
    fail "$3: $1 and $2 differ"
  }
}

cone="$root/examples/cornell-cone"
office="$root/examples/office-ies"

# 1. measure and map: the default binary, then K = 1, 2, 3.
"$PLAIN" measure "$cone/cornell.dae" -s Cone -s Cube-Ceiling -n 300000 --json > "$work/measure-plain.json"
"$PLAIN" map "$cone/cornell.dae" -s Cube-Ceiling -n 200000 --grid 0.5 -o "$work/map-plain" --json > "$work/map-plain.json"
for k in 1 2 3; do
  "${mpirun[@]}" -np $k "$MPI" measure "$cone/cornell.dae" -s Cone -s Cube-Ceiling -n 300000 --json > "$work/measure-$k.json"
  same "$work/measure-plain.json" "$work/measure-$k.json" "measure, K = $k"
  "${mpirun[@]}" -np $k "$MPI" map "$cone/cornell.dae" -s Cube-Ceiling -n 200000 --grid 0.5 -o "$work/map-$k" --json > "$work/map-$k.json"
  same "$work/map-plain.json" "$work/map-$k.json" "map --json, K = $k"
  cmp "$work/map-plain.csv" "$work/map-$k.csv" || fail "map's CSV, K = $k"
done
echo "measure, map: the same for K = 1, 2, 3 as the default binary"

# 2. solve: cornell-cone (a moved object) and office-ies (IES luminaires, a uniformity
# grid, dimming), with reduced budgets.
solve() {  # solve BINARY_AND_ARGS… -- PROBLEM OUT EXTRA…
  "$@" --no-images --no-report --json > /dev/null
}
for example in cone office; do
  problem="${!example}/problem.xml"
  args=(--iterations 40 --photons 20000)
  [ $example = office ] && args=(--iterations 25 --photons 10000)
  solve "$PLAIN" solve "$problem" -o "$work/$example-plain" "${args[@]}"
  for k in 1 2 3; do
    solve "${mpirun[@]}" -np $k "$MPI" solve "$problem" -o "$work/$example-$k" "${args[@]}"
    for f in solutions.csv result.json; do
      same "$work/$example-plain/$f" "$work/$example-$k/$f" "$example solve, K = $k"
    done
  done
done
# The paired search screens cells in batches, and the walk readies its next candidates,
# dealt to the ranks whole and exchanged: still the same files.
args=(--iterations 40 --photons 20000 --strategy PAIRED_ISOC)
solve "$PLAIN" solve "$cone/problem.xml" -o "$work/paired-plain" "${args[@]}"
for k in 2 3; do
  solve timeout 300 "${mpirun[@]}" -np $k "$MPI" solve "$cone/problem.xml" -o "$work/paired-$k" "${args[@]}" ||
    fail "paired solve, K = $k: did not finish (a hung exchange?)"
  for f in solutions.csv result.json; do
    same "$work/paired-plain/$f" "$work/paired-$k/$f" "paired solve, K = $k"
  done
done
# Nodes may differ in cores: ranks of 1 and 3 threads choose their batches alike.
uneven=(solve "$cone/problem.xml" -o "$work/uneven" "${args[@]}" --no-images --no-report --json)
timeout 300 "${mpirun[@]}" -np 1 "$MPI" "${uneven[@]}" --threads 1 : -np 1 "$MPI" "${uneven[@]}" --threads 3 \
  > /dev/null || fail "paired solve on ranks of 1 and 3 threads: did not finish"
for f in solutions.csv result.json; do
  same "$work/paired-plain/$f" "$work/uneven/$f" "paired solve on ranks of 1 and 3 threads"
done
# Rank 0 writes the report (its plan's map traced alone) after the others have ended.
timeout 300 "${mpirun[@]}" -np 2 "$MPI" solve "$office/problem.xml" -o "$work/report-2" \
  --iterations 25 --photons 10000 --no-images > /dev/null 2>&1 ||
  fail "a solve with its report on 2 ranks did not finish (rank 0 waiting for the others?)"
test -s "$work/report-2/report.html" || fail "a solve on 2 ranks wrote no report"
for f in solutions.csv result.json; do
  same "$work/office-plain/$f" "$work/report-2/$f" "office solve with its report, K = 2"
done
echo "solve: solutions.csv and result.json the same for K = 1, 2, 3 as the default binary"

# 3. A rank that cannot load the scene ends the job, named.
set +e
out=$(timeout 120 "${mpirun[@]}" -np 2 sh -c \
  'if [ "$OMPI_COMM_WORLD_RANK" = 1 ]; then s=/nonexistent/scene.dae; else s="$0"; fi; exec "$1" measure "$s" -s Cone -n 4000000' \
  "$cone/cornell.dae" "$MPI" 2>&1)
status=$?
set -e
[ $status -ne 0 ] && [ $status -ne 124 ] || fail "a rank without its scene: exit status $status"
grep -q "rank 1 of 2: error: /nonexistent/scene.dae" <<<"$out" || fail "no rank named: $out"
echo "a rank without its scene: the job ends (status $status) naming rank 1"

# 4. A rank killed in the middle of a solve: the job ends, the files hold complete rows,
# and --resume on 3 ranks continues them as the default binary resuming them does.
full=(--iterations 300 --photons 20000)
set +e
"${mpirun[@]}" -np 2 sh -c 'echo $$ > "$0.$OMPI_COMM_WORLD_RANK"; exec "$@"' "$work/pid" \
  "$MPI" solve "$cone/problem.xml" -o "$work/killed" "${full[@]}" --no-images --no-report \
  > "$work/killed.out" 2>&1 &
job=$!
for _ in $(seq 600); do
  rows=$(cat "$work/killed/solutions.csv" 2>/dev/null | wc -l)
  [ "$rows" -gt 20 ] && break
  sleep 0.1
done
kill -KILL "$(cat "$work/pid.1")"
wait $job
status=$?
set -e
[ $status -ne 0 ] || fail "a killed rank: the job ended with status 0"
grep -qi "rank 1" "$work/killed.out" || fail "a killed rank is not named: $(cat "$work/killed.out")"
kept=$(($(wc -l < "$work/killed/solutions.csv") - 1))
[ "$kept" -lt 300 ] || fail "the job was not stopped early ($kept rows)"
cp -r "$work/killed" "$work/killed-plain"
solve "$PLAIN" solve "$cone/problem.xml" -o "$work/killed-plain" "${full[@]}" --resume
solve "${mpirun[@]}" -np 3 "$MPI" solve "$cone/problem.xml" -o "$work/killed" "${full[@]}" --resume
for f in solutions.csv result.json; do
  same "$work/killed-plain/$f" "$work/killed/$f" "a killed job resumed on 3 ranks"
done
[ "$(wc -l < "$work/killed/solutions.csv")" -gt $((kept + 100)) ] || fail "the resumed run added few rows"
echo "a killed rank: the job ends (status $status) naming rank 1; --resume on 3 ranks continues its $kept rows as one process does"

# 5. Ctrl-C reaching the ranks one by one (as srun forwards it): rank 0's flag stops every
# rank at the same candidate, one flagged alone is ignored, and the files stay valid.
long=(--iterations 1000 --photons 20000)
set +e
"${mpirun[@]}" -np 2 sh -c 'echo $$ > "$0.$OMPI_COMM_WORLD_RANK"; exec "$@"' "$work/ipid" \
  "$MPI" solve "$cone/problem.xml" -o "$work/interrupted" "${long[@]}" --no-images --no-report \
  > "$work/interrupted.out" 2>&1 &
job=$!
for _ in $(seq 600); do
  rows=$(cat "$work/interrupted/solutions.csv" 2>/dev/null | wc -l)
  [ "$rows" -gt 20 ] && break
  sleep 0.1
done
kill -INT "$(cat "$work/ipid.1")"
before=$(wc -l < "$work/interrupted/solutions.csv")
sleep 0.3
kill -0 $job 2>/dev/null || fail "rank 1's Ctrl-C alone ended the job"
[ "$(wc -l < "$work/interrupted/solutions.csv")" -gt "$before" ] || fail "rank 1's Ctrl-C alone stopped the search"
kill -INT "$(cat "$work/ipid.0")"
for _ in $(seq 1200); do kill -0 $job 2>/dev/null || break; sleep 0.1; done
kill -0 $job 2>/dev/null && { kill -KILL $job; fail "an interrupted job did not end (a rank left waiting?)"; }
wait $job
status=$?
set -e
[ $status -ne 0 ] || fail "an interrupted solve ended with status 0"
kept=$(($(wc -l < "$work/interrupted/solutions.csv") - 1))
[ "$kept" -lt 1000 ] || fail "the interrupted job was not stopped early ($kept rows)"
cp -r "$work/interrupted" "$work/interrupted-plain"
solve "$PLAIN" solve "$cone/problem.xml" -o "$work/interrupted-plain" "${long[@]}" --resume
solve "${mpirun[@]}" -np 2 "$MPI" solve "$cone/problem.xml" -o "$work/interrupted" "${long[@]}" --resume
for f in solutions.csv result.json; do
  same "$work/interrupted-plain/$f" "$work/interrupted/$f" "an interrupted job resumed on 2 ranks"
done
echo "Ctrl-C on every rank: the job stops together (status $status) after $kept rows; --resume continues them"
echo "tests/mpi/run.sh: all passed"
