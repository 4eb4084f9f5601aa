#!/usr/bin/env bash
# The exact rigid inclusion at random positions: the particle's velocity
# error depends on where it sits relative to the mesh, which is noise along
# a trajectory. For N positions drawn (seeded) in the middle of the unit box
# (x, y in [0.4, 0.6]), radius a, at each maximum level, prints the largest
# and mean |U| / (g a) (exact 0) and relative omega error.
# Usage: contrib/benchmarks/random_inclusion.sh [a, default 0.05] [levels, default "6 7 8"] [N, default 6]
# FIDUS=<binary> uses another build; OLD=<binary> adds the same rows for it.
# FLUID="Entry = value; Entry = value" sets entries of subsection Fluid,
# LABEL=<text> names the rows (default: the binary's name). UNIFORM=1 refines
# the whole box to each level (Minimum level = Maximum level) instead of
# adapting to the particle: the cost of the same error without adaptivity.
# The last columns are the mean cells and the mean wall seconds of a run
# (statistics.csv), for the cost at equal error. DIM=3 places spheres in
# the unit cube (x, y, z in [0.4, 0.6]) instead of discs.
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
a="${1:-0.05}"; levels="${2:-6 7 8}"; n="${3:-6}"
work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT
dim="${DIM:-2}"
lower="0, 0"; upper="1, 1"
[ "$dim" = 3 ] && lower="0, 0, 0" && upper="1, 1, 1"
positions=$(awk -v n="$n" -v dim="$dim" 'BEGIN { srand(7); for (i = 0; i < n; ++i) {
  printf "%.6f,%.6f", 0.4 + 0.2 * rand(), 0.4 + 0.2 * rand()
  if (dim == 3) printf ",%.6f", 0.4 + 0.2 * rand()
  printf "\n" } }')

fluid_settings=$(echo "${FLUID:-}" | tr ';' '\n' | sed '/^ *$/d; s/^ */  set /')
echo "| binary | level | max \|U\|/(g a) | mean \|U\|/(g a) | max omega error | mean omega error | Uzawa (mean) | FGMRES (mean) | cells (mean) | wall s (mean) |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for binary in ${OLD:-} "$fidus"; do
  for level in $levels; do
    coarse=3
    [ "${UNIFORM:-0}" = 1 ] && coarse=$level
    rm -f "$work/errors.txt"
    for p in $positions; do
      cat > "$work/run.prm" <<EOF2
set Dimension = $dim
set Output directory = $work/out
subsection Domain
  set Lower left = $lower
  set Upper right = $upper
  set Boundary condition = exact rigid inclusion
end
subsection Fluid
$fluid_settings
end
subsection Particles
  set Radius = $a
  set Positions = $p
end
subsection Time stepping
  set End time = 0
end
subsection Mesh refinement
  set Initial global refinement = $coarse
  set Minimum level = $coarse
  set Maximum level = $level
end
EOF2
      "$binary" "$work/run.prm" 2> /dev/null | grep "exact rigid inclusion" |
        sed 's/.*relative omega error \([^,]*\), |U|\/(g a) \(.*\)/\2 \1/' | tr '\n' ' ' >> "$work/errors.txt"
      awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i }
               NR == 2 { print $c["uzawa_iterations"], $c["linear_iterations"], $c["cells"], $c["wall_seconds"] }' \
        "$work/out/statistics.csv" >> "$work/errors.txt"
    done
    awk -v b="${LABEL:-$(basename "$binary")}" -v l="$level" '
      { if ($1 > mu) mu = $1; su += $1; if ($2 > mw) mw = $2; sw += $2; si += $3; sf += $4; sc += $5; st += $6; k++ }
      END { printf "| %s | %d | %.2e | %.2e | %.2e | %.2e | %.1f | %.0f | %.0f | %.2f |\n", b, l, mu, su / k, mw, sw / k, si / k, sf / k, sc / k, st / k }' "$work/errors.txt"
  done
done
