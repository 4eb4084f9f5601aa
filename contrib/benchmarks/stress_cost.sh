#!/usr/bin/env bash
# Cost of the stress evaluation (HydrodynamicStress + contact_stress, the
# 'stress' row of the timer) against the whole step, on shipped scenes cut
# short: the paper's 2D scene, the dense 2D suspension (prm/
# dense_suspension_2d.prm, 120 discs between sliding walls) and the 3D
# two-sphere scene. The issue's budget is 5 % of a step.
# Usage: contrib/benchmarks/stress_cost.sh [steps, default 5]
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
steps="${1:-5}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

printf '| scene | steps | run s | stress s | stress / run |\n|---|---|---|---|---|\n'
for scene in two_particles_2d dense_suspension_2d two_particles_3d; do
  {
    echo "include $top/prm/$scene.prm"
    echo "set Output directory = $work/$scene"
    echo "subsection Time stepping"
    echo "  set End time = $(grep -m1 '^ *set Time step' "$top/prm/$scene.prm" |
                            sed 's/.*= *//' | awk -v n="$steps" '{print $1 * n}')"
    echo "end"
    echo "subsection Output"
    echo "  set Particle output interval = 0"
    echo "  set Checkpoint wall interval = 0"
    echo "end"
  } > "$work/$scene.prm"
  "$fidus" "$work/$scene.prm" > "$work/$scene.log" 2>&1
  total=$(grep -m1 'Total wallclock time' "$work/$scene.log" |
            sed 's/.*elapsed since start *| *//; s/s.*//')
  stress=$(grep '^| stress ' "$work/$scene.log" | awk -F'|' '{print $4}' | sed 's/s//')
  awk -v s="$scene" -v n="$steps" -v t="$total" -v x="$stress" \
    'BEGIN { printf "| %s | %d | %.2f | %.3f | %.2f %% |\n", s, n, t, x, 100 * x / t }'
done
