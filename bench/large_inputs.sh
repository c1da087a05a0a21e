#!/usr/bin/env bash
# Loading, checking and scheduling large diagrams: `mechflow check` of a
# chain of N gain blocks (N = 5000 ... 100000), of a line of N bodies joined
# by translational joints and springs (N = 1000 ... 50000), and of N
# identifiers, defined by numbers (`identifiers`) or each by an expression
# of the one above (`expressions`, N = 10000 ... 100000), with the wall time
# and peak memory of each and the growth exponent between sizes.
#   bench/large_inputs.sh [build folder]     (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
mechflow=${1:-build}/mechflow
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

blocks() {  # N gains in a chain after a sine, into an integrator
  awk -v n="$1" 'BEGIN {
    print "<diagram name=\"chain\"><blocks><block type=\"sine\" name=\"s\"/>"
    for (i = 1; i <= n; ++i) printf "<block type=\"gain\" name=\"g%d\" k=\"1\"/>\n", i
    print "<block type=\"integrator\" name=\"x\"/></blocks><connections>"
    print "<connect from=\"s.y\" to=\"g1.u\"/>"
    for (i = 2; i <= n; ++i) printf "<connect from=\"g%d.y\" to=\"g%d.u\"/>\n", i - 1, i
    printf "<connect from=\"g%d.y\" to=\"x.u\"/></connections></diagram>\n", n }'
}
bodies() {  # N bodies in a line, each on a translational joint and a spring
  awk -v n="$1" 'BEGIN {
    print "<diagram name=\"line\"><mechanism name=\"m\">"
    for (i = 1; i <= n; ++i) {
      printf "<body name=\"b%d\" mass=\"1\" inertia=\"1 1 1\"/>\n", i
      printf "<joint name=\"j%d\" type=\"translational\" body1=\"%s\" body2=\"b%d\" axis=\"1 0 0\"/>\n", i, (i == 1 ? "Base0" : "b" (i - 1)), i
      printf "<joint_force name=\"f%d\" type=\"linear\" dof=\"j%d\" c=\"100\"/>\n", i, i
    }
    print "</mechanism></diagram>" }'
}

identifiers() {  # N identifiers defined by numbers; a gain reads the last
  awk -v n="$1" 'BEGIN {
    print "<diagram name=\"ids\"><identifiers>"
    for (i = 0; i < n; ++i) printf "<identifier name=\"p%d\" value=\"%d\"/>\n", i, i
    printf "</identifiers><blocks><block type=\"integrator\" name=\"x\"/><block type=\"gain\" name=\"g\" k=\"p%d\"/>", n - 1
    print "</blocks><connections><connect from=\"x.y\" to=\"g.u\"/><connect from=\"g.y\" to=\"x.u\"/></connections></diagram>" }'
}
expressions() {  # N identifiers, each the one above plus one
  identifiers "$1" | awk '/<identifier name="p[0-9]+"/ && !/"p0"/ {
    match($0, /"p[0-9]+"/); i = substr($0, RSTART + 2, RLENGTH - 3)
    printf "<identifier name=\"p%d\" value=\"p%d + 1\"/>\n", i, i - 1; next } { print }'
}

measure() {  # kind n -> "seconds kib"
  "$1" "$2" > "$work/d.xml"
  /usr/bin/time -f "%e %M" -o "$work/time" "$mechflow" check "$work/d.xml" > /dev/null
  cat "$work/time"
}

report() {  # kind sizes...
  local kind=$1; shift
  local previous_n="" previous_t=""
  printf "%-8s %8s %10s %10s %9s\n" "$kind" N "time [s]" "peak MiB" "exponent"
  for n in "$@"; do
    read -r seconds kib < <(measure "$kind" "$n")
    exponent="-"
    if [ -n "$previous_n" ]; then
      exponent=$(awk -v t1="$previous_t" -v t2="$seconds" -v n1="$previous_n" -v n2="$n" \
        'BEGIN { if (t1 > 0 && t2 > 0) printf "%.2f", log(t2 / t1) / log(n2 / n1); else print "-" }')
    fi
    printf "%-8s %8d %10.2f %10.1f %9s\n" "" "$n" "$seconds" "$(awk -v k="$kib" 'BEGIN { print k / 1024 }')" "$exponent"
    previous_n=$n previous_t=$seconds
  done
}

report blocks 5000 10000 20000 50000 100000
report bodies 1000 2000 4000 10000 20000 50000
report identifiers 10000 20000 50000 100000
report expressions 10000 20000 50000 100000

# Instruction counts (callgrind: exact and repeatable on a busy machine),
# for the growth exponent without timing noise; skipped without valgrind.
if command -v valgrind >/dev/null && [ "${MECHFLOW_COUNT_INSTRUCTIONS:-1}" = 1 ]; then
  count() {  # kind n -> instructions
    "$1" "$2" > "$work/d.xml"
    valgrind --tool=callgrind --callgrind-out-file="$work/cg" "$mechflow" check "$work/d.xml" >/dev/null 2>&1
    awk '/^summary:/ { print $2 }' "$work/cg"
  }
  for pair in "blocks 25000 100000" "bodies 2500 10000"; do
    read -r kind n1 n2 <<< "$pair"
    i1=$(count "$kind" "$n1") i2=$(count "$kind" "$n2")
    awk -v k="$kind" -v n1="$n1" -v n2="$n2" -v i1="$i1" -v i2="$i2" \
      'BEGIN { printf "%-8s instructions %d: %.3g, %d: %.3g, exponent %.2f\n", k, n1, i1, n2, i2, log(i2 / i1) / log(n2 / n1) }'
  done
fi
