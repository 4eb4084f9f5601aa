#!/usr/bin/env bash
# Squeeze test of the sub-grid lubrication correction (dense-suspension
# issue): two equal discs (2D) on the compressional axis of a linear shear
# (u = y e_x in the unit box, line of centres at -45 degrees through the
# box centre), at gaps h from GAPS (relative to the radius a). The shear
# pushes the pair together; the quantity compared is the closing speed
#   s = -n . (U1 - U0),  normalised by the undisturbed one, d/2 (d = |X1-X0|).
# For each gap and coarse level it prints s from
#   - the mesh alone (the fluid's rigid velocities, no correction),
#   - the mesh plus 'Fluid/Lubrication correction' (s from the gap change
#     over one explicit step of DT, which carries the corrected velocity),
# and divides both by a resolved reference: the same box and pair at the
# reference levels REF (no correction), with the gap refined to the
# finest level. The two reference levels must agree before the ratios mean
# anything; their difference is printed.
# Env: A (radius, default 0.1), LEVELS (coarse levels, default "4 5": the
# diameter spans 3.2 and 6.4 cells), REF (default "10 11"), GAPS (default
# "0.5 0.2 0.1 0.05 0.02 0.01"), DT (default 1e-4), RETRACTION (Solid
# retraction of the coarse runs, default 0), REF_RETRACTION (of the
# reference, default 0.45: the cut-cell bias of the radius, doc/rheology.md),
# RIGID_TOL (Rigid velocity tolerance, default 1e-5), FLOW_RANGE
# (Lubrication flow range of the corrected runs, default auto), WORK (keep
# the runs there; finished runs found there are not run again), FIDUS.
# Usage: contrib/benchmarks/squeeze_pair.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
a="${A:-0.1}"; levels="${LEVELS:-4 5}"; ref="${REF:-10 11}"
gaps="${GAPS:-0.5 0.2 0.1 0.05 0.02 0.01}"; dt="${DT:-1e-4}"
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi

# run <name> <gap/a> <level> <lubrication true|false> <gap refinement>
#     <solid retraction>
run() {
  local name="$1" gap="$2" level="$3" lub="$4" gapref="$5" retraction="$6"
  local positions
  positions=$(/usr/bin/python3 -c "
import math
a, g = $a, $gap
s = (2 * a + g * a) / (2 * math.sqrt(2.))
print('%.15f, %.15f; %.15f, %.15f' % (0.5 - s, 0.5 + s, 0.5 + s, 0.5 - s))")
  cat > "$work/$name.prm" <<PRM
set Dimension = 2
set Output directory = $work/$name
subsection Domain
  set Boundary condition = linear shear
end
subsection Fluid
  set Rigidity tolerance = 1e-5
  set Rigidity measure = box
  set Rigid velocity tolerance = ${RIGID_TOL:-1e-5}
  set Maximum Uzawa iterations = 30
  set Solid retraction = $retraction
  set Shared cells = fluid
  set Lubrication correction = $lub
  set Lubrication flow range = ${FLOW_RANGE:-auto}
  subsection Linear solver
    set Tolerance = 1e-9
  end
end
subsection Particles
  set Radius = $a
  set Positions = $positions
end
subsection Contact
  set Model = none
end
subsection Time stepping
  set End time = $dt
  set Time step = $dt
end
subsection Mesh refinement
  set Initial global refinement = 3
  set Minimum level = 3
  set Maximum level = $level
  set Gap refinement distance = $gapref
end
subsection Output
  set Verbosity = quiet
  set Checkpoint wall interval = 0
end
PRM
  # A finished run in WORK is kept (a study stopped half-way resumes, and
  # the references can be copied into another WORK).
  if [ -f "$work/$name.wall" ] && [ -f "$work/$name/particles.csv" ]; then
    return 0
  fi
  local start; start=$(date +%s.%N)
  if ! "$fidus" "$work/$name.prm" > "$work/$name.log" 2>&1; then
    echo "run $name failed:" >&2; tail -3 "$work/$name.log" >&2; return 1
  fi
  echo "$(date +%s.%N) - $start" | bc > "$work/$name.wall"
}

# closing <name> <mesh|step>: normalised closing speed of a run
closing() {
  /usr/bin/python3 - "$work/$1/particles.csv" "$2" "$dt" <<'PY'
import csv, math, sys
path, how, dt = sys.argv[1], sys.argv[2], float(sys.argv[3])
rows = list(csv.DictReader(open(path)))
def at(step):
    r = [x for x in rows if int(x["step"]) == step]
    r.sort(key=lambda x: int(x["id"]))
    return [(float(x["x"]), float(x["y"]), float(x["ux"]), float(x["uy"])) for x in r]
p0 = at(0)
dx, dy = p0[1][0] - p0[0][0], p0[1][1] - p0[0][1]
d = math.hypot(dx, dy)
if how == "mesh":
    s = -(dx * (p0[1][2] - p0[0][2]) + dy * (p0[1][3] - p0[0][3])) / d
else:
    p1 = at(1)
    d1 = math.hypot(p1[1][0] - p1[0][0], p1[1][1] - p1[0][1])
    s = -(d1 - d) / dt
print("%.10g" % (s / (0.5 * d)))
PY
}

echo "Two discs a = $a on the compressional axis, closing speed / (d/2)."
echo "Reference levels: $ref (no correction, gap refinement 0.05 a)."
echo
echo "| h/a | reference | ref. levels differ | level | mesh alone / ref | with correction / ref | wall s (coarse, correction) |"
echo "|---|---|---|---|---|---|---|"
for g in $gaps; do
  refs=()
  for L in $ref; do
    run "ref_${g}_$L" "$g" "$L" false 0.05 "${REF_RETRACTION:-0.45}"
    refs+=("$(closing "ref_${g}_$L" mesh)")
  done
  best="${refs[${#refs[@]}-1]}"
  spread=$(/usr/bin/python3 -c "
r = [float(x) for x in '${refs[*]}'.split()]
print('%.1e' % (abs(r[-1] - r[0]) / abs(r[-1])) if len(r) > 1 else '')")
  for L in $levels; do
    run "off_${g}_$L" "$g" "$L" false 0.5 "${RETRACTION:-0}"
    run "on_${g}_$L" "$g" "$L" true 0.5 "${RETRACTION:-0}"
    mesh=$(closing "off_${g}_$L" mesh)
    corr=$(closing "on_${g}_$L" step)
    printf "| %s | %.5g | %s | %s | %.3f | %.3f | %.1f |\n" "$g" "$best" "$spread" "$L" \
      "$(echo "$mesh / $best" | bc -l)" "$(echo "$corr / $best" | bc -l)" \
      "$(cat "$work/on_${g}_$L.wall")"
  done
done
