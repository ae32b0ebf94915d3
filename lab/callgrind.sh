#!/usr/bin/env bash
# Instructions per step on the host (x86-64), deterministic: callgrind's instruction totals for N and 2N steps
# of `step-loop`, differenced, so start-up cost cancels. Needs valgrind (Debian: apt-get install valgrind).
#   lab/callgrind.sh [f32|f64]      -> Markdown table, every scheme x stabilizer, linear input model
# Baumgarte wraps the Runge-Kutta schemes only (quatprop 0.2): "–" for the exponential maps.
set -euo pipefail
cd "$(dirname "$0")/.."
precision="${1:-f32}"
cargo build -q --release -p quatprop-lab --bin step-loop
bin="${CARGO_TARGET_DIR:-target}/release/step-loop"
n=20000
count() {
  local out; out=$(mktemp)
  valgrind --tool=callgrind --callgrind-out-file="$out" "$bin" "$@" >/dev/null 2>&1
  awk '/^summary:/ {print $2}' "$out"; rm -f "$out"
}
echo "| scheme | Off | Normalize | FirstOrder | Every16 | Baumgarte |"
echo "|---|---|---|---|---|---|"
for s in Euler Rk2 Rk3 Rk4 Rk5 ExpMap Magnus4 Cf4; do
  row="| $s |"
  for z in Off Normalize FirstOrder Every16 Baumgarte; do
    if ! "$bin" "$s" "$z" "$precision" 1 >/dev/null 2>&1; then
      row="$row – |"
      continue
    fi
    a=$(count "$s" "$z" "$precision" $n); b=$(count "$s" "$z" "$precision" $((2 * n)))
    row="$row $(awk -v a="$a" -v b="$b" -v n="$n" 'BEGIN {printf "%.1f", (b - a) / n}') |"
  done
  echo "$row"
done
