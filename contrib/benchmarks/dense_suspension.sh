#!/usr/bin/env bash
# Long stress run (issue: numerical robustness): a dense 2D suspension of
# N discs at area fraction phi between sliding walls (periodic in x),
# sheared for S strain units, with the chosen contact model and fluid
# model. The short version is tests/robustness/dense_2d.
# Prints: steps, smallest gap over the run (must be >= -tolerance), the
# largest Uzawa and FGMRES counts per step, max |U| and |omega| over the
# run, and whether any value was NaN (contrib/benchmarks/summarize_run.sh).
# At area fraction 0.4 many gaps are below the cell size, where one cell
# would have to carry two rigid motions: with such cells held rigid
# (SHARED_CELLS=rigid, the seed's model) the Uzawa loop cannot reach its
# tolerance (a warning per step; cap it with MAX_UZAWA=3). fidus's default
# releases them, since a contact model is on (doc/fluid.md).
# Set KEEP=<dir> to keep the output directory (CSV files) in <dir>.
# RIGIDITY=<tol> (default 1e-3) sets Fluid/Rigidity tolerance, in the box
# measure of the tables in doc/.
# MAX_UZAWA=<n> (default 50, fidus's), SHARED_CELLS=rigid|fluid|auto and
# REUSE=true|false|auto (default auto, fidus's) set Fluid/Maximum Uzawa
# iterations, Fluid/Shared cells and Fluid/Reuse multiplier;
# INEXACT=<factor> (default 0) sets Fluid/Linear solver/Inexact Uzawa
# factor; LUBRICATION=true|false (default false) sets Fluid/Lubrication
# correction; METHOD=auto|iterative|direct (default auto, fidus's) sets
# Fluid/Linear solver/Method.
# Long runs: WORK=<dir> works in <dir> (kept) instead of a temporary folder,
# CHECKPOINT=<steps> writes a checkpoint every <steps> steps (and on
# SIGTERM/SIGINT), and RESUME=1 with the same WORK continues the run there
# from its newest checkpoint ('fidus --resume').
# With "cut finite element" the gaps are resolved (lubrication included),
# one serial sparse direct solve per step; no field output.
# Usage: contrib/benchmarks/dense_suspension.sh [gluey|inelastic] \
#          ["fictitious domain"|"undisturbed shear"|"cut finite element"] \
#          [strain, default 10] \
#          [N, default 100] [phi, default 0.4] [max level, default 7]
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
model="${1:-gluey}"; fluid="${2:-fictitious domain}"; strain="${3:-10}"
n="${4:-100}"; phi="${5:-0.4}"; level="${6:-7}"
. "$top/contrib/benchmarks/long_run.sh"
long_run_prepare dense.prm

# Random sequential addition, minimum image in x, clear of the y walls.
a=$(/usr/bin/python3 - "$n" "$phi" "$work/positions.txt" <<'PY'
import math, random, sys
n, phi, out = int(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
a = math.sqrt(phi / (n * math.pi))
random.seed(1)
x = []
while len(x) < n:
    p = (random.random(), random.random())
    if not (a + 1e-3 < p[1] < 1 - a - 1e-3):
        continue
    if all((lambda dx, dy: dx * dx + dy * dy)(p[0] - q[0] - round(p[0] - q[0]),
                                              p[1] - q[1]) >= (2 * a + 1e-3) ** 2
           for q in x):
        x.append(p)
open(out, "w").write("".join("%.15f %.15f\n" % p for p in x))
print("%.15f" % a)
PY
)
cat > "$work/dense.prm" <<EOF2
set Dimension = 2
set Output directory = $work/out
subsection Domain
  set Boundary condition = sliding walls
end
subsection Fluid
  set Model = $fluid
  set Rigidity tolerance = ${RIGIDITY:-1e-3}
  set Rigidity measure = box
  set Maximum Uzawa iterations = ${MAX_UZAWA:-50}
  set Shared cells = ${SHARED_CELLS:-auto}
  set Reuse multiplier = ${REUSE:-auto}
  set Lubrication correction = ${LUBRICATION:-false}
  subsection Linear solver
    set Inexact Uzawa factor = ${INEXACT:-0}
    set Method = ${METHOD:-auto}
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
  set Time step = 0.02
end
subsection Mesh refinement
  set Initial global refinement = 4
  set Minimum level = 4
  set Maximum level = $level
end
subsection Output
  set Progress interval = 25
  set Checkpoint interval = ${CHECKPOINT:-0}
$([ "$fluid" = "cut finite element" ] && echo "  set Field output interval = 0")
end
EOF2
echo "N = $n, phi = $phi, a = $a, $model, $fluid, strain $strain, level $level"
status=0
"$fidus" "$work/dense.prm" || status=$?
"$top/contrib/benchmarks/summarize_run.sh" "$work/out"
if [ -n "${KEEP:-}" ]; then mkdir -p "$KEEP" && cp -r "$work/out/." "$KEEP/"; fi
exit $status
