#!/usr/bin/env bash
# Exact contact stick against the regularised law on the same models, in one
# run: the seed examples Falling, Oscillations (with mu_static = 0.4: true
# stick-slip) and Fidget (a wheel set rocking on two rims), and a box held on
# a 20 deg incline for 100 s. Prints, per model
# and law, the solver's steps, right-hand sides and events, the simulation's
# own time (`mechflow run`'s "finished in" line, best of 5: reading the
# diagram and writing files are the same for both laws and would only dilute
# the ratio), and the ratio exact / regularised.
#   bench/exact_contact_stick.sh [build folder]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
mechflow=$(realpath "${1:-build}/mechflow")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# the law's attributes: the examples' v_eps (regularised) or stick="exact"
exact() { sed -E 's/ v_eps="[^"]*"/ stick="exact"/g' "$1"; }
sed 's/value="0.3" comment="static/value="0.4" comment="static/' diagrams/examples/oscillations.xml \
  > "$work/oscillations_regularised.xml"
cp diagrams/examples/falling.xml "$work/falling_regularised.xml"
cp diagrams/examples/fidget.xml "$work/fidget_regularised.xml"
cat > "$work/held_box_regularised.xml" <<'XML'
<diagram name="held_box"><identifiers>
  <identifier name="theta" value="20*pi/180"/><identifier name="m" value="2"/><identifier name="a" value="0.05"/>
  <identifier name="c" value="1e5"/><identifier name="sag" value="m*9.81*cos(theta)/(4*c)"/></identifiers>
  <mechanism name="m"><body name="Box" mass="m" inertia="m*(2*a)^2/6 m*(2*a)^2/6 m*(2*a)^2/6"/>
    <joint name="j" type="quaternion" body1="Base0" body2="Box" position="0 -(a-sag)*sin(theta) (a-sag)*cos(theta)"
           angles="theta 0 0"/>
    <contact name="c" type="points_plane" body1="Box" body2="Base0" normal="0 -sin(theta) cos(theta)"
             points="-a -a -a; a -a -a; -a a -a; a a -a" stiffness="c" damping="2*sqrt(m*c/4)" mu="0.5" v_eps="1e-4"/>
    <sensor name="p" kind="position" body="Box"/></mechanism>
  <solver t_end="100" rtol="1e-8" atol="1e-10"/><output interval="10"><log signal="m.p"/></output></diagram>
XML
for model in falling oscillations fidget held_box; do exact "$work/${model}_regularised.xml" > "$work/${model}_exact.xml"; done

simulation() {  # diagram -> best seconds of 5 runs, and the solver's counters
  local best=
  for _ in 1 2 3 4 5; do
    "$mechflow" run "$1" --out "$work/out_$(basename "$1" .xml)" --no-plot > "$work/log" 2>&1
    local s; s=$(awk '/^finished in/ { printf "%.4f", $3 }' "$work/log")
    if [ -z "$best" ] || awk -v a="$s" -v b="$best" 'BEGIN { exit !(a < b) }'; then best=$s; fi
  done
  local counters
  counters=$(awk '/^solver:/ { steps = $2; rhs = $4 } /events,/ { events = $1 } END { printf "%s %s %s", steps, rhs, events }' "$work/log")
  echo "$best $counters"
}

printf '%-14s %-12s %8s %8s %8s %8s\n' model law "time [s]" steps RHS events
for model in falling oscillations fidget held_box; do
  read -r t_reg s_reg r_reg e_reg < <(simulation "$work/${model}_regularised.xml")
  read -r t_ex s_ex r_ex e_ex < <(simulation "$work/${model}_exact.xml")
  printf '%-14s %-12s %8s %8s %8s %8s\n' "$model" regularised "$t_reg" "$s_reg" "$r_reg" "$e_reg"
  printf '%-14s %-12s %8s %8s %8s %8s\n' "$model" exact "$t_ex" "$s_ex" "$r_ex" "$e_ex"
  awk -v a="$t_ex" -v b="$t_reg" -v sa="$s_ex" -v sb="$s_reg" -v m="$model" \
    'BEGIN { printf "%-14s exact / regularised: time %.2f, steps %.2f\n", m, (b > 0 ? a / b : 0), sa / sb }'
done
