#!/bin/bash
# Contact projection benchmark: time per projection and dual iterations for
# N = 1e3, 1e4, 1e5 particles at volume fractions 0.3 and 0.5, in 2D and 3D,
# for each dual solver, with the pair search timed separately (cell list and
# R-tree). Prints a markdown table. Not a test: it never asserts on time.
#
# Usage: contrib/benchmarks/contact_projection.sh [BENCHMARK_BINARY] [STEPS]
#   BENCHMARK_BINARY defaults to build/fidus_contact_benchmark
#   (make fidus_contact_benchmark); STEPS projections averaged (default 3).
# Environment: SOLVERS (default "pgs_subspace pgs apg pg"), SIZES, FRACTIONS,
#   FRICTION (default 0: Coulomb's mu; any value > 0 uses the frictional
#   non-smooth Gauss-Seidel whatever the solver named).
set -e
BIN=${1:-build/fidus_contact_benchmark}
STEPS=${2:-3}
SOLVERS=${SOLVERS:-"pgs_subspace pgs apg pg"}
SIZES=${SIZES:-"1000 10000 100000"}
FRACTIONS=${FRACTIONS:-"0.3 0.5"}
if [ ! -x "$BIN" ]; then
  echo "no benchmark binary at $BIN (build it with: make fidus_contact_benchmark)" >&2
  exit 1
fi
echo "| dim | N | phi | solver | rows | active | iterations | projection [s] | in projection: search [s] | solve [s] | cell list alone [s] | R-tree alone [s] | residual |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for dim in 2 3; do
  for n in $SIZES; do
    for phi in $FRACTIONS; do
      for solver in $SOLVERS; do
        "$BIN" $dim $n $phi $solver $STEPS ${FRICTION:-0} |
          awk '{ gsub(/\)/, "", $19); res = $27; if (NF > 27) res = res " NOT CONVERGED";
                 printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n",
                 $1, $2, $3, $4, $6, $8, $12, $14, $17, $19, $21, $24, res }'
      done
    done
  done
done
