#!/usr/bin/env bash
# The cut finite element in any box, and its field output, against the
# invariances of Stokes flow (tests/cli/check_cut_box.py does the checks):
#  1. scaled and shifted: the box (-1, 2)-(1, 4), twice the unit box, with
#     the discs' positions and radii mapped alike, moves them the same way
#     (positions, velocities, relative viscosity and walls' stress), and
#     its fields are the unit box's, points mapped, velocities doubled,
#     pressures equal;
#  2. periodic doubling: the box (0, 0)-(2, 1) between sliding walls with
#     the discs and their copies shifted by 1 along x moves every copy as
#     the unit box moves the original (uniform meshes: see the checker);
#  3. the walls' velocity in the fields of the scaled box is the shear's,
#     +-g H/2;
#  4. threads: the model runs its one rank on the machine's cores; the
#     iterative solver on 2 threads moves the discs as on 1 (the sums are
#     taken in another order, so the runs agree to round-off, within 1e-10
#     of the largest value of each column of particles.csv, measured
#     0.5-1e-11; at the tolerance 1e-10, since at the default 1e-8 the
#     solver's stop amplified those differences to 0.6-1e-9);
#  5. the tolerance (Fluid/Cut linear tolerance): the same scene at 1e-6
#     takes fewer FGMRES iterations than at 1e-10, and at each tolerance
#     the translational velocities, the angular velocities and the
#     stresslets are within 1e3 times it of the direct solver's (each
#     relative to its largest value; measured: 15-35 times for U and the
#     stresslets, 180-400 for omega);
#  6. a box whose sides are not whole multiples of the shortest, 1.37 x 1
#     (its cells are not squares), and the same box scaled by 2 and moved
#     to (0, 2): the same motions, velocities doubled (to 1e-7, as 1.), and
#     its fields cover the box, with the shear's velocity on the walls.
# Usage: run_cut_box_test.sh path/to/fidus path/to/repo
. "$(dirname "${BASH_SOURCE[0]}")/driver_test_lib.sh" "$1" "$2"

scene() {  # scene NAME LOWER UPPER RADIUS POSITIONS [MINIMUM LEVEL]
  cat <<PRM
set Dimension = 2
set Output directory = $work/$1
subsection Domain
  set Lower left = $2
  set Upper right = $3
  set Boundary condition = sliding walls
end
subsection Fluid
  set Model = cut finite element
  set Cut minimum gap = 1e-3
end
subsection Particles
  set Radius = $4
  set Positions = $5
end
subsection Contact
  set Model = inelastic
end
subsection Time stepping
  set End time = 0.4
  set Time step = 0.2
  set Scheme = trapezoidal
end
subsection Mesh refinement
  set Initial global refinement = ${6:-3}
  set Minimum level = ${6:-3}
  set Maximum level = ${6:-4}
end
subsection Output
  set Field output interval = 1
  set Verbosity = quiet
end
PRM
}

scene unit "0, 0" "1, 1" 0.05 "0.98, 0.8; 0.52, 0.5; 0.3, 0.25" > unit.prm
scene scaled "-1, 2" "1, 4" 0.1 "0.96, 3.6; 0.04, 3; -0.4, 2.5" > scaled.prm
scene uniform "0, 0" "1, 1" 0.05 "0.7, 0.75; 0.45, 0.5; 0.25, 0.3" 5 \
  > uniform.prm
scene doubled "0, 0" "2, 1" 0.05 \
  "0.7, 0.75; 0.45, 0.5; 0.25, 0.3; 1.7, 0.75; 1.45, 0.5; 1.25, 0.3" 5 \
  > doubled.prm
for name in unit scaled uniform doubled; do
  check "fidus runs $name.prm" "$fidus" $name.prm
done
check "the invariances (check_cut_box.py)" \
  "$python" "$repo/tests/cli/check_cut_box.py" "$work"

# 4. The uniform scene at level 6 with the iterative solver (about 40 000
# unknowns, enough for deal.II to split its products among threads).
for threads in 1 2; do
  scene "threads-$threads" "0, 0" "1, 1" 0.05 "0.7, 0.75; 0.45, 0.5; 0.25, 0.3" 6 |
    sed 's/set Cut minimum gap = 1e-3/&\n  set Cut linear solver = iterative\n  set Cut linear tolerance = 1e-10/;
         s/set Field output interval = 1/set Field output interval = 0/' \
    > "threads-$threads.prm"
  check "fidus runs on $threads thread(s)" \
    env DEAL_II_NUM_THREADS=$threads "$fidus" "threads-$threads.prm"
done
check "2 threads agree with 1 to round-off" "$python" - "$work" <<'PY'
import csv, sys
rows = [list(csv.DictReader(open(sys.argv[1] + "/threads-%d/particles.csv" % t)))
        for t in (1, 2)]
assert len(rows[0]) == len(rows[1]) > 3, "the runs differ in length"
worst = 0.
for column in ("x", "y", "ux", "uy", "omega_z", "stresslet_xy"):
    scale = max(abs(float(r[column])) for r in rows[0])
    for a, b in zip(*rows):
        worst = max(worst, abs(float(a[column]) - float(b[column])) / scale)
