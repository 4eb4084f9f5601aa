#!/usr/bin/env bash
# How large a time step the bulk 3D scene can take: the scene
# (prm/rheology_bulk_3d.prm: spheres of radius 0.05 at phi = 0.3 between
# sliding walls, released shared cells, the lubrication correction,
# inelastic contact) in a box of LX x 1 x LZ on a uniform mesh of the unit
# box's level LEVEL, from the same start to the strain END at each of the
# time steps DTS, one run after the other.
#
# Each run is compared with the one at the smallest step, at the times
# that every run reaches (multiples of the largest step):
# - the particles' positions: rms and largest distance to the reference's
#   (periodic images in x and z), in radii, at END, and the observed order
#   between consecutive steps;
# - the relative viscosity, N1, N2 and the particle pressure (eta_f gamma
#   units) averaged from 0 to END (trapezoid over each run's own rows:
#   what a user averages), and their difference to the reference's;
# - the cost: s per step and strain per hour of wall time.
# The shear rate is 1, so a step's strain is the step itself, and two
# touching spheres move 2 a gamma dt past each other in one step.
#
# Env: LEVEL (default 5: a/h = 1.6; 6: a/h = 3.2), LX, LZ (default 0.5,
# 0.5: 143 spheres), DTS (default "0.1 0.05 0.025 0.0125"), END (default
# 0.8), ENTRIES (prm lines appended to the scene, \n between them, e.g.
# "subsection Time stepping\n  set Scheme = trapezoidal\nend"), NP (ranks,
# default 2), FIDUS, WORK (keep the runs there; a run whose statistics
# reach END is not run again).
# Usage: contrib/benchmarks/bulk_time_step.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
. "$top/contrib/benchmarks/bulk_scene.sh"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
level="${LEVEL:-5}"; lx="${LX:-0.5}"; lz="${LZ:-0.5}"
dts="${DTS:-0.1 0.05 0.025 0.0125}"; end="${END:-0.8}"; np="${NP:-2}"
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

runs=()
for dt in $dts; do
  out="$work/dt_$dt"
  runs+=("$dt:$out")
  if [ -f "$out/statistics.csv" ] && /usr/bin/python3 - "$out" "$end" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/statistics.csv")))
sys.exit(0 if rows and float(rows[-1]["time"]) >= float(sys.argv[2]) - 1e-9 else 1)
PY
  then continue; fi
  {
    bulk_prm "$out" "$lx" 1 "$lz" "$level" "$end" |
      sed -e "s#^  set Time step .*#  set Time step = $dt#" \
          -e "s#^  set Particle output interval.*#  set Particle output interval = 1#"
    printf "%b\n" "${ENTRIES:-}"
  } > "$work/dt_$dt.prm"
  if ! mpirun -np "$np" --oversubscribe "$fidus" "$work/dt_$dt.prm" \
       > "$work/log_$dt" 2>&1; then
    echo "run at dt = $dt failed:"; tail -3 "$work/log_$dt"; exit 1
  fi
done

/usr/bin/python3 - "$lx" "$lz" "$end" "${runs[@]}" <<'PY'
import csv, math, sys
lx, lz, end = map(float, sys.argv[1:4])
runs = [(float(r.split(":", 1)[0]), r.split(":", 1)[1]) for r in sys.argv[4:]]
runs.sort()
keys = ["relative_viscosity", "normal_stress_difference_1",
        "normal_stress_difference_2", "particle_pressure"]


def load(out):
    stats = [r for r in csv.DictReader(open(out + "/statistics.csv"))
             if float(r["time"]) <= end + 1e-9]
    last = {}
    for r in csv.DictReader(open(out + "/particles.csv")):
        t = float(r["time"])
        if abs(t - end) < 1e-9:
            last[int(r["id"])] = (float(r["x"]), float(r["y"]), float(r["z"]),
                                  float(r["radius"]))
    return stats, last


def average(stats, key):
    t = [float(r["time"]) for r in stats]
    v = [float(r[key]) for r in stats]
    area = sum(0.5 * (v[i] + v[i + 1]) * (t[i + 1] - t[i])
               for i in range(len(t) - 1))
    return area / (t[-1] - t[0])


def distance(p, q):
    d = [p[0] - q[0], p[1] - q[1], p[2] - q[2]]
    d[0] -= lx * round(d[0] / lx)
    d[2] -= lz * round(d[2] / lz)
    return math.sqrt(sum(c * c for c in d)) / p[3]


data = [(dt, *load(out)) for dt, out in runs]
ref_dt, ref_stats, ref_last = data[0]
means = {dt: [average(s, k) for k in keys] for dt, s, _ in data}
print("| dt (strain per step) | 2 a dt / a | steps | rms distance to dt = %g at %g, radii | largest | observed order | eta_r | N1 | N2 | Pi | s per step | strain per hour |" % (ref_dt, end))
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
previous = None
for dt, stats, last in data:
    if dt == ref_dt:
        rms = big = float("nan")
    else:
        d = [distance(ref_last[i], last[i]) for i in ref_last]
        rms = math.sqrt(sum(x * x for x in d) / len(d)); big = max(d)
    order = ""
    if previous is not None and previous == previous and rms == rms and previous > 0:
        order = "%.2f" % math.log2(rms / previous)
    steps = len(stats) - 1
    wall = (float(stats[-1]["wall_seconds"]) - float(stats[0]["wall_seconds"])) / steps
    m = means[dt]
    cells = " | ".join("%.4f" % x for x in m)
    if dt != ref_dt:
        cells = " | ".join("%.4f (%+.4f)" % (x, x - r) for x, r in zip(m, means[ref_dt]))
    print("| %g | %.3f | %d | %s | %s | %s | %s | %.1f | %.0f |" % (
        dt, 2 * dt, steps, "–" if rms != rms else "%.2e" % rms,
        "–" if big != big else "%.2e" % big, order or "–", cells, wall,
        3600 * dt / wall))
    previous = rms
PY
