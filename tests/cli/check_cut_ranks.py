#!/usr/bin/env python3
"""The checks of run_cut_ranks_test.sh on its runs' output folders
NAME-RANKS/ (see there): the cut element on 2 and 3 ranks against 1, to
round-off. Reads particles.csv, statistics.csv and the last step's
solution_*.vtu pieces (deal.II's zlib-compressed, base64-encoded arrays)
with the standard library only. Usage: check_cut_ranks.py WORK_FOLDER"""
import csv
import glob
import re
import sys

from deal_vtu import vtu_arrays

work = sys.argv[1]
failures = 0
# MUMPS pivots in another order on more ranks, and the shares are summed in
# another order: round-off times the system's condition (measured: 2D
# 1e-12, 3D 2e-13, both runs direct; 4e-9 when the one-rank 3D run was
# iterative at the tolerance 1e-10). A share counted twice or lost moves
# the answers by 1e-2 and more.
TOLERANCE = {2: 1e-9, 3: 1e-9}


def check(name, value, low, high):
    global failures
    ok = low <= value <= high
    failures += not ok
    print('%s: %.3e in [%g, %g]: %s' % (name, value, low, high,
                                          'OK' if ok else 'FAILED'))


def rows(run, name):
    return list(csv.DictReader(open('%s/%s/%s' % (work, run, name))))


def worst_difference(reference, other, groups):
    """Largest |a - b| over the rows, relative to the largest |a| of the
    column's group (a velocity's components together: one that is zero by
    symmetry holds round-off only)."""
    if len(reference) != len(other) or not reference:
        return float('inf')
    worst = 0.
    for group in groups:
        scale = max(abs(float(r[c])) for r in reference for c in group) or 1.
        for column in group:
            for a, b in zip(reference, other):
                worst = max(worst,
                            abs(float(a[column]) - float(b[column])) / scale)
    return worst


def last_fields(run):
    """The last step's pieces, named in its .pvtu, joined in rank order."""
    record = sorted(glob.glob('%s/%s/solution_*.pvtu' % (work, run)))[-1]
    pieces = re.findall(r'<Piece Source="([^"]*)"', open(record).read())
    joined = {}
    for piece in pieces:
        for name, values in vtu_arrays('%s/%s/%s' % (work, run, piece)).items():
            joined.setdefault(name, []).extend(values)
    return joined, len(pieces)


PARTICLES = {2: (('x', 'y'), ('ux', 'uy', 'omega_z'),
                 ('stresslet_xx', 'stresslet_xy', 'stresslet_yy')),
             3: (('x', 'y', 'z'),
                 ('ux', 'uy', 'uz', 'omega_x', 'omega_y', 'omega_z'),
                 ('stresslet_xx', 'stresslet_xy', 'stresslet_yy',
                  'stresslet_zz'))}
STRESS = (('relative_viscosity',), ('normal_stress_difference_1',),
          ('particle_pressure',))

for scene, ranks, dim in (('walls', (2, 3), 2), ('forced', (2, 3), 2),
                          ('spheres', (2,), 3)):
    one = scene + '-1'
    for n in ranks:
        other = '%s-%d' % (scene, n)
        check('%s: particles.csv on %d ranks against 1' % (scene, n),
              worst_difference(rows(one, 'particles.csv'),
                               rows(other, 'particles.csv'), PARTICLES[dim]),
              0., TOLERANCE[dim])
        stress = STRESS + ((('wall_shear_stress',),) if scene == 'walls'
                           else ())
        check('%s: statistics.csv stresses on %d ranks against 1' % (scene, n),
              worst_difference(rows(one, 'statistics.csv'),
                               rows(other, 'statistics.csv'), stress),
              0., TOLERANCE[dim])

# The iterative solver at the tolerance 1e-11: the ranks' split velocity
# block and multigrid change the preconditioner (a cut-cell block stops at
# a rank's rows), not the answer beyond the tolerance's effect (measured
# 5e-10 to 2e-9); a share summed twice or lost moves it by 1e-2 and more.
for n in (2, 3):
    for name, groups in (('particles.csv', PARTICLES[3]),
                         ('statistics.csv', STRESS)):
        check('spheres, iterative: %s on %d ranks against 1' % (name, n),
              worst_difference(rows('spheres_iterative-1', name),
                               rows('spheres_iterative-%d' % n, name),
                               groups),
              0., 1e-8)
for name, groups in (('particles.csv', PARTICLES[3]),
                     ('statistics.csv', STRESS + (('wall_shear_stress',),))):
    check('walls3d, iterative: %s on 2 ranks against 1' % name,
          worst_difference(rows('walls3d-1', name), rows('walls3d-2', name),
                           groups),
          0., 1e-8)
check('spheres: particles.csv iterative against direct, 1 rank',
      worst_difference(rows('spheres-1', 'particles.csv'),
                       rows('spheres_iterative-1', 'particles.csv'),
                       PARTICLES[3]),
      0., 1e-7)

# The fields: one piece per rank, together the one rank's fields.
reference, pieces = last_fields('walls-1')
check('walls: pieces of the one rank\'s .pvtu', pieces, 1, 1)
for n in (2, 3):
    joined, pieces = last_fields('walls-%d' % n)
    check('walls: pieces of the .pvtu on %d ranks' % n, pieces, n, n)
    for name in ('points', 'velocity', 'pressure', 'placement'):
        a, b = reference[name], joined.get(name, ())
        if len(a) != len(b):
            check('walls: %s values on %d ranks minus on 1' % (name, n),
                  abs(len(b) - len(a)), 0, 0)
            continue
        scale = max(abs(v) for v in a) or 1.
        check('walls: %s on %d ranks against 1' % (name, n),
              max(abs(u - v) for u, v in zip(a, b)) / scale, 0., 1e-6)

# The pushed disc (force (0.5, -1) at the centre of the shear) moves down
# and forward, at the speed of a disc of radius 0.06 under a unit force in
# 2D (about 0.1-0.3, the logarithm of the box over the radius); the shear
# and its neighbour give it less than 0.03.
first = [r for r in rows('forced-2', 'particles.csv') if r['step'] == '0']
pushed = [float(first[0][k]) for k in ('ux', 'uy')]
check('forced: the pushed disc\'s uy on 2 ranks (force -1)', pushed[1],
      -1., -0.05)
check('forced: its ux (force +0.5, shear 0 at its centre)', pushed[0],
      0.02, 1.)
sys.exit(1 if failures else 0)
