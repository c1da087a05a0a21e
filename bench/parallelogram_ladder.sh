#!/usr/bin/env bash
# A ladder of N parallelogram four-bars (N + 1 cranks on a line of pivots,
# joined by N coupling rods; diagrams/examples/coupling_rods.xml is N = 2)
# turning over the top under gravity through 20 s: every half turn all links
# are collinear and the loops lose N ranks at once. Prints, per N, the wall
# time of `mechflow run`, the solver counters, and the energy drift of the
# coupled cranks (which must stay constant) from the written results.
#   bench/parallelogram_ladder.sh [build folder] [rtol] [N...]   (default: build 1e-9 2 10 40)
set -euo pipefail
cd "$(dirname "$0")/.."
mechflow=${1:-build}/mechflow
rtol=${2:-1e-9}
shift $(( $# > 2 ? 2 : $# ))
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(2 10 40)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

ladder() {  # N rtol
  awk -v n="$1" -v rtol="$2" 'BEGIN {
    print "<diagram name=\"ladder\"><identifiers><identifier name=\"a\" value=\"0.5\"/>"
    print "<identifier name=\"d\" value=\"1\"/><identifier name=\"w\" value=\"10\"/></identifiers><mechanism name=\"m\">"
    for (k = 0; k <= n; ++k) printf "<body name=\"Crank%d\" mass=\"a\" com=\"0 a/2 0\" inertia=\"a^3/12 1e-4 a^3/12\"/>\n", k
    for (k = 1; k <= n; ++k) printf "<body name=\"Rod%d\" mass=\"d\" com=\"0 d/2 0\" inertia=\"d^3/12 1e-4 d^3/12\"/>\n", k
    for (k = 0; k <= n; ++k)
      printf "<joint name=\"p%d\" type=\"rotational\" body1=\"Base0\" body2=\"Crank%d\" point1=\"0 %d*d 0\" axis=\"1 0 0\" q0=\"1\" v0=\"w\"/>\n", k, k, k
    for (k = 1; k <= n; ++k) {
      printf "<joint name=\"a%d\" type=\"rotational\" body1=\"Crank%d\" body2=\"Rod%d\" point1=\"0 a 0\" axis=\"1 0 0\" q0=\"-1\" v0=\"-w\"/>\n", k, k - 1, k
      printf "<joint name=\"b%d\" type=\"rotational\" body1=\"Rod%d\" body2=\"Crank%d\" point1=\"0 d 0\" point2=\"0 a 0\" axis=\"1 0 0\"/>\n", k, k, k
    }
    printf "<sensor name=\"crank\" kind=\"coordinate\" dof=\"p0\"/><sensor name=\"speed\" kind=\"velocity\" dof=\"p0\"/>"
    printf "<sensor name=\"last\" kind=\"coordinate\" dof=\"p%d\"/></mechanism>\n", n
    printf "<solver t_end=\"20\" rtol=\"%s\" atol=\"%g\"/>\n", rtol, rtol * 1e-2
    print "<output interval=\"0.01\"><log signal=\"m.crank\"/><log signal=\"m.speed\"/><log signal=\"m.last\"/></output></diagram>" }'
}

printf "%5s %10s %8s %12s %12s %12s  %s\n" N "time [s]" steps "RHS" "energy drift" "crank spread" outcome
for n in "${sizes[@]}"; do
  ladder "$n" "$rtol" > "$work/ladder.xml"
  start=$(date +%s.%N)
  if "$mechflow" run "$work/ladder.xml" --out "$work/out" > "$work/log" 2>&1; then outcome=finished; else outcome=failed; fi
  seconds=$(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN { printf "%.2f", e - s }')
  steps=$(awk '/^solver:/ { print $2 }' "$work/log")
  rhs=$(awk '/^solver:/ { gsub(/[(+]/, ""); print $4 + $7 }' "$work/log")
  # I theta'^2 / 2 + V with I = (N + 1) m_c a^2 / 3 + N m_r a^2, V = g ((N + 1) m_c a / 2 + N m_r a) sin(theta)
  read -r drift spread < <(awk -F, -v n="$n" 'NR > 1 {
      I = (n + 1) * 0.125 / 3 + n * 0.25; k = 9.81 * ((n + 1) * 0.125 + n * 0.5)
      e = I * $3 * $3 / 2 + k * sin($2); if (NR == 2) e0 = e
      d = (e - e0) / e0; if (d < 0) d = -d; if (d > drift) drift = d
      s = $4 - $2; if (s < 0) s = -s; if (s > spread) spread = s }
    END { printf "%.1e %.1e\n", drift, spread }' "$work/out/ladder.csv")
  printf "%5d %10s %8s %12s %12s %12s  %s\n" "$n" "$seconds" "$steps" "$rhs" "$drift" "$spread" "$outcome"
done
