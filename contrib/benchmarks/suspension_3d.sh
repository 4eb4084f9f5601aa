#!/usr/bin/env bash
# Long 3D stress run (issue: numerical robustness): N spheres at volume
# fraction phi between sliding walls (periodic in x and z), sheared with
# the fictitious-domain fluid and the chosen contact model for S strain
# units. The short version is tests/robustness/suspension_3d (one step).
# Prints: steps, smallest gap over the run (must be >= -tolerance), the
# largest Uzawa and FGMRES counts per step, max |U| and |omega| over the
# run, the wall time, and whether any value was NaN.
# Set KEEP=<dir> to keep the output directory (CSV files) in <dir>.
# Long runs: WORK=<dir> works in <dir> (kept) instead of a temporary folder,
# CHECKPOINT=<steps> writes a checkpoint every <steps> steps (and on
# SIGTERM/SIGINT), and RESUME=1 with the same WORK continues the run there
# from its newest checkpoint ('fidus --resume').
# SHARED_CELLS=rigid|fluid|auto and REUSE=true|false|auto set Fluid/Shared
# cells and Fluid/Reuse multiplier (default auto, fidus's default: released
# shared cells and no warm start, since a contact model is on);
# LUBRICATION=true adds the sub-grid lubrication correction (default
# false); RIGIDITY=<tolerance> (default 1e-2) and MAX_UZAWA=<n> (default 5)
# set Fluid/Rigidity tolerance and Fluid/Maximum Uzawa iterations;
# MEASURE=box|particle (default box, the measure of the tables in doc/)
# sets Fluid/Rigidity measure (RIGIDITY=auto MEASURE=particle MAX_UZAWA=50
# is fidus's default);
# INEXACT=<factor> (default 0) sets Fluid/Linear solver/Inexact Uzawa
# factor.
# Usage: contrib/benchmarks/suspension_3d.sh [gluey|inelastic] \
#          [strain, default 1] [N, default 24] [phi, default 0.25] \
#          [max level, default 4] [time step, default 0.1]
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
model="${1:-gluey}"; strain="${2:-1}"; n="${3:-24}"; phi="${4:-0.25}"
level="${5:-4}"; dt="${6:-0.1}"
. "$top/contrib/benchmarks/long_run.sh"
long_run_prepare suspension.prm

# Random sequential addition, minimum image in x and z, clear of the y walls.
a=$(/usr/bin/python3 - "$n" "$phi" "$work/positions.txt" <<'PY'
import math, random, sys
n, phi, out = int(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
a = (3 * phi / (4 * math.pi * n)) ** (1 / 3)
random.seed(1)
x = []
def d2(p, q):
    dx = p[0] - q[0] - round(p[0] - q[0])
    dz = p[2] - q[2] - round(p[2] - q[2])
    return dx * dx + (p[1] - q[1]) ** 2 + dz * dz
tries = 0
while len(x) < n:
    tries += 1
    if tries > 10 ** 6:
        sys.exit("suspension_3d.sh: could not place %d spheres at phi = %g" % (n, phi))
    p = (random.random(), random.random(), random.random())
    if not (a + 1e-3 < p[1] < 1 - a - 1e-3):
        continue
    if all(d2(p, q) >= (2 * a + 1e-3) ** 2 for q in x):
        x.append(p)
open(out, "w").write("".join("%.15f %.15f %.15f\n" % p for p in x))
print("%.15f" % a)
PY
)
cat > "$work/suspension.prm" <<EOF2
set Dimension = 3
set Output directory = $work/out
subsection Domain
  set Lower left = 0, 0, 0
  set Upper right = 1, 1, 1
  set Boundary condition = sliding walls
end
subsection Fluid
  set Model = fictitious domain
  set Rigidity tolerance = ${RIGIDITY:-1e-2}
  set Rigidity measure = ${MEASURE:-box}
  set Maximum Uzawa iterations = ${MAX_UZAWA:-5}
  set Shared cells = ${SHARED_CELLS:-auto}
  set Reuse multiplier = ${REUSE:-auto}
  set Lubrication correction = ${LUBRICATION:-false}
  subsection Linear solver
    set Inexact Uzawa factor = ${INEXACT:-0}
  end
end
subsection Particles
  set Radius = $a
  set Positions file = $work/positions.txt
end
subsection Contact
  set Model = $model
end
subsection Time stepping
  set End time = $strain
  set Time step = $dt
end
subsection Mesh refinement
  set Initial global refinement = 2
  set Minimum level = 2
  set Maximum level = $level
end
subsection Output
  set Progress interval = 5
  set Checkpoint interval = ${CHECKPOINT:-0}
end
EOF2
echo "3D: N = $n, phi = $phi, a = $a, $model, strain $strain, level $level, dt $dt"
status=0
start=$(date +%s)
"$fidus" "$work/suspension.prm" || status=$?
echo "wall seconds $(( $(date +%s) - start ))"
"$top/contrib/benchmarks/summarize_run.sh" "$work/out"
if [ -n "${KEEP:-}" ]; then mkdir -p "$KEEP" && cp -r "$work/out/." "$KEEP/"; fi
exit $status
