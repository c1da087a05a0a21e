#!/usr/bin/env bash
# Sweep throughput: runs per second of the seed
# ElastFriction (diagrams/examples/elast_friction.xml, 3 s, its own 1 ms grid)
# swept over RUNS values of the sliding force F, on 1 thread, on 2 threads,
# and on 2 MPI ranks of one thread each; the ideal for 2 is twice 1 thread.
# Each configuration runs REPEAT times (alternating); the medians are
# printed of two times: the runs alone (the sweep's own "finished in" line,
# from the first run's start to the last run's end on the root process) and
# the whole command (loading, runs, the summary and its one overlay plot of
# every run, drawn by gnuplot after the runs).
#   bench/sweep_throughput.sh [build folder] [MPI build folder] [RUNS] [REPEAT]
#   (defaults: build, build-mpi, 200, 3; the MPI part is skipped without
#   an MPI build: cmake -B build-mpi -DMECHFLOW_MPI=ON && cmake --build build-mpi --target mechflow)
set -euo pipefail
cd "$(dirname "$0")/.."
serial=${1:-build}/mechflow
mpi=${2:-build-mpi}/mechflow
runs=${3:-200}
repeat=${4:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
example=diagrams/examples/elast_friction.xml
vary="F=5:15:$runs"

mpirun_as=(mpirun)
[ "$(id -u)" -eq 0 ] && mpirun_as+=(--allow-run-as-root)

configs=("1 thread" "2 threads")
[ -x "$mpi" ] && command -v mpirun >/dev/null && configs+=("2 MPI ranks")

run() {  # config -> "runs-seconds whole-seconds"
  local out="$work/out" start end
  rm -rf "$out"
  start=$(date +%s.%N)
  case "$1" in
    "1 thread") "$serial" sweep "$example" --vary "$vary" --jobs 1 --out "$out" ;;
    "2 threads") "$serial" sweep "$example" --vary "$vary" --jobs 2 --out "$out" ;;
    "2 MPI ranks") "${mpirun_as[@]}" -n 2 "$mpi" sweep "$example" --vary "$vary" --jobs 1 --out "$out" ;;
  esac > "$work/stdout" 2> "$work/stderr" || { cat "$work/stderr" >&2; exit 1; }
  end=$(date +%s.%N)
  local ok
  ok=$(awk -F, 'NR > 1 && /,ok,/ { n++ } END { print n + 0 }' "$out"/*.sweep.csv)
  [ "$ok" -eq "$runs" ] || { echo "$1: $ok of $runs runs ok" >&2; exit 1; }
  echo "$(sed -n 's/^finished in \([0-9.e-]*\) s of wall time.*/\1/p' "$work/stdout") $(echo "$end - $start" | bc -l)"
}

declare -A runs_time whole_time
for ((k = 0; k < repeat; ++k)); do
  for config in "${configs[@]}"; do
    read -r a b <<< "$(run "$config")"
    runs_time[$config]+="$a "
    whole_time[$config]+="$b "
  done
done

median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
base_runs=$(echo "${runs_time["1 thread"]}" | median)
base_whole=$(echo "${whole_time["1 thread"]}" | median)
printf "%d runs of %s (sweep over F), median of %d, %d cores\n" "$runs" "$example" "$repeat" "$(nproc)"
printf "%-12s | %12s %8s %8s | %12s %8s %8s\n" "" "runs [s]" "runs/s" speedup "command [s]" "runs/s" speedup
for config in "${configs[@]}"; do
  r=$(echo "${runs_time[$config]}" | median)
  w=$(echo "${whole_time[$config]}" | median)
  printf "%-12s | %12.3f %8.1f %8.2f | %12.2f %8.1f %8.2f\n" "$config" "$r" "$(echo "$runs / $r" | bc -l)" \
    "$(echo "$base_runs / $r" | bc -l)" "$w" "$(echo "$runs / $w" | bc -l)" "$(echo "$base_whole / $w" | bc -l)"
done
[ -x "$mpi" ] || echo "2 MPI ranks: not measured (no MPI build at ${2:-build-mpi})"
