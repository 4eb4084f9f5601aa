#!/usr/bin/env bash
# Force-driven squeeze of spheres against exact Stokes solutions (the
# dense-suspension issue's squeeze test): 'Particles/External force' pushes
#   - pair: two equal spheres towards each other along x (forces +F and -F),
#     reference Brenner (1961): each approaches at F / (6 pi eta a lambda),
#   - wall: one sphere towards the wall y = 0 (force -F e_y), reference
#     Brenner (1961), the sphere and the plane,
# in the closed unit box at rest (linear shear with Shear rate = 0), at gaps
# h from GAPS (relative to the radius a), for each maximum level of LEVELS.
# Printed, divided by the exact speed:
#   - the mesh alone: the fluid's rigid velocity (particles.csv at step 0),
#   - mesh + 'Fluid/Lubrication correction': the displacement over one step
#     of DT (which carries the corrected velocity).
# The box is not unbounded: its walls slow the spheres too, most where the
# exact resistance is smallest (the widest gaps). The last column gives the
# exact lambda, so that the size of that effect can be judged.
# Env: A (radius, default 0.1), LEVELS (default "4 5": the diameter spans
# 3.2 and 6.4 cells), GAPS (default "0.5 0.2 0.1 0.05 0.02 0.01"), CASES
# (default "pair wall"), DT (default 1e-4), RETRACTION (Solid retraction,
# default 0), RANGE (Lubrication range, default auto), RIGID_TOL (Rigid velocity
# tolerance, default 1e-5), ROUGHNESS (Contact/Roughness, default
# 5e-3, fidus's; gaps below it count as it), NP (MPI ranks per run,
# default 1), WORK (keep the runs there), FIDUS.
# Usage: contrib/benchmarks/squeeze_force.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
a="${A:-0.1}"; levels="${LEVELS:-4 5}"; dt="${DT:-1e-4}"
gaps="${GAPS:-0.5 0.2 0.1 0.05 0.02 0.01}"; cases="${CASES:-pair wall}"
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi
launch=()
[ "${NP:-1}" -gt 1 ] && launch=(mpirun -np "$NP")

# run <name> <case> <gap/a> <level>
run() {
  local name="$1" case="$2" gap="$3" level="$4" positions forces
  if [ "$case" = pair ]; then
    positions=$(/usr/bin/python3 -c "
a, g = $a, $gap
s = a + 0.5 * g * a
print('%.15f, 0.5, 0.5; %.15f, 0.5, 0.5' % (0.5 - s, 0.5 + s))")
    forces="1, 0, 0; -1, 0, 0"
  else
    positions=$(/usr/bin/python3 -c "
a, g = $a, $gap
print('0.5, %.15f, 0.5' % (a + g * a))")
    forces="0, -1, 0"
  fi
  cat > "$work/$name.prm" <<PRM
set Dimension = 3
set Output directory = $work/$name
subsection Domain
  set Lower left = 0, 0, 0
  set Upper right = 1, 1, 1
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
  set Lubrication correction = true
  set Lubrication range = ${RANGE:-auto}
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

# speeds <name> <case> <gap/a>: exact lambda, mesh / exact, corrected / exact
speeds() {
  /usr/bin/python3 - "$work/$1/particles.csv" "$2" "$3" "$a" "$dt" <<'PY'
import csv, math, sys
path, case, gap, a, dt = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])

def brenner(alpha, pair):
    # Brenner (1961): the sphere and the plane; two equal spheres approaching
    # with equal and opposite velocities (cosh alpha = centre distance / 2a).
    s = 0.
    for n in range(1, 100000):
        k = 2 * n + 1
        if k * alpha > 600:
            break
        if pair:
            b = (4 * math.cosh((n + .5) * alpha) ** 2 + k * k * math.sinh(alpha) ** 2) / \
                (2 * math.sinh(k * alpha) - k * math.sinh(2 * alpha)) - 1
        else:
            b = (2 * math.sinh(k * alpha) + k * math.sinh(2 * alpha)) / \
                (4 * math.sinh((n + .5) * alpha) ** 2 - k * k * math.sinh(alpha) ** 2) - 1
        t = n * (n + 1) / ((2 * n - 1) * (2 * n + 3)) * b
        s += t
        if n > 10 and abs(t) < 1e-15 * abs(s):
            break
    return 4. / 3. * math.sinh(alpha) * s

pair = case == "pair"
lam = brenner(math.acosh(1 + gap / (2 if pair else 1)), pair)
exact = 1. / (6 * math.pi * a * lam)            # F = 1, eta = 1
rows = list(csv.DictReader(open(path)))
def at(step):
    r = sorted((x for x in rows if int(x["step"]) == step), key=lambda x: int(x["id"]))
    return [(float(x["x"]), float(x["y"]), float(x["ux"]), float(x["uy"])) for x in r]
p0, p1 = at(0), at(1)
if pair:   # approach speed of each sphere: half the closing speed
    mesh = 0.5 * (p0[0][2] - p0[1][2])
    step = 0.5 * ((p0[1][0] - p0[0][0]) - (p1[1][0] - p1[0][0])) / dt
else:      # speed towards the wall
    mesh = -p0[0][3]
    step = (p0[0][1] - p1[0][1]) / dt
print("%.6g %.4f %.4f" % (lam, mesh / exact, step / exact))
PY
}

echo "Spheres a = $a pushed by a force, speed divided by the exact (Brenner 1961)."
echo
echo "| case | h/a | exact lambda | level | mesh alone / exact | with correction / exact | wall s |"
echo "|---|---|---|---|---|---|---|"
for c in $cases; do
  for g in $gaps; do
    for L in $levels; do
      name="${c}_${g}_$L"
      run "$name" "$c" "$g" "$L" || continue
      read -r lam mesh corr < <(speeds "$name" "$c" "$g")
      printf "| %s | %s | %.4g | %s | %s | %s | %.1f |\n" "$c" "$g" "$lam" "$L" \
        "$mesh" "$corr" "$(cat "$work/$name.wall")"
    done
  done
done
