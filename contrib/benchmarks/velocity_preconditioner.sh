#!/usr/bin/env bash
# Velocity-block preconditioners of the fluid predictor, in one run on one
# machine: the ML AMG against the geometric multigrid (GMG), each with and
# without the particles' rigid-body correction (Fluid/Linear solver/
# Rigid-body correction), and GMG with the velocity block assembled instead
# of applied matrix-free (Matrix-free velocity block = false). Scenes:
#   inclusion3d L [r]  one sphere (a = 0.2) off-centre, exact rigid inclusion,
#                  maximum level L, penalty factor r (default 1e3)
#   inclusion2d L [r]  one disc (a = 0.15) off-centre, exact rigid inclusion
#   dense2d        prm/dense_suspension_2d.prm, first step (3 Uzawa solves)
#   paper2d        prm/two_particles_2d.prm, gluey, the whole run
#   spheres3d      24 spheres at volume fraction 0.25 between sliding walls,
#                  level 4, one step (as contrib/benchmarks/suspension_3d.sh)
#   pair3d L       prm/two_particles_3d.prm at maximum level L, first step
# Prints one row per scene and preconditioner: cells, DoFs (velocity and
# pressure, of the last solve), Uzawa iterations, FGMRES
# iterations (total and per solve), assembly, set-up and solve seconds of
# the fluid predictor summed over the run, the run's wall seconds and its
# peak memory (resident set, MB).
# Usage: contrib/benchmarks/velocity_preconditioner.sh [scene ...]
#        (default: inclusion2d 8, inclusion3d 3, inclusion3d 4, inclusion3d 5,
#         pair3d 6, dense2d, paper2d)
#        TIMEOUT=s stops a run after s seconds and prints a row saying so.
#        CHEAP=n sets Maximum cheap iterations (0: inner solves only).
#        NP=n runs on n MPI ranks (peak memory: the largest rank's).
#        VARIANTS="GMG true true;AMG true true" limits the runs to those
#        (preconditioner, rigid-body correction, matrix-free[, averaging
#        [, smoother blocks]]) variants; averaging is Multigrid viscosity
#        averaging (default: the AVERAGING environment variable, else
#        fidus's default), smoother blocks is Multigrid smoother blocks,
#        "none" or "cut" (cut cells; default: fidus's default), shown as
#        "+none" or "+cut" after the averaging, e.g.
#        VARIANTS="AMG true true;GMG true true none;GMG true true galerkin cut".
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

scene_prm() {
  local scene=$1 level=${2:-} penalty=${3:-1e3}
  case $scene in
    inclusion2d|inclusion3d)
      local dim=${scene:9:1}
      if [ "$dim" = 2 ]; then ll="0, 0"; ur="1, 1"; r=0.15; x="0.53, 0.48"
      else ll="0, 0, 0"; ur="1, 1, 1"; r=0.2; x="0.53, 0.48, 0.51"; fi
      cat <<EOF
set Dimension = $dim
subsection Domain
  set Lower left = $ll
  set Upper right = $ur
  set Boundary condition = exact rigid inclusion
end
subsection Fluid
  set Penalty factor = $penalty
  set Rigidity tolerance = 1e-3
  set Rigidity measure = box
end
subsection Particles
  set Radius = $r
  set Positions = $x
end
subsection Time stepping
  set End time = 0
end
subsection Mesh refinement
  set Initial global refinement = 2
  set Minimum level = 2
  set Maximum level = $level
end
EOF
      ;;
    dense2d)
      cat <<EOF
include $top/prm/dense_suspension_2d.prm
subsection Time stepping
  set End time = 0
end
subsection Fluid
  set Maximum Uzawa iterations = 3
end
subsection Output
  set Checkpoint wall interval = 0
end
EOF
      ;;
    paper2d)
      echo "include $top/prm/two_particles_2d.prm"
      ;;
    pair3d)
      cat <<EOF
include $top/prm/two_particles_3d.prm
subsection Time stepping
  set End time = 0
end
subsection Mesh refinement
  set Maximum level = $level
end
subsection Output
  set Checkpoint wall interval = 0
end
EOF
      ;;
    spheres3d)
      # Same placement as suspension_3d.sh (random sequential addition).
      /usr/bin/python3 - "$work/positions.txt" <<'PY'
import math, random, sys
n, phi = 24, 0.25
a = (3 * phi / (4 * math.pi * n)) ** (1 / 3)
random.seed(1)
x = []
def d2(p, q):
    dx = p[0] - q[0] - round(p[0] - q[0])
    dz = p[2] - q[2] - round(p[2] - q[2])
    return dx * dx + (p[1] - q[1]) ** 2 + dz * dz
while len(x) < n:
    p = (random.random(), random.random(), random.random())
    if a + 1e-3 < p[1] < 1 - a - 1e-3 and all(d2(p, q) >= (2 * a + 1e-3) ** 2 for q in x):
        x.append(p)
open(sys.argv[1], "w").write("".join("%.15f %.15f %.15f\n" % p for p in x))
PY
      a=$(/usr/bin/python3 -c "import math; print((3*0.25/(4*math.pi*24))**(1/3))")
      cat <<EOF
