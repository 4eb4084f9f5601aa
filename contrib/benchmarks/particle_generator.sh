#!/bin/bash
# Particle generator benchmark: seconds to place N = 1e3, 1e4, 1e5 particles
# without overlap, for 2D bidisperse discs (radii 1 and 1.4, 50/50 by number,
# x periodic, walls in y) at area fractions 0.4 and 0.6, and 3D spheres
# (radius 1, x and z periodic, walls in y) at volume fractions 0.3 and 0.5.
# Prints a Markdown table. Not a test: it never asserts on time.
#
# Usage: contrib/benchmarks/particle_generator.sh [SEED]
#   Builds the benchmark stand-alone
#   with g++ (the contact library needs only Eigen and Boost) into
#   ${BIN:-/tmp/pg_bench}.
# Environment: SIZES (default "1000 10000 100000"), FRACTIONS_2D (default
# "0.4 0.6"), FRACTIONS_3D (default "0.3 0.5"), BIN, CXX (default g++).
set -e
cd "$(dirname "$0")/../.."
SEED=${1:-1}
BIN=${BIN:-/tmp/pg_bench}
SIZES=${SIZES:-"1000 10000 100000"}
FRACTIONS_2D=${FRACTIONS_2D:-"0.4 0.6"}
FRACTIONS_3D=${FRACTIONS_3D:-"0.3 0.5"}
nice -n 10 ${CXX:-g++} -O3 -std=c++17 -Iinclude -I/usr/include/eigen3 \
  contrib/benchmarks/particle_generator.cc source/contact/*.cc source/lubrication/*.cc source/particles/*.cc -o "$BIN"

echo "| dim | N | target | fraction reached | seconds | smallest gap / a_min | sweeps |"
echo "|---|---|---|---|---|---|---|"
for dim in 2 3; do
  if [ $dim = 2 ]; then fractions=$FRACTIONS_2D; else fractions=$FRACTIONS_3D; fi
  for phi in $fractions; do
    for n in $SIZES; do
      # A failed generation prints FAILED and its message; keep going.
      nice -n 10 "$BIN" $dim $n $phi $SEED |
        awk -v phi=$phi '
          $3 == "FAILED" { msg = $0; for (i = 0; i < 6; ++i) sub(/^[^ ]+ /, "", msg)
                           printf "| %s | %s | %s | FAILED | %s | - | %s |\n", $1, $2, phi, $4, msg; next }
          { printf "| %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, phi, $3, $4, $5, $6 }'
    done
  done
done