print("largest difference between 1 and 2 threads: %.1e" % worst)
sys.exit(0 if worst < 1e-10 else 1)
PY

# 5. The tolerance: the 2-thread scene at 1e-10 and 1e-6, and with the
# direct solver.
for t in 10 6; do
  sed "/set Cut linear tolerance/d;
       s/set Cut linear solver = iterative/&\n  set Cut linear tolerance = 1e-$t/;
       s#threads-2#tolerance-$t#" threads-2.prm > tolerance-$t.prm
done
sed '/set Cut linear tolerance/d;
     s/set Cut linear solver = iterative/set Cut linear solver = direct/;
     s#threads-2#direct#' threads-2.prm > direct.prm
for name in tolerance-10 tolerance-6 direct; do
  check "fidus runs $name.prm" "$fidus" $name.prm
done
check "the tolerance: fewer iterations, answers within 1e3 times it" \
  "$python" - "$work" <<'PY'
import csv, sys
def rows(name):
    return list(csv.DictReader(open(sys.argv[1] + "/%s/particles.csv" % name)))
def iterations(name):
    return sum(int(r["linear_iterations"]) for r in
               csv.DictReader(open(sys.argv[1] + "/%s/statistics.csv" % name)))
direct, ok = rows("direct"), True
for name, tolerance in (("tolerance-10", 1e-10), ("tolerance-6", 1e-6)):
    worst = 0.
    for group in (("ux", "uy"), ("omega_z",),
                  ("stresslet_xx", "stresslet_xy", "stresslet_yy")):
        scale = max(abs(float(r[c])) for r in direct for c in group)
        worst = max(worst, max(abs(float(a[c]) - float(b[c]))
                               for a, b in zip(rows(name), direct)
                               for c in group) / scale)
    print("tolerance %g: %d FGMRES, largest difference from the direct "
          "solver %.1e (bound %.0e)" % (tolerance, iterations(name), worst,
                                        1e3 * tolerance))
    ok = ok and worst < 1e3 * tolerance
ok = ok and iterations("tolerance-6") < iterations("tolerance-10")
sys.exit(0 if ok else 1)
PY

# 6. A box of sides 1.37 x 1, unscaled and scaled by 2 to (0, 2)-(2.74, 4).
scene uneven "0, 0" "1.37, 1" 0.05 "0.98, 0.8; 0.52, 0.5; 0.3, 0.25; 1.2, 0.6" \
  > uneven.prm
scene uneven-scaled "0, 2" "2.74, 4" 0.1 \
  "1.96, 3.6; 1.04, 3; 0.6, 2.5; 2.4, 3.2" > uneven-scaled.prm
for name in uneven uneven-scaled; do
  check "fidus runs $name.prm" "$fidus" $name.prm
done
check "the box 1.37 x 1: scaled motions, fields on the box" \
  "$python" - "$work" "$repo/tests/cli" <<'PY'
import csv, glob, sys
sys.path.insert(0, sys.argv[2])
from deal_vtu import vtu_arrays
def last(name):
    rows = list(csv.DictReader(open(sys.argv[1] + "/%s/particles.csv" % name)))
    step = max(int(r["step"]) for r in rows)
    return [[float(r[k]) for k in ("x", "y", "ux", "uy", "omega_z")]
            for r in rows if int(r["step"]) == step]
one, two, a = last("uneven"), last("uneven-scaled"), 0.05
position = max(max(abs(q[0] / 2. - p[0]), abs((q[1] - 2.) / 2. - p[1])) / a
               for p, q in zip(one, two))
velocity = max(max(abs(q[2] / 2. - p[2]), abs(q[3] / 2. - p[3])) / a
               for p, q in zip(one, two))
omega = max(abs(q[4] - p[4]) for p, q in zip(one, two))
moved = max(abs(p[0] - x0) for p, x0 in zip(one, (0.98, 0.52, 0.3, 1.2)))
# The points are written in single precision.
files = sorted(glob.glob(sys.argv[1] + "/uneven-scaled/solution_*.vtu"))
f = vtu_arrays(files[-1])
xs = f["points"][0::3]
wall = max(abs(f["velocity"][3 * k] - (f["points"][3 * k + 1] - 3.))
           for k in range(len(xs))
           if min(abs(f["points"][3 * k + 1] - 2.),
                  abs(f["points"][3 * k + 1] - 4.)) < 1e-9)
print("positions %.1e a, velocities %.1e g a, omega %.1e g apart; the discs "
      "moved up to %.2e; fields over x in [%g, %g], walls %.1e from the "
      "shear" % (position, velocity, omega, moved, min(xs), max(xs), wall))
ok = (position < 1e-8 and velocity < 1e-7 and omega < 1e-7 and moved > 1e-3
      and abs(min(xs)) < 1e-6 and abs(max(xs) - 2.74) < 1e-6 and wall < 1e-6)
sys.exit(0 if ok else 1)
PY

echo "$passes passed, $failures failed"
[ $failures -eq 0 ]
