#!/usr/bin/env bash
# Relative velocity of two equal spheres held at a fixed gap in simple shear,
# against Batchelor & Green's exact mobility functions (batchelor_green.py):
# the sheared-pair half of the dense-suspension issue's lubrication checks,
# taken apart from the trajectory. Two force-free spheres of radius A sit in
# the middle of the unit box in linear shear u = (y - 1/2) e_x (rate 1), their
# line of centres at angle THETA (degrees) from the flow direction, in the
# shear plane, at gaps h from GAPS (relative to a). Exact (unbounded):
#   radial      dr/dt       = r (1 - A(r)) sin(th) cos(th)
#   tangential  r dth/dt    = -r [sin^2(th) + B(r)/2 cos(2 th)]
# At 135 degrees the pair is on the compressional axis (it closes at the
# largest rate; the tangential part does not depend on B); at 90 degrees it
# sits across the flow, where the passing pair is closest (no radial part,
# the tangential part is 1 - B/2).
# Printed, divided by the exact value, for each maximum level of LEVELS:
#   - the mesh alone: the fluid's rigid velocities (particles.csv at step 0),
#   - mesh + 'Fluid/Lubrication correction': the displacement over one step
#     of DT (which carries the corrected velocities).
# The box's walls, 9a from the pair at a = 0.05, are not in the reference:
# they change the far field by a few per cent.
# Env: A (radius, default 0.05), LEVELS (default "5 6": a diameter spans 3.2
# and 6.4 cells), GAPS (default "0.1 0.02 0.005"), ANGLES (default "135 90"),
# DT (default 1e-4), RANGE (Lubrication range, default auto), FLOW_RANGE
# (Lubrication flow range, default auto; 0.3 gives the correction as it was
# before the flow range existed, commit 3ac5e56), TANGENTIAL
# (Lubrication tangential terms, default true), RIGIDITY (Rigidity tolerance,
# default 1e-4), MAX_UZAWA (default 10), RETRACTION (Solid retraction,
# default: fidus's), FLOW_EDGE (Lubrication flow edge, default auto), NP (MPI
# ranks per run, default 1), JOBS (runs at a time, default 1), SHIFT (the
# pair's midpoint moved off the mesh vertex (1/2, 1/2) by "sx sy" finest
# cells, default "0 0"), WORK (keep the runs there), FIDUS.
# Usage: contrib/benchmarks/shear_pair_velocity.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
a="${A:-0.05}"; levels="${LEVELS:-5 6}"; dt="${DT:-1e-4}"
gaps="${GAPS:-0.1 0.02 0.005}"; angles="${ANGLES:-135 90}"; jobs="${JOBS:-1}"
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi
launch=()
[ "${NP:-1}" -gt 1 ] && launch=(mpirun -np "$NP")

