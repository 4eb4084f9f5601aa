#!/usr/bin/env bash
# Force-driven squeeze of discs, the 2D counterpart of squeeze_force.sh.
# Two cylinders have no exact solution in a bounded box, and unbounded 2D
# Stokes flow has none at all (Stokes's paradox), so the reference is the
# resolved mesh itself: the same scene at maximum levels REF_LEVEL - 1 and
# REF_LEVEL, where the gap refinement puts several cells across the gap,
# without the correction, extrapolated to zero cell size at first order.
# 'Particles/External force' (1 per unit length) pushes
#   - pair: two equal discs towards each other along x,
#   - wall: one disc towards the wall y = 0,
#   - slide: one disc along the wall y = 0 (free to turn: the tangential
#     lubrication terms),
#   - pairslide: the two discs of 'pair' pushed past each other along y
#     (forces (0, 1) and (0, -1), free to turn: the pairs' tangential
#     terms; the speed is half the relative sliding speed),
# in the closed unit square at rest (linear shear with Shear rate = 0), at
# gaps h from GAPS (relative to the radius a), for each maximum level of
# LEVELS. Printed, divided by the reference speed:
#   - the mesh alone: the fluid's rigid velocity (particles.csv, step 0),
#   - mesh + 'Fluid/Lubrication correction': the displacement over one step
#     of DT (which carries the corrected velocity).
# The rows of the two reference levels show how far they are from it.
# Env: A (radius, default 0.1), LEVELS (default "6 7 8": the diameter spans
# 12.8 to 51 cells), REF_LEVEL (default 11), GAPS (default "0.2 0.1 0.05
# 0.02"), CASES (default "pair wall"), DT (default 1e-4), RETRACTIONS
# (Solid retraction of the LEVELS runs, default "0 0.3"; the references
# have none), RANGE (Lubrication range, default auto), TANGENTIAL_RANGE
# (Lubrication tangential range, default auto),
# RIGID_TOL (Rigid velocity tolerance, default 1e-5), ROUGHNESS (Contact/Roughness, default
# 5e-3, fidus's; gaps below it count as it), NP (MPI ranks per
# run, default 1), WORK (keep the runs there), FIDUS.
# Usage: contrib/benchmarks/squeeze_force_2d.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
a="${A:-0.1}"; levels="${LEVELS:-6 7 8}"; dt="${DT:-1e-4}"
ref_level="${REF_LEVEL:-11}"; retractions="${RETRACTIONS:-0 0.3}"
gaps="${GAPS:-0.2 0.1 0.05 0.02}"; cases="${CASES:-pair wall}"
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi
launch=()
[ "${NP:-1}" -gt 1 ] && launch=(mpirun -np "$NP")

