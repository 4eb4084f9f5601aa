#!/usr/bin/env bash
# What the cut element's iterative solver's tolerance (Fluid/Cut linear
# tolerance) costs and changes: each scene runs at every tolerance of
# TOLERANCES, one rank, and its answers are compared with those of the
# first (smallest) tolerance. Scenes:
#   sphere3d  one sphere a = 0.1 off the centre in linear shear, maximum
#             level 5 (a/h = 3.2), 3 solves 0.02 apart;
#   pair3d    the paper's 3D pair (prm/two_particles_3d_cut.prm: a = 0.05,
#             the sub-grid correction below 0.05 a) placed GAP (default
#             0.1) radii apart on the compressional axis, 3 solves 0.02
#             apart;
#   dense3d   37 spheres at phi = 0.3 between sliding walls
#             (contrib/benchmarks/dense_configurations_cut_3d.prm: a/h = 2,
#             the correction below 0.4 a) placed by the generator as in
#             prm/rheology_steady_shear_3d.prm, one step (2 solves).
# The scenes of DIRECT (default none; "sphere3d": 4 GB and a minute per
# solve) also run once with the direct solver, whose difference from the
# reference shows the answers' round-off floor.
# Columns: FGMRES per solve, FGMRES and solve seconds per solve (means),
# and the largest differences from the reference over the particles and
# steps: of the velocities (U and omega, relative to the largest), of the
# stresslets (relative to the largest), of the pair's closing speed
# (relative to it), of eta_r, N1, N2 and Pi (in eta_f gamma_dot).
# Env: SCENES (default "sphere3d pair3d dense3d"), TOLERANCES (default
# "1e-11 1e-10 1e-9 1e-8 1e-7 1e-6"), GAP, DIRECT, FIDUS, WORK (keep the
# runs there).
# Usage: contrib/benchmarks/cut_tolerance.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
scenes="${SCENES:-sphere3d pair3d dense3d}"
tolerances="${TOLERANCES:-1e-11 1e-10 1e-9 1e-8 1e-7 1e-6}"
gap="${GAP:-0.1}"
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi

# scene_prm NAME OUT SOLVER_LINES: the scene's prm, output in OUT, with
# SOLVER_LINES (entries of Fluid) added.
scene_prm() {
  local fluid="s#^subsection Fluid#subsection Fluid\n$3#"
  local verbose='s/^subsection Output/subsection Output\n  set Verbosity = verbose/'
  case "$1" in
    sphere3d) cat <<PRM | sed -e "$fluid"
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
    pair3d)
      local h
      h=$(/usr/bin/python3 -c "print(0.05 * (2 + $gap) / 2 / 2**0.5)")
      local positions
      positions=$(/usr/bin/python3 -c "print('%.12g, %.12g, 0.5; %.12g, %.12g, 0.5' % (0.5 - $h, 0.5 + $h, 0.5 + $h, 0.5 - $h))")
      sed -e "s#^set Output directory.*#set Output directory = $2#" \
          -e "s/^  set Positions .*/  set Positions = $positions/" \
          -e 's/^  set End time .*/  set End time          = 0.04/' \
          -e 's/^  set Time step .*/  set Time step         = 0.02/' \
          -e 's/^  set Gap step fraction .*/  set Gap step fraction = 0/' \
          -e "$verbose" -e "$fluid" "$top/prm/two_particles_3d_cut.prm" ;;
    dense3d)
      sed -e "s#^set Output directory.*#set Output directory = $2#" \
          -e "s/^  set Radius = 0.125/  subsection Generator\n    set Fraction = 0.3\n    set Radii = 0.125\n    set Minimum separation = 0.01\n    set Seed = 1\n  end/" \
          -e "s/^subsection Mesh refinement/subsection Output\n  set Verbosity = verbose\nend\nsubsection Mesh refinement/" \
          -e "$fluid" "$top/contrib/benchmarks/dense_configurations_cut_3d.prm" ;;
    *) echo "cut_tolerance.sh: unknown scene '$1'; allowed: sphere3d pair3d dense3d" >&2; exit 1 ;;
  esac
}