# run <name> <angle> <gap/a> <level>
run() {
  local name="$1" angle="$2" gap="$3" level="$4" positions
  positions=$(/usr/bin/python3 -c "
import math
a, g, th = $a, $gap, math.radians($angle)
s = a + 0.5 * g * a
dx, dy = s * math.cos(th), s * math.sin(th)
sx, sy = (float(v) * 0.5 ** $level for v in '${SHIFT:-0 0}'.split())
cx, cy = 0.5 + sx, 0.5 + sy
print('%.15f, %.15f, 0.5; %.15f, %.15f, 0.5' % (cx - dx, cy - dy, cx + dx, cy + dy))")
  cat > "$work/$name.prm" <<PRM
set Dimension = 3
set Output directory = $work/$name
subsection Domain
  set Lower left = 0, 0, 0
  set Upper right = 1, 1, 1
  set Boundary condition = linear shear
  set Shear rate = 1
end
subsection Fluid
  set Rigidity tolerance = ${RIGIDITY:-1e-4}
  set Rigidity measure = box
  set Maximum Uzawa iterations = ${MAX_UZAWA:-10}
  set Shared cells = fluid
  set Lubrication correction = true
  set Lubrication range = ${RANGE:-auto}
  set Lubrication flow range = ${FLOW_RANGE:-auto}
  set Lubrication flow edge = ${FLOW_EDGE:-auto}
${RETRACTION:+  set Solid retraction = $RETRACTION}
  set Lubrication tangential terms = ${TANGENTIAL:-true}
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
  set Walls = true
end
subsection Time stepping
  set End time = $dt
  set Time step = $dt
end
subsection Mesh refinement
  set Initial global refinement = 2
  set Minimum level = 2
  set Maximum level = $level
end
subsection Output
  set Verbosity = quiet
  set Field output interval = 0
  set Checkpoint wall interval = 0
end
PRM
  local start; start=$(date +%s.%N)
  if ! "${launch[@]}" "$fidus" "$work/$name.prm" > "$work/$name.log" 2>&1; then
    echo "run $name failed:" >&2; tail -3 "$work/$name.log" >&2; return 1
  fi
  echo "$(date +%s.%N) - $start" | bc > "$work/$name.wall"
}

# ratios <name> <angle> <gap/a>: exact radial and tangential velocity (a gdot),
# then mesh / exact and corrected / exact for each
ratios() {
  /usr/bin/python3 - "$work/$1/particles.csv" "$2" "$3" "$a" "$dt" "$top/contrib/benchmarks" <<'PY'
import csv, math, sys
path, angle, gap, a, dt = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
sys.path.insert(0, sys.argv[6])
from batchelor_green import Mobility
th = math.radians(angle)
r = 2 + gap
A, B = Mobility().AB(r)
n, t = (math.cos(th), math.sin(th)), (-math.sin(th), math.cos(th))
exact = (r * (1 - A) * math.sin(th) * math.cos(th),
         -r * (math.sin(th) ** 2 + 0.5 * B * math.cos(2 * th)))
rows = list(csv.DictReader(open(path)))
def at(step):
    s = sorted((x for x in rows if int(x["step"]) == step), key=lambda x: int(x["id"]))
    return [(float(x["x"]), float(x["y"]), float(x["ux"]), float(x["uy"])) for x in s]
p0, p1 = at(0), at(1)
mesh = (p0[1][2] - p0[0][2], p0[1][3] - p0[0][3])
step = tuple(((p1[1][k] - p1[0][k]) - (p0[1][k] - p0[0][k])) / dt for k in (0, 1))
def split(v):   # in units of a gdot
    return (v[0] * n[0] + v[1] * n[1]) / a, (v[0] * t[0] + v[1] * t[1]) / a
def ratio(x, e):
    return "%.4f" % (x / e) if abs(e) > 1e-12 else "(%.2e)" % x
m, c = split(mesh), split(step)
print("%.4g %.4g %s %s %s %s" % (exact[0], exact[1], ratio(m[0], exact[0]),
      ratio(c[0], exact[0]), ratio(m[1], exact[1]), ratio(c[1], exact[1])))
PY
}

echo "Two spheres a = $a held in shear (rate 1); relative velocity over the exact"
echo "(Batchelor & Green). Radial: closing speed along the line of centres;"
echo "tangential: speed across it. A value in brackets is the velocity itself"
echo "(in a gdot), where the exact one is 0."
echo
echo "| angle | h/a | level | exact radial | mesh / exact | corrected / exact | exact tangential | mesh / exact | corrected / exact | wall s |"
echo "|---|---|---|---|---|---|---|---|---|---|"
names=()
for th in $angles; do
  for g in $gaps; do
    for L in $levels; do
      names+=("${th}_${g}_$L")
    done
  done
done
# runs, JOBS at a time
running=0
for name in "${names[@]}"; do
  IFS=_ read -r th g L <<< "$name"
  run "$name" "$th" "$g" "$L" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then wait -n || true; running=$((running - 1)); fi
done
wait || true
for name in "${names[@]}"; do
  IFS=_ read -r th g L <<< "$name"
  [ -f "$work/$name.wall" ] || continue
  read -r er et mr cr mt ct < <(ratios "$name" "$th" "$g")
  printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %.1f |\n" "$th" "$g" "$L" \
    "$er" "$mr" "$cr" "$et" "$mt" "$ct" "$(cat "$work/$name.wall")"
done
