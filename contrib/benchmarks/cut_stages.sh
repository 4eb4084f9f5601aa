#!/usr/bin/env bash
# Where a cut element step's time goes: the stages of each solve (mesh,
# DoFs and sparsity pattern, assembly, solve and its FGMRES, measurement)
# that fidus prints with Output/Verbosity = verbose, averaged over the
# solves of a short run of each scene, for one or more builds run one
# after the other (REPEAT rounds, alternating, so that a busy machine
# hurts them alike). Scenes:
#   sphere3d   one sphere a = 0.1 off the centre in linear shear, maximum
#              level 5 (a/h = 3.2), 3 solves (the iterative solver);
#   pair3d     prm/two_particles_3d_cut.prm, 3 solves;
#   dense2d    prm/rheology_steady_shear_2d_cut.prm with the sub-grid
#              correction below 0.02 a and no gap cells, 4 solves (the
#              direct solver);
#   dense2d_resolved  the same prm as shipped (every gap resolved), 2 solves;
#   dense3d    the 37 spheres of prm/rheology_steady_shear_3d.prm (phi =
#              0.3, sliding walls) at their generated start, a/h = 2, the
#              sub-grid correction below 0.4 a, no gap cells, 2 solves.
# Env: SCENES (default "sphere3d pair3d dense2d"), BINARIES ("label=path
# ...", default "current=build-release/fidus"), RANKS (MPI ranks, default
# "1"; several: "1 2", each run with mpirun --bind-to none, so that one
# rank takes every core as threads), REPEAT (default 1), WORK (keep the
# runs there). Prints one Markdown row per build, scene and number of ranks
# (the seconds per solve, the unknowns and FGMRES of the first solve, and
# the peak memory per rank).
# Usage: BINARIES="before=/path/fidus after=build-release/fidus" \
#          contrib/benchmarks/cut_stages.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
scenes="${SCENES:-sphere3d pair3d dense2d}"
if [ -z "${BINARIES:-}" ]; then
  "$top/contrib/build.sh" fidus >/dev/null
  BINARIES="current=$top/build-release/fidus"
fi
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi

# scene_prm NAME OUT: print the scene's prm with its output in OUT.
scene_prm() {
  local verbose='s/^subsection Output/subsection Output\n  set Verbosity = verbose/'
  case "$1" in
    sphere3d) cat <<PRM
set Dimension        = 3
set Output directory = $2
subsection Domain
  set Lower left         = 0, 0, 0
  set Upper right        = 1, 1, 1
  set Boundary condition = linear shear
  set Shear rate         = 1
end
subsection Fluid
  set Model = cut finite element
end
subsection Particles
  set Radius    = 0.1
  set Positions = 0.43, 0.56, 0.52
end
subsection Time stepping
  set End time  = 0.04
  set Time step = 0.02
end
subsection Mesh refinement
  set Initial global refinement = 2
  set Minimum level             = 2
  set Maximum level             = 5
end
subsection Output
  set Verbosity = verbose
end
PRM
    ;;
    pair3d) sed -e "s#^set Output directory.*#set Output directory = $2#" \
                -e 's/^  set End time .*/  set End time          = 0.4/' \
                -e "$verbose" "$top/prm/two_particles_3d_cut.prm" ;;
    dense2d) sed -e "s#^set Output directory.*#set Output directory = $2#" \
                 -e "s/Cut minimum gap = 1e-4/Cut minimum gap = 0.02\n  set Lubrication correction = true/" \
                 -e "s/Cut gap cells   = 2/Cut gap cells   = 0/" \
                 -e 's/End time  = 1.5/End time  = 0.06/' \
                 -e "$verbose" "$top/prm/rheology_steady_shear_2d_cut.prm" ;;
    dense2d_resolved) sed -e "s#^set Output directory.*#set Output directory = $2#" \
                 -e 's/End time  = 1.5/End time  = 0.02/' \
                 -e "$verbose" "$top/prm/rheology_steady_shear_2d_cut.prm" ;;
    dense3d) cat <<PRM
set Dimension        = 3
set Output directory = $2
subsection Domain
  set Lower left         = 0, 0, 0
  set Upper right        = 1, 1, 1
  set Boundary condition = sliding walls
end
subsection Fluid
  set Model                  = cut finite element
  set Cut minimum gap        = 0.4
  set Cut gap cells          = 0
  set Lubrication correction = true
end
subsection Particles
  subsection Generator
    set Fraction           = 0.3
    set Radii              = 0.125
    set Minimum separation = 0.01
    set Seed               = 1
  end
end
subsection Contact
  set Model = gluey
end
subsection Time stepping
  set End time  = 0.002
  set Time step = 0.002
end
subsection Mesh refinement
  set Initial global refinement = 4
  set Minimum level             = 4
  set Maximum level             = 4
end
subsection Output
  set Verbosity = verbose
end
PRM
    ;;
    *) echo "cut_stages.sh: unknown scene '$1'; allowed: sphere3d pair3d dense2d dense2d_resolved dense3d" >&2; exit 1 ;;
  esac
}

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
echo "| scene | build | ranks | round | unknowns | FGMRES | mesh | DoFs and pattern | assembly | solve | of which FGMRES | measure | s per solve | peak |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for round in $(seq "${REPEAT:-1}"); do
  for scene in $scenes; do
    for ranks in ${RANKS:-1}; do
    for binary in $BINARIES; do
      label="${binary%%=*}"; path="${binary#*=}"
      run="$work/${scene}_${label}_${ranks}_$round"
      scene_prm "$scene" "$run" > "$run.prm"
      launch=()
      [ "$ranks" = 1 ] || launch=(mpirun --bind-to none -np "$ranks")
      if ! "${launch[@]}" "$path" "$run.prm" > "$run.log" 2>&1; then
        echo "| $scene | $label | $ranks | $round | run failed: $run.log |"; continue
      fi
      /usr/bin/python3 - "$run.log" "$scene" "$label" "$round" "$ranks" <<'PY'
import re, statistics, sys
log, scene, label, rnd, ranks = sys.argv[1:]
text = open(log).read()
keys = ["mesh", "DoFs and pattern", "assembly", "solve", "of which FGMRES", "measure", "all"]
rows = []
for line in text.splitlines():
    if "cut element:" not in line:
        continue
    row = {k: float(v) for k, v in re.findall(r"(mesh|DoFs and pattern|assembly|solve|of which FGMRES|measure|all) ([0-9.e+-]+)", line)}
    row.setdefault("of which FGMRES", 0.)
    unknowns = re.search(r"(\d+) unknowns", line).group(1)
    fgmres = re.search(r"FGMRES (\d+)", line)
    rows.append((row, unknowns, fgmres.group(1) if fgmres else "direct"))
peak = re.search(r"peak memory per rank: ([0-9.]+ [KMG]B)", text)
mean = {k: statistics.mean(r[0][k] for r in rows) for k in keys}
print("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
    scene, label, ranks, rnd, rows[0][1], rows[0][2],
    " | ".join("%.2f" % mean[k] for k in keys), peak.group(1) if peak else "?"))
PY
    done
    done
  done
done
