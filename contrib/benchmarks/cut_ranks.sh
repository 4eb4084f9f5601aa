#!/usr/bin/env bash
# The cut element's direct solver on 1, 2 (and more) MPI ranks: per scene
# and number of ranks, the unknowns, the seconds of each stage of a solve
# (mean over the solves: mesh, DoFs and pattern, assembly, solve,
# measure, all), the peak memory of the largest rank (fidus's own count),
# and the largest difference from the one rank's particle velocities (over
# the largest |U|, |omega| a).
# Scenes:
#   dense2d    prm/rheology_steady_shear_2d_cut.prm (138 discs, every gap
#              resolved, about 450 000 unknowns), two steps of 0.02;
#   pair3d     two spheres a = 0.15 held in linear shear at a gap of 0.5 a
#              along the flow's gradient, Maximum level 4, the direct solver
#              (about 38 000 unknowns), two steps of 0.2.
# Env: SCENES (default "dense2d pair3d"), RANKS (default "1 2"), BINARIES
# (default "build-release/fidus"; several: "label=path label=path", run one
# after the other per scene and number of ranks, each compared with the
# first's one rank), WORK (keep the runs there).
# Usage: BINARIES="before=/tmp/fidus_old after=build-release/fidus" \
#          contrib/benchmarks/cut_ranks.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
scenes="${SCENES:-dense2d pair3d}"
ranks_list="${RANKS:-1 2}"
binaries="${BINARIES:-build-release/fidus}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi

# scene_prm NAME OUT: print the scene's prm, its output in OUT.
scene_prm() {
  case "$1" in
    dense2d)
      sed -e "s|^set Output directory.*|set Output directory = $2|" \
          -e "s|set End time .*|set End time = 0.04|" \
          "$top/prm/rheology_steady_shear_2d_cut.prm"
      printf 'subsection Output\n  set Verbosity = verbose\nend\n' ;;
    pair3d) cat <<PRM
set Dimension        = 3
set Output directory = $2
subsection Domain
  set Lower left         = 0, 0, 0
  set Upper right        = 1, 1, 1
  set Boundary condition = linear shear
end
subsection Fluid
  set Model             = cut finite element
  set Cut linear solver = direct
end
subsection Particles
  set Radius    = 0.15
  set Positions = 0.5, 0.3125, 0.5; 0.5, 0.6875, 0.5
end
subsection Contact
  set Model = inelastic
end
subsection Time stepping
  set End time  = 0.4
  set Time step = 0.2
end
subsection Mesh refinement
  set Initial global refinement = 2
  set Minimum level             = 2
  set Maximum level             = 4
end
subsection Output
  set Verbosity = verbose
end
PRM
      ;;
    *) echo "unknown scene $1" >&2; exit 1 ;;
  esac
}

labels=""
for scene in $scenes; do
  for ranks in $ranks_list; do
    for entry in $binaries; do
      label="${entry%%=*}"; binary="${entry#*=}"
      [ "$label" = "$entry" ] && label="$(basename "$(dirname "$binary")")"
      case "$binary" in /*) ;; *) binary="$top/$binary" ;; esac
      labels="$labels $label"
      run="$scene-$label-$ranks"
      scene_prm "$scene" "$work/$run" > "$work/$run.prm"
      # Unbound: one rank takes every core as threads (OpenMPI binds a
      # rank to one core by default).
      (cd "$work" && mpirun --bind-to none -np "$ranks" "$binary" "$run.prm" \
         > "$run.log" 2>&1) ||
        echo "fidus failed (a build before the ranks were allowed?): $work/$run.log" >&2
    done
  done
done
labels="$(echo $labels | tr ' ' '\n' | awk '!seen[$0]++' | tr '\n' ' ')"

python3 - "$work" "$scenes" "$ranks_list" "$labels" <<'PY'
import csv, re, sys
work, scenes, ranks_list, labels = (sys.argv[1], sys.argv[2].split(),
                                    sys.argv[3].split(), sys.argv[4].split())
stage = re.compile(r'cut element: (\d+) unknowns.*?; s: mesh ([\d.e+-]+), DoFs '
                   r'and pattern ([\d.e+-]+), assembly ([\d.e+-]+), solve '
                   r'([\d.e+-]+), measure ([\d.e+-]+), all ([\d.e+-]+)')
print('| scene | binary | ranks | unknowns | mesh s | DoFs s | assembly s '
      '| solve s | measure s | all s | peak per rank | velocities against '
      'the first |')
print('|---|---|---|---|---|---|---|---|---|---|---|---|')
for scene in scenes:
    reference = None
    for ranks, label in [(r, l) for r in ranks_list for l in labels]:
        run = '%s-%s-%s' % (scene, label, ranks)
        log = open('%s/%s.log' % (work, run)).read()
        solves = [[float(x) for x in m.groups()] for m in stage.finditer(log)]
        if not solves:
            print('| %s | %s | %s | failed: %s |' % (scene, label, ranks, ' '.join(
                l for l in log.splitlines() if l.startswith('fidus:'))[:120]))
            continue
        mean = [sum(s[k] for s in solves) / len(solves) for k in range(7)]
        peak = re.search(r'peak memory per rank: ([\d.]+ [KMG]B)', log)
        rows = list(csv.DictReader(open('%s/%s/particles.csv' % (work, run))))
        keys = [k for k in ('ux', 'uy', 'uz', 'omega_x', 'omega_y', 'omega_z')
                if k in rows[0]]
        values = [[float(r[k]) * (float(r['radius']) if 'omega' in k else 1.)
                   for k in keys] for r in rows]
        if reference is None:
            reference, difference = values, '—'
        else:
            scale = max(abs(v) for row in reference for v in row)
            difference = '%.1e' % (max(abs(a - b) for ra, rb in
                                       zip(reference, values)
                                       for a, b in zip(ra, rb)) / scale)
        print('| %s | %s | %s | %d | %s | %s | %s |' % (
            scene, label, ranks, mean[0],
            ' | '.join('%.2f' % x for x in mean[1:]),
            peak.group(1) if peak else '?', difference))
PY
