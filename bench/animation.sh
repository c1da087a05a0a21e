#!/usr/bin/env bash
# What the animation costs, so that the README can say what --animate adds to a run.
#  1. Run overhead: the wall time of `mechflow run EXAMPLE --quiet` (load, run,
#     CSV, plot, animation) against the same with --no-animate, for every
#     example diagram with shapes; medians of REPEAT runs each, alternating.
#  2. Size: the animation file's size, and a 10-body chain over 10 s logged
#     every 1 ms (the issue's budget case).
#  3. Frame time in headless Chromium (software WebGL): the animation page's
#     "#frametime=N" mode plays N frames at 60 frames per second and times
#     each from the new time to the finished image (a pixel read back), in
#     real time (no --virtual-time-budget, which would stop the clock).
#   bench/animation.sh [build folder] [REPEAT]     (default: build 5)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
mechflow=$root/${1:-build}/mechflow
repeat=${2:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
wall() {  # wall time [s] of one run
  local start; start=$(now)
  "$mechflow" run "$@" --quiet --out "$work/out" > /dev/null
  echo "$(now) - $start" | bc -l
}

echo "## Run overhead (medians of $repeat)"
echo
echo "| example | without [s] | with [s] | ratio | file [KiB] |"
echo "| --- | --- | --- | --- | --- |"
for diagram in diagrams/examples/*.xml; do
  grep -q "<shape" "$diagram" || continue
  name=$(basename "$diagram" .xml)
  : > "$work/with"; : > "$work/without"
  for ((i = 0; i < repeat; ++i)); do
    if ((i % 2)); then wall "$diagram" --animate >> "$work/with"; wall "$diagram" --no-animate >> "$work/without"
    else wall "$diagram" --no-animate >> "$work/without"; wall "$diagram" --animate >> "$work/with"; fi
  done
  with=$(median < "$work/with"); without=$(median < "$work/without")
  size=$(( $(stat -c %s "$work/out/$name.html") / 1024 ))
  printf "| %s | %.3f | %.3f | %.2f | %d |\n" "$name" "$without" "$with" "$(echo "$with / $without" | bc -l)" "$size"
done

echo
echo "## Size budget: a chain of 10 bodies, 10 s, rows every 1 ms"
awk 'BEGIN {
  print "<diagram name=\"chain10\"><mechanism name=\"m\">"
  for (i = 1; i <= 10; ++i) {
    printf "<body name=\"b%d\" mass=\"1\" com=\"0 0 -0.25\" inertia=\"0.01 0.01 0.001\"/>\n", i
    printf "<joint name=\"j%d\" type=\"rotational\" body1=\"%s\" body2=\"b%d\" axis=\"1 0 0\" %s q0=\"0.3\"/>\n",
           i, (i == 1 ? "Base0" : "b" (i - 1)), i, (i == 1 ? "" : "point1=\"0 0 -0.5\"")
    printf "<shape type=\"cylinder\" body=\"b%d\" position=\"0 0 -0.25\" length=\"0.5\" radius=\"0.02\"/>\n", i
  }
  print "<sensor name=\"q1\" kind=\"coordinate\" dof=\"j1\"/></mechanism><solver t_end=\"10\"/>"
  print "<output interval=\"0.001\"><log signal=\"m.q1\"/></output></diagram>" }' > "$work/chain10.xml"
"$mechflow" run "$work/chain10.xml" --animate --gltf --out "$work/chain" | grep "^wrote.*\(html\|glb\)"

echo
echo "## Frame time in headless Chromium (600 frames at 60 frames per second)"
echo
echo "| example | median [ms] | 95th percentile [ms] | largest [ms] |"
echo "| --- | --- | --- | --- |"
for name in tension_mechanism falling; do
  "$mechflow" run "diagrams/examples/$name.xml" --animate --quiet --out "$work/$name" > /dev/null
  report=$(chromium --headless=new --no-sandbox --use-gl=angle --use-angle=swiftshader --enable-unsafe-swiftshader \
    --window-size=1280,800 --dump-dom "file://$work/$name/$name.html#frametime=600" \
    2> /dev/null | sed -n 's:.*<pre id="mechflow-test">\(.*\)</pre>.*:\1:p')
  echo "$report" | awk -v name="$name" -F'[:,}]' '{ for (i = 1; i < NF; ++i) v[$i] = $(i + 1) }
    END { printf "| %s | %.2f | %.2f | %.2f |\n", name, v["\"median_ms\""], v["\"p95_ms\""], v["\"max_ms\""] }'
done