for scene in $scenes; do
  echo
  echo "$scene:"
  echo
  echo "| solver | FGMRES per solve | FGMRES s | solve s | U | omega | stresslets | closing speed | eta_r | N1 | N2 | Pi |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
  reference=""
  cases="$tolerances"
  case " ${DIRECT:-} " in *" $scene "*) cases="$cases direct" ;; esac
  for t in $cases; do
    run="$work/${scene}_$t"
    if [ "$t" = direct ]; then lines='  set Cut linear solver = direct'
    else lines="  set Cut linear solver = iterative\n  set Cut linear tolerance = $t"; fi
    scene_prm "$scene" "$run" "$lines" > "$run.prm"
    if ! "$fidus" "$run.prm" > "$run.log" 2>&1; then
      echo "| $t | run failed: $(tail -1 "$run.log" | cut -c1-200) |"; continue
    fi
    [ -n "$reference" ] || reference="$run"
    /usr/bin/python3 - "$run" "$reference" "$t" <<'PY'
import csv, math, re, statistics, sys
run, ref, label = sys.argv[1:]
def particles(r):
    return {(p["step"], p["id"]): p for p in csv.DictReader(open(r + "/particles.csv"))}
def stats(r):
    return {s["step"]: s for s in csv.DictReader(open(r + "/statistics.csv"))}
a, b = particles(run), particles(ref)
keys = [k for k in a if k in b]
translation = ["ux", "uy", "uz"]
rotation = ["omega_x", "omega_y", "omega_z"]
sl = ["stresslet_" + c for c in ("xx", "xy", "xz", "yy", "yz", "zz")]
def rel(cols):
    big = max(abs(float(b[k][c])) for k in keys for c in cols)
    return max(abs(float(a[k][c]) - float(b[k][c])) for k in keys for c in cols) / big
def closing(p, step):
    rows = sorted((v for (s, i), v in p.items() if s == step), key=lambda v: v["id"])
    if len(rows) != 2:
        return None
    x = [float(rows[1][c]) - float(rows[0][c]) for c in ("x", "y", "z")]
    u = [float(rows[1][c]) - float(rows[0][c]) for c in ("ux", "uy", "uz")]
    n = math.sqrt(sum(v * v for v in x))
    return sum(x[i] * u[i] for i in range(3)) / n
steps = sorted({s for s, i in keys}, key=int)
speeds = [(closing(a, s), closing(b, s)) for s in steps]
closing_text = "" if speeds[0][0] is None else "%.1e" % max(abs(p - q) / abs(q) for p, q in speeds)
sa, sb = stats(run), stats(ref)
common = [s for s in sa if s in sb]
def dstat(c):
    return "%.1e" % max(abs(float(sa[s][c]) - float(sb[s][c])) for s in common)
log = open(run + ".log").read()
lines = [l for l in log.splitlines() if "cut element:" in l]
def mean(pattern):
    v = [float(m.group(1)) for l in lines for m in [re.search(pattern, l)] if m]
    return statistics.mean(v) if v else float("nan")
fgmres = mean(r"FGMRES (\d+)")
print("| %s | %s | %s | %.2f | %.1e | %.1e | %.1e | %s | %s | %s | %s | %s |" % (
    label, "direct" if math.isnan(fgmres) else "%.1f" % fgmres,
    "" if math.isnan(fgmres) else "%.2f" % mean(r"of which FGMRES ([0-9.e+-]+)"),
    mean(r"solve ([0-9.e+-]+)"), rel(translation), rel(rotation), rel(sl),
    closing_text,
    dstat("relative_viscosity"), dstat("normal_stress_difference_1"),
    dstat("normal_stress_difference_2"), dstat("particle_pressure")))
PY
  done
done
