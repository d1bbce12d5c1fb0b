#!/usr/bin/env bash
# Tests that the sbatch scripts of docs/scaling.md do what the page says, without Slurm:
# the scripts are taken out of the page (the fenced block after each
# "<!-- tested: NAME" comment), the array script runs once per task of --array=0-3 with
# the variables Slurm sets for it, then the merge script, then the MPI script on 3 ranks
# (skipped, saying so, without mpirun); each results.csv must be --jobs 1's byte for byte.
#   tests/scaling_docs_test.sh SHAPEBENCH
set -u
binary=$1
cd "$(dirname "$0")/.." || exit 1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bad=0
fail() { echo "scaling docs: $*"; bad=1; }

# The fenced block after the line "<!-- tested: NAME ...".
script_of() {
  awk -v name="$1" '
    index($0, "<!-- tested: " name) == 1 { want = 1; next }
    want && /^```/ { if (inside) exit; inside = 1; next }
    inside { print }' docs/scaling.md
}
for name in array.sbatch merge.sbatch mpi.sbatch; do
  script_of "$name" > "$work/$name"
  [ -s "$work/$name" ] || fail "docs/scaling.md has no tested block $name"
done
array_ids=$(sed -n 's/^#SBATCH --array=\([0-9]*\)-\([0-9]*\)$/\1 \2/p' "$work/array.sbatch")
[ -n "$array_ids" ] || fail "array.sbatch has no --array=FIRST-LAST"
read -r first last <<< "$array_ids"

"$binary" sweep configs/sweeps/natural_period.yaml --jobs 1 --out "$work/reference" > /dev/null ||
  fail "the --jobs 1 reference failed"
reference="$work/reference/results.csv"

for ((id = first; id <= last; id++)); do
  SHAPEBENCH=$binary OUT=$work/array SLURM_ARRAY_TASK_ID=$id SLURM_ARRAY_TASK_MIN=$first \
    SLURM_ARRAY_TASK_MAX=$last SLURM_ARRAY_TASK_COUNT=$((last - first + 1)) SLURM_ARRAY_TASK_STEP=1 \
    SLURM_CPUS_PER_TASK=2 bash "$work/array.sbatch" > "$work/array-$id.out" 2>&1 ||
    fail "array task $id failed: $(cat "$work/array-$id.out")"
done
count=$((last - first + 1))
[ -f "$work/array/shard-0-of-$count/results.csv" ] || fail "no $work/array/shard-0-of-$count/results.csv"
SHAPEBENCH=$binary OUT=$work/array bash "$work/merge.sbatch" > "$work/merge.out" 2>&1 ||
  fail "merge failed: $(cat "$work/merge.out")"
cmp -s "$reference" "$work/array/merged/results.csv" || fail "the merged array differs from --jobs 1"

if ! command -v mpirun > /dev/null; then
  echo "scaling docs: mpi.sbatch skipped (no mpirun; install openmpi-bin, as make test does)"
elif ! ldd "$binary" | grep -q libmpi; then
  echo "scaling docs: mpi.sbatch skipped ($binary was built without MPI; install libopenmpi-dev)"
else
  # (ASAN_OPTIONS: in make test-sanitize, Open MPI's own unfreed allocations are no leak of ours.)
  ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0" \
    OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 SHAPEBENCH=$binary OUT=$work/mpi \
    MPIRUN="mpirun -n 3 --oversubscribe" SLURM_CPUS_PER_TASK=1 bash "$work/mpi.sbatch" > "$work/mpi.out" 2>&1 ||
    fail "mpi.sbatch failed: $(cat "$work/mpi.out")"
  cmp -s "$reference" "$work/mpi/results.csv" || fail "the MPI run differs from --jobs 1"
fi
[ $bad -eq 0 ] && echo "scaling docs: array ($count tasks) + merge and MPI scripts give --jobs 1's results.csv"
exit $bad
