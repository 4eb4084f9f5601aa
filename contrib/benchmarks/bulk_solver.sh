#!/usr/bin/env bash
# What the fluid solve of a dense 3D step costs against the solver's
# settings: the bulk scene (prm/rheology_bulk_3d.prm: spheres of radius
# 0.05 at phi = 0.3 between sliding walls, released shared cells, the
# lubrication correction, inexact Uzawa) in a box of LX x 1 x LZ, on a
# uniform mesh of the unit box's level LEVEL, STEPS steps of 0.02 after
# step 0, once per variant.
#
# A variant is "name|entries": the entries (prm lines, \n between them)
# are appended to the scene, so they override its settings. The default
# variants: the plain Uzawa loop ('Uzawa acceleration depth = 0') at the
# penalty factors 1000 (fidus's default), 300 and 100; the accelerated
# loop (depth 3, the scene's) at 100 (the scene's) and 30; and 1000 with
# the velocity block solved inside every FGMRES step ('Maximum cheap
# iterations = 0').
#
# Printed per variant, per step after step 0 (the mean): Uzawa
# iterations, FGMRES iterations, wall seconds; the peak memory of the
# largest rank; the last step's relative viscosity and rigidity residual
# (the stress must not depend on the solver's settings beyond the rigidity
# tolerance's reach), and the warnings of the run (a stalled Uzawa loop).
#
# Env: LEVEL (default 5: a/h = 1.6; 6: a/h = 3.2), LX, LZ (default 0.5,
# 0.5: 143 spheres), STEPS (default 2), NP (ranks, default 2), VARIANTS
# (";"-separated), FIDUS, WORK (keep the runs there).
# Usage: contrib/benchmarks/bulk_solver.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
. "$top/contrib/benchmarks/bulk_scene.sh"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
level="${LEVEL:-5}"; lx="${LX:-0.5}"; lz="${LZ:-0.5}"
steps="${STEPS:-2}"; np="${NP:-2}"
variants="${VARIANTS:-r 1000|  set Penalty factor = 1000\n  set Uzawa acceleration depth = 0;r 300|  set Penalty factor = 300\n  set Uzawa acceleration depth = 0;r 100|  set Penalty factor = 100\n  set Uzawa acceleration depth = 0;r 100, Anderson 3|  set Penalty factor = 100;r 30, Anderson 3|  set Penalty factor = 30;r 1000, A solved inside|  set Penalty factor = 1000\n  set Uzawa acceleration depth = 0\n  subsection Linear solver\n    set Maximum cheap iterations = 0\n  end}"
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

echo "| variant | spheres | unknowns | Uzawa per step | FGMRES per step | s per step | peak MB per rank | eta_r (last step) | rigidity residual | warnings |"
echo "|---|---|---|---|---|---|---|---|---|---|"
IFS=';' read -ra list <<< "$variants"
for variant in "${list[@]}"; do
  name="${variant%%|*}"; entries="${variant#*|}"
  tag="$(echo "$name" | tr -c 'A-Za-z0-9' '_')"
  out="$work/run_$tag"
  {
    bulk_prm "$out" "$lx" 1 "$lz" "$level" \
      "$(/usr/bin/python3 -c "print($steps * 0.02)")"
    printf "subsection Fluid\n%b\nend\n" "$entries"
  } > "$work/run_$tag.prm"
  if ! mpirun -np "$np" --oversubscribe "$fidus" "$work/run_$tag.prm" > "$work/log_$tag" 2>&1; then
    echo "| $name | run failed |"; tail -3 "$work/log_$tag"; continue
  fi
  /usr/bin/python3 - "$out" "$work/log_$tag" "$name" <<'PY'
import csv, re, sys
out, log, name = sys.argv[1:4]
rows = list(csv.DictReader(open(out + "/statistics.csv")))
later = rows[1:] if len(rows) > 1 else rows
n = len(later)
spheres = len({r["id"] for r in csv.DictReader(open(out + "/particles.csv"))
               if r["step"] == "0"})
text = open(log).read()
peak = re.search(r"peak memory per rank: ([0-9.]+) (MB|GB)", text)
mb = float(peak.group(1)) * (1024 if peak.group(2) == "GB" else 1) if peak else float("nan")
warnings = len(re.findall(r"^fidus: warning", text, re.M))
mean = lambda key: sum(float(r[key]) for r in later) / n
last = later[-1]
print("| %s | %d | %d | %.1f | %.0f | %.1f | %.0f | %.4f | %.2e | %d |" % (
    name, spheres, int(last["dofs"]), mean("uzawa_iterations"),
    mean("linear_iterations"),
    (float(last["wall_seconds"]) - float(rows[0]["wall_seconds"])) / n, mb,
    float(last["relative_viscosity"]), float(last["rigidity_residual"]),
    warnings))
PY
done