set Dimension = 3
subsection Domain
  set Lower left = 0, 0, 0
  set Upper right = 1, 1, 1
  set Boundary condition = sliding walls
end
subsection Fluid
  set Rigidity tolerance = 1e-2
  set Rigidity measure = box
  set Maximum Uzawa iterations = 5
end
subsection Particles
  set Radius = $a
  set Positions file = $work/positions.txt
end
subsection Contact
  set Model = gluey
end
subsection Time stepping
  set End time = 0
end
subsection Mesh refinement
  set Initial global refinement = 2
  set Minimum level = 2
  set Maximum level = 4
end
EOF
      ;;
    *) echo "unknown scene '$scene'" >&2; exit 1 ;;
  esac
}

run() {
  local label=$1 pc=$2 rb=$3 mf=$4 avg=$5 blocks=$6; shift 6
  local prm="$work/run.prm"
  scene_prm "$@" > "$prm"
  cat >> "$prm" <<EOF
set Output directory = $work/out
subsection Fluid
  subsection Linear solver
    set Preconditioner = $pc
    set Rigid-body correction = $rb
    set Matrix-free velocity block = $mf
$( [ "$avg" = default ] || echo "    set Multigrid viscosity averaging = $avg")
$( [ "$blocks" = default ] || echo "    set Multigrid smoother blocks = ${blocks/cut/cut cells}")
$( [ -z "${CHEAP:-}" ] || echo "    set Maximum cheap iterations = $CHEAP")
  end
end
subsection Output
  set Verbosity = verbose
  set Field output interval = 0
  set Particle output interval = 0
end
EOF
  local start=$(date +%s.%N)
  local log
  local status=0
  # timeout inside time, with SIGKILL: fidus answers SIGTERM by finishing
  # its step, and a signal to time alone would leave fidus running.
  local launcher=()
  [ -z "${NP:-}" ] || launcher=(mpirun -np "$NP")
  log=$(OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
    /usr/bin/time -f "peak-kB %M" timeout -s KILL "${TIMEOUT:-0}" \
    "${launcher[@]}" "$fidus" "$prm" 2>&1) || status=$?
  [ "$blocks" = default ] || avg="$avg+$blocks"
  [ "$pc" = GMG ] || { mf=-; avg=-; }
  if [ $status = 124 ] || [ $status = 137 ]; then
    printf "| %-18s | %s | %-5s | %-5s | %-8s | stopped after %s s |\n" "$label" "$pc" "$rb" "$mf" "$avg" "$TIMEOUT"
    return
  elif [ $status != 0 ]; then
    echo "$label: run failed"; echo "$log" | tail -5; return
  fi
  local wall=$(echo "$(date +%s.%N) - $start" | bc)
  echo "$log" | /usr/bin/python3 -c '
import re, sys
label, pc, rb, mf, avg, wall = sys.argv[1:7]
text = sys.stdin.read()
cells = re.findall(r"cells (\d+)", text)
dofs = re.findall(r"DoFs (\d+)", text)
# Per solve (verbose lines): the last "Uzawa k: ... FGMRES total N" before
# each "Stokes: assembly" line gives its Uzawa iterations and FGMRES total.
uz, fg, last = [], [], None
for line in text.splitlines():
    m = re.search(r"Uzawa (\d+): .*FGMRES total (\d+)", line)
    if m:
        last = (int(m.group(1)) + 1, int(m.group(2)))
    elif "Stokes: assembly" in line and last:
        uz.append(last[0]); fg.append(last[1]); last = None
assembly = sum(float(s) for s in re.findall(r"Stokes: assembly ([0-9.e-]+) s", text))
setup = sum(float(s) for s in re.findall(r"preconditioner set-up ([0-9.e-]+) s", text))
peak = re.findall(r"peak-kB (\d+)", text)
solve = sum(float(s) for s in re.findall(r"Uzawa/FGMRES ([0-9.e-]+) s", text))
print("| %-18s | %s | %-5s | %-5s | %-8s | %7s | %8s | %5d | %7d | %6.1f | %6.2f | %7.2f | %8.2f | %7.1f | %6.0f |" % (
    label, pc, rb, mf, avg, cells[-1] if cells else "?",
    dofs[-1] if dofs else "?", sum(uz), sum(fg),
    sum(fg) / max(sum(uz), 1), assembly, setup, solve, float(wall),
    int(peak[-1]) / 1024 if peak else float("nan")))
' "$label" "$pc" "$rb" "$mf" "$avg" "$wall"
}

scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=("inclusion2d 8" "inclusion3d 3" "inclusion3d 4" "inclusion3d 5" "pair3d 6" dense2d paper2d)
IFS=';' read -r -a variants <<< "${VARIANTS:-AMG false true;AMG true true;GMG false true;GMG true false;GMG true true}"
echo "| scene              | PC  | rigid | m-free | averaging | cells   | DoFs     | Uzawa | FGMRES  | /solve | assembly s | set-up s | solve s  | wall s  | peak MB |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
  for variant in "${variants[@]}"; do
    read -r pc rb mf avg blocks <<< "$variant"
    run "$s" "$pc" "$rb" "$mf" "${avg:-${AVERAGING:-default}}" "${blocks:-default}" $s
  done
done
