#!/usr/bin/env bash
# How the cost of a dense 3D step grows with the number of spheres and
# shrinks with the number of ranks: the bulk scene (prm/rheology_bulk_3d.prm:
# spheres of radius 0.05 at phi = 0.3 between sliding walls, periodic in x
# and z, inelastic contact, lubrication correction) in boxes of 1 x 1 x 1,
# 1 x 1 x 0.5 and 0.5 x 1 x 0.5 at the same cell size (the generator fills
# each at the same fraction, so the number of spheres follows the volume),
# each on every number of ranks of NPS, for STEPS steps of 0.02.
#
# Printed per run: the spheres, ranks, cells, unknowns, and per step (the
# mean over the steps after step 0; statistics.csv's clock is cumulative)
# the wall seconds and the FGMRES iterations, per call each stage of fidus's
# timing table (fluid; the particle stages:
# rigid motion, lubrication, contact, stress; mesh), and the peak memory of
# the largest rank. The particle stages should grow like the number of
# spheres (the contact projection and the lubrication correction are
# replicated on every rank), the fluid like the unknowns per rank.
#
# Env: LEVEL (the unit box's maximum level, default 4: a/h = 0.8; 5:
# a/h = 1.6; 6: a/h = 3.2), STEPS (default 3), BOXES (default
# "0.5:0.5 1:0.5 1:1", x and z lengths), NPS (default "1 2 3"; more ranks
# than cores are oversubscribed and their times are not a speed-up), FIDUS,
# WORK (keep the runs there).
# Usage: contrib/benchmarks/bulk_scaling.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
. "$top/contrib/benchmarks/bulk_scene.sh"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
level="${LEVEL:-4}"; steps="${STEPS:-3}"
boxes="${BOXES:-0.5:0.5 1:0.5 1:1}"; nps="${NPS:-1 2 3}"
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

echo "| box | spheres | ranks | cells | unknowns | s per step | FGMRES per step | fluid s | rigid motion s | lubrication s | contact s | stress s | mesh s | peak MB per rank |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for box in $boxes; do
  lx=${box%%:*}; lz=${box#*:}
  for np in $nps; do
    out="$work/run_${lx}_${lz}_$np"
    bulk_prm "$out" "$lx" 1 "$lz" "$level" \
      "$(/usr/bin/python3 -c "print($steps * 0.02)")" > "$work/run.prm"
    launch=(mpirun -np "$np" --oversubscribe)
    if ! "${launch[@]}" "$fidus" "$work/run.prm" > "$work/log" 2>&1; then
      echo "| $lx x 1 x $lz | run on $np ranks failed |"; tail -3 "$work/log"; continue
    fi
    /usr/bin/python3 - "$out" "$work/log" "$lx" "$lz" "$np" <<'PY'
import csv, re, sys
out, log, lx, lz, np = sys.argv[1:6]
rows = list(csv.DictReader(open(out + "/statistics.csv")))
later = rows[1:] if len(rows) > 1 else rows
n = len(later)
spheres = len({r["id"] for r in csv.DictReader(open(out + "/particles.csv"))
               if r["step"] == "0"})
text = open(log).read()
def stage(name):
    m = re.search(r"\|\s*" + re.escape(name) + r"\s*\|\s*(\d+)\s*\|\s*([0-9.e+-]+)s", text)
    return float(m.group(2)) / max(1, int(m.group(1))) if m else float("nan")
peak = re.search(r"peak memory per rank: ([0-9.]+) (MB|GB)", text)
mb = float(peak.group(1)) * (1024 if peak.group(2) == "GB" else 1) if peak else float("nan")
mean = lambda key: sum(float(r[key]) for r in later) / n
print("| %s x 1 x %s | %d | %s | %d | %d | %.2f | %.0f | %.2f | %.3f | %.3f | %.4f | %.3f | %.3f | %.0f |" % (
    lx, lz, spheres, np, int(later[-1]["cells"]), int(later[-1]["dofs"]),
    (float(later[-1]["wall_seconds"]) - float(rows[0]["wall_seconds"])) / n,
    mean("linear_iterations"), stage("fluid"), stage("rigid motion"),
    stage("lubrication"), stage("contact"), stage("stress"), stage("mesh"), mb))
PY
  done
done