# run <name> <case> <gap/a> <level> <lubrication true|false>
run() {
  local name="$1" case="$2" gap="$3" level="$4" lubrication="$5" positions forces
  # Without the correction only the rigid velocity of step 0 is used.
  local end_time="$dt"
  [ "$lubrication" = false ] && end_time=0
  if [ "$case" = pair ] || [ "$case" = pairslide ]; then
    positions=$(/usr/bin/python3 -c "
a, g = $a, $gap
s = a + 0.5 * g * a
print('%.15f, 0.5; %.15f, 0.5' % (0.5 - s, 0.5 + s))")
    forces="1, 0; -1, 0"
    [ "$case" = pairslide ] && forces="0, 1; 0, -1"
  else
    positions=$(/usr/bin/python3 -c "
a, g = $a, $gap
print('0.5, %.15f' % (a + g * a))")
    forces="0, -1"
    # slide: the same disc pushed along the wall (free to turn).
    [ "$case" = slide ] && forces="1, 0"
  fi
  cat > "$work/$name.prm" <<PRM
set Dimension = 2
set Output directory = $work/$name
subsection Domain
  set Lower left = 0, 0
  set Upper right = 1, 1
  set Boundary condition = linear shear
  set Shear rate = 0
end
subsection Fluid
  set Rigidity tolerance = 1e-4
  set Rigidity measure = box
  set Rigid velocity tolerance = ${RIGID_TOL:-1e-5}
  set Maximum Uzawa iterations = ${MAX_UZAWA:-30}
  set Solid retraction = ${RETRACTION:-0}
  set Shared cells = fluid
  set Lubrication correction = $lubrication
  set Lubrication range = ${RANGE:-auto}
  set Lubrication tangential range = ${TANGENTIAL_RANGE:-auto}
  subsection Linear solver
    set Tolerance = 1e-9
  end
end
subsection Particles
  set Radius = $a
  set Positions = $positions
  set External force = $forces
end
subsection Contact
  set Model = none
  set Walls = true
  set Roughness = ${ROUGHNESS:-5e-3}
end
subsection Time stepping
  set End time = $end_time
  set Time step = $dt
end
subsection Mesh refinement
  set Initial global refinement = 3
  set Minimum level = 3
  set Maximum level = $level
end
subsection Output
  set Verbosity = quiet
  set Field output interval = 0
  set Checkpoint wall interval = 0
end
PRM
  # A finished run in WORK is kept (a study stopped half-way resumes).
  if [ -f "$work/$name.wall" ] && [ -f "$work/$name/particles.csv" ]; then
    return 0
  fi
  local start; start=$(date +%s.%N)
  if ! "${launch[@]}" "$fidus" "$work/$name.prm" > "$work/$name.log" 2>&1; then
    echo "run $name failed:" >&2; tail -3 "$work/$name.log" >&2; return 1
  fi
  echo "$(date +%s.%N) - $start" | bc > "$work/$name.wall"
}

# speeds <name> <case>: the mesh's rigid speed and the speed over one step
speeds() {
  /usr/bin/python3 - "$work/$1/particles.csv" "$2" "$dt" <<'PY'
import csv, sys
path, case, dt = sys.argv[1], sys.argv[2], float(sys.argv[3])
rows = list(csv.DictReader(open(path)))
def at(step):
    r = sorted((x for x in rows if int(x["step"]) == step), key=lambda x: int(x["id"]))
    return [(float(x["x"]), float(x["y"]), float(x["ux"]), float(x["uy"])) for x in r]
p0, p1 = at(0), at(1)
step = float("nan")  # a run of step 0 only has no displacement
if case == "pair":   # approach speed of each disc: half the closing speed
    mesh = 0.5 * (p0[0][2] - p0[1][2])
    if p1:
        step = 0.5 * ((p0[1][0] - p0[0][0]) - (p1[1][0] - p1[0][0])) / dt
elif case == "pairslide":  # half the relative sliding speed
    mesh = 0.5 * (p0[0][3] - p0[1][3])
    if p1:
        step = 0.5 * ((p1[0][1] - p1[1][1]) - (p0[0][1] - p0[1][1])) / dt
elif case == "slide":  # speed along the wall
    mesh = p0[0][2]
    if p1:
        step = (p1[0][0] - p0[0][0]) / dt
else:                # speed towards the wall
    mesh = -p0[0][3]
    if p1:
        step = (p0[0][1] - p1[0][1]) / dt
print("%.10g %.10g" % (mesh, step))
PY
}

echo "Discs a = $a pushed by a force (1 per unit length), speed divided by the"
echo "resolved speed: the mesh alone (no correction, no retraction) at maximum"
echo "levels $((ref_level - 1)) and $ref_level, extrapolated to zero cell size at first"
echo "order (the rigid region's error is a fraction of a cell): 2 s($ref_level) - s($((ref_level - 1)))."
echo
echo "| case | h/a | level | retraction | a / cell | gap / cell | mesh alone / resolved | with correction / resolved | wall s |"
echo "|---|---|---|---|---|---|---|---|---|"
ratio() { /usr/bin/python3 -c "print('%.4f' % ($1 / $2))"; }
for c in $cases; do
  for g in $gaps; do
    fine="${c}_${g}_${ref_level}_ref"; finer_ok=true
    coarse="${c}_${g}_$((ref_level - 1))_ref"
    RETRACTION=0 run "$coarse" "$c" "$g" "$((ref_level - 1))" false || continue
    RETRACTION=0 run "$fine" "$c" "$g" "$ref_level" false || continue
    read -r s_coarse _ < <(speeds "$coarse" "$c")
    read -r s_fine _ < <(speeds "$fine" "$c")
    ref_speed=$(/usr/bin/python3 -c "print('%.10g' % (2 * $s_fine - $s_coarse))")
    for name in "$coarse" "$fine"; do
      L="${name%_ref}"; L="${L##*_}"
      read -r mesh _ < <(speeds "$name" "$c")
      printf "| %s | %s | %s (reference) | 0 | %.1f | %.2f | %s | | %.1f |\n" "$c" "$g" "$L" \
        "$(echo "$a * 2^$L" | bc -l)" "$(echo "$g * $a * 2^$L" | bc -l)" \
        "$(ratio "$mesh" "$ref_speed")" "$(cat "$work/$name.wall")"
    done
    for r in $retractions; do
      for L in $levels; do
        name="${c}_${g}_${L}_$r"
        RETRACTION=$r run "$name" "$c" "$g" "$L" true || continue
        read -r mesh corr < <(speeds "$name" "$c")
        printf "| %s | %s | %s | %s | %.1f | %.2f | %s | %s | %.1f |\n" "$c" "$g" "$L" "$r" \
          "$(echo "$a * 2^$L" | bc -l)" "$(echo "$g * $a * 2^$L" | bc -l)" \
          "$(ratio "$mesh" "$ref_speed")" "$(ratio "$corr" "$ref_speed")" \
          "$(cat "$work/$name.wall")"
      done
    done
  done
done
