#!/usr/bin/env bash
# Loading, checking and scheduling large diagrams: `mechflow check` of a
# chain of N gain blocks (N = 5000 ... 100000), of a line of N bodies joined
# by translational joints and springs (N = 1000 ... 50000), and of N
# identifiers, defined by numbers (`identifiers`) or each by an expression
# of the one above (`expressions`, N = 10000 ... 100000), and of N instances
# of a subsystem (`dampers`, an array of diagrams/examples/parts/friction_damper.xml,
# N = 250 ... 1000), with the wall time and peak memory of each and the growth
# exponent between sizes. Then the run of diagrams/examples/damper_chain.xml
# (three friction-damper subsystems) against the same model written out flat
# (tests/regression/data/damper_chain_flat.xml): the ratio of their wall
# times and, with valgrind, of their instruction counts.
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

dampers() {  # an array of N friction-damper subsystems, all on one slip velocity
  mkdir -p "$work/parts"
  cp diagrams/examples/parts/friction_damper.xml "$work/parts/"
  awk -v n="$1" 'BEGIN {
    print "<diagram name=\"dampers\"><blocks><block type=\"sine\" name=\"s\"/><block type=\"constant\" name=\"c\" value=\"0\"/>"
    printf "<block type=\"subsystem\" name=\"d\" src=\"parts/friction_damper.xml\" count=\"%d\">", n
    print "<param name=\"preload\" value=\"1+index\"/></block><block type=\"integrator\" name=\"x\"/></blocks><connections>"
    for (i = 0; i < n; ++i) printf "<connect from=\"s.y\" to=\"d[%d].v\"/><connect from=\"c.y\" to=\"d[%d].v_surface\"/>\n", i, i
    printf "<connect from=\"d[%d].F\" to=\"x.u\"/></connections></diagram>\n", n - 1 }'
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
report dampers 250 500 1000

# The cost of parts at run time: none once loaded (the loader flattens them).
# Wall times (ns clock) of load, run and CSV (copies without the plot, which
# gnuplot would dominate) of the example and of its flat twin, 9 alternating
# runs each, medians.
median() { sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
mkdir -p "$work/parts"
cp diagrams/examples/parts/friction_damper.xml "$work/parts/"
sed 's/ plot="[^"]*"//' diagrams/examples/damper_chain.xml > "$work/chain_parts.xml"
sed 's/ plot="[^"]*"//' tests/regression/data/damper_chain_flat.xml > "$work/chain_flat.xml"
for i in 1 2 3 4 5 6 7 8 9; do
  for kind in parts flat; do
    start=$(date +%s%N)
    "$mechflow" run "$work/chain_$kind.xml" --quiet --no-animate --out "$work/out" > /dev/null
    echo $(( $(date +%s%N) - start )) >> "$work/run_times_$kind"
  done
done
awk -v p="$(median < "$work/run_times_parts")" -v f="$(median < "$work/run_times_flat")" \
  'BEGIN { printf "damper_chain run [s]: parts %.3f, flat %.3f, ratio %.3f\n", p / 1e9, f / 1e9, p / f }'

# Instruction counts (callgrind: exact and repeatable on a busy machine),
# for the growth exponent without timing noise; skipped without valgrind.
if command -v valgrind >/dev/null && [ "${MECHFLOW_COUNT_INSTRUCTIONS:-1}" = 1 ]; then
  count() {  # kind n -> instructions
    "$1" "$2" > "$work/d.xml"
    valgrind --tool=callgrind --callgrind-out-file="$work/cg" "$mechflow" check "$work/d.xml" >/dev/null 2>&1
    awk '/^summary:/ { print $2 }' "$work/cg"
  }
  for pair in "blocks 25000 100000" "bodies 2500 10000" "dampers 250 1000"; do
    read -r kind n1 n2 <<< "$pair"
    i1=$(count "$kind" "$n1") i2=$(count "$kind" "$n2")
    awk -v k="$kind" -v n1="$n1" -v n2="$n2" -v i1="$i1" -v i2="$i2" \
      'BEGIN { printf "%-8s instructions %d: %.3g, %d: %.3g, exponent %.2f\n", k, n1, i1, n2, i2, log(i2 / i1) / log(n2 / n1) }'
  done
  run_count() {  # diagram -> instructions of its `mechflow run`
    valgrind --tool=callgrind --callgrind-out-file="$work/cg" "$mechflow" run "$1" --quiet --no-animate --out "$work/out" \
      >/dev/null 2>&1
    awk '/^summary:/ { print $2 }' "$work/cg"
  }
  awk -v p="$(run_count "$work/chain_parts.xml")" -v f="$(run_count "$work/chain_flat.xml")" \
    'BEGIN { printf "damper_chain run instructions: parts %.4g, flat %.4g, ratio %.4f\n", p, f, p / f }'
fi
