#!/usr/bin/env bash
# The BLAS under fidus: Debian's reference BLAS/LAPACK against OpenBLAS
# (libopenblas0-serial, which contrib/install_dependencies.sh installs and
# which Debian's alternatives then select), on the same machine in one run.
# Each case runs once with each library, chosen with LD_LIBRARY_PATH, and
# the table gives the wall seconds and the largest difference of the
# results (particle positions, or the cut inclusion's errors). Not a test.
#
#   - cut 3D: the exact 3D inclusion with the cut element, level 3, one
#     solve (MUMPS's dense fronts are most of it);
#   - cut 2D: the exact 2D inclusion, level 8, one solve;
#   - cut sliding walls: 20 discs a = 0.05, area fraction 0.16, between
#     sliding walls, the cut element, 5 steps;
#   - FD paper pair: prm/two_particles_2d.prm (the fictitious domain:
#     FGMRES with Trilinos' AMG, whose coarse solves use LAPACK).
#
# Usage: contrib/benchmarks/blas_choice.sh
# Env: FIDUS, FIDUS_CUT_INCLUSION (the binaries; default: built with
#   contrib/build.sh).
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
lib=/usr/lib/x86_64-linux-gnu
reference="$lib/blas:$lib/lapack"
openblas="$lib/openblas-serial"
if [ ! -e "$openblas/libblas.so.3" ]; then
  echo "blas_choice: $openblas/libblas.so.3 is missing (apt-get install libopenblas0-serial)" >&2
  exit 1
fi
fidus="${FIDUS:-}"
cut="${FIDUS_CUT_INCLUSION:-}"
if [ -z "$fidus" ] || [ -z "$cut" ]; then
  "$top/contrib/build.sh" fidus fidus_cut_inclusion >/dev/null
  fidus="${fidus:-$top/build-release/fidus}"
  cut="${cut:-$top/build-release/fidus_cut_inclusion}"
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

seconds() { # command... -> wall seconds on stdout, its output in $work/out
  local t0 t1
  t0=$(date +%s.%N)
  "$@" > "$work/out" 2> "$work/err"
  t1=$(date +%s.%N)
  echo "$t1 - $t0" | bc -l
}

# The last line of a CSV's rows for the last step, as numbers.
final_positions() { # particles.csv -> "x y" per particle of the last time
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
           { t = $col["time"]; x[$col["id"]] = $col["x"]; y[$col["id"]] = $col["y"]; last = t }
           END { for (i in x) print i, x[i], y[i] }' "$1" | sort -n
}

max_difference() { # two files of "id x y" -> largest |dX|
  paste "$1" "$2" | awk '{ d = sqrt(($2 - $5)^2 + ($3 - $6)^2); if (d > m) m = d } END { printf "%.1e", m }'
}

cat > "$work/sliding.prm" <<'EOF'
set Dimension = 2
subsection Domain
  set Boundary condition = sliding walls
end
subsection Fluid
  set Model = cut finite element
end
subsection Particles
  subsection Generator
    set Fraction           = 0.16
    set Radii              = 0.05
    set Minimum separation = 0.02
    set Seed               = 1
  end
end
subsection Contact
  set Model = gluey
end
subsection Time stepping
  set End time  = 0.25
  set Time step = 0.05
end
subsection Mesh refinement
  set Initial global refinement = 3
  set Minimum level             = 3
  set Maximum level             = 5
end
subsection Output
  set Verbosity = quiet
end
EOF

echo "| case | reference BLAS s | OpenBLAS s | speed-up | largest difference |"
echo "|---|---|---|---|---|"
for case in "cut 3D" "cut 2D" "cut sliding walls" "FD paper pair"; do
  declare -A t=()
  for which in reference openblas; do
    path="$reference"
    [ "$which" = openblas ] && path="$openblas"
    dir="$work/$which"
    mkdir -p "$dir"
    case "$case" in
      "cut 3D")
        t[$which]=$(seconds env LD_LIBRARY_PATH="$path" "$cut" 3 0.1 3 1 0)
        # The errors' columns (all but the seconds).
        grep '^| 3 ' "$work/out" | cut -d'|' -f2-9 > "$dir/result" ;;
      "cut 2D")
        t[$which]=$(seconds env LD_LIBRARY_PATH="$path" "$cut" 2 0.1 8 1 2)
        grep '^| 8 ' "$work/out" | cut -d'|' -f2-9 > "$dir/result" ;;
      "cut sliding walls")
        sed "1a set Output directory = $dir/run" "$work/sliding.prm" > "$dir/run.prm"
        t[$which]=$(seconds env LD_LIBRARY_PATH="$path" "$fidus" "$dir/run.prm")
        final_positions "$dir/run/particles.csv" > "$dir/result" ;;
      "FD paper pair")
        sed "s|^set Output directory.*|set Output directory = $dir/paper|" \
          "$top/prm/two_particles_2d.prm" > "$dir/paper.prm"
        t[$which]=$(seconds env LD_LIBRARY_PATH="$path" "$fidus" "$dir/paper.prm")
        final_positions "$dir/paper/particles.csv" > "$dir/result" ;;
    esac
  done
  if [[ "$case" == cut\ [23]D ]]; then
    if cmp -s "$work/reference/result" "$work/openblas/result"; then
      difference="same digits"
    else
      difference="errors differ: $(tr -s ' ' < "$work/reference/result") / $(tr -s ' ' < "$work/openblas/result")"
    fi
  else
    difference="|ΔX| $(max_difference "$work/reference/result" "$work/openblas/result")"
  fi
  printf "| %s | %.2f | %.2f | %.2f | %s |\n" "$case" "${t[reference]}" \
    "${t[openblas]}" "$(echo "${t[reference]} / ${t[openblas]}" | bc -l)" \
    "$difference"
done
