#!/usr/bin/env bash
# Where a fluid solve's time goes, per step: assembly of the system (B, the
# pressure mass, the right-hand side), set-up of the preconditioner (the
# multigrid levels' viscosity tables, their diagonals, the smoothers'
# cut-cell blocks, the coarse matrix and AMG) and the Uzawa/FGMRES loop.
# Shipped scenes, cut short, with Verbosity = verbose; means over the steps
# after the first (the first builds the mesh and every diagonal from
# scratch), and over the steps that kept the mesh of the step before
# ("kept", column remeshed = 0 of statistics.csv: there the diagonals are
# updated only where the particles moved).
# Env: STEPS (default 6), NP (MPI ranks, default 2), SCENES (default
# "two_particles_2d dense_suspension_2d two_particles_3d"),
# BINARIES ("label=path ...", default "current=build-release/fidus": give
# two builds to compare them in one run), WORK (keep the runs there).
# Usage: contrib/benchmarks/setup_cost.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
steps="${STEPS:-6}"; np="${NP:-2}"
scenes="${SCENES:-two_particles_2d dense_suspension_2d two_particles_3d}"
if [ -z "${BINARIES:-}" ]; then
  "$top/contrib/build.sh" fidus >/dev/null
  binaries="current=$top/build-release/fidus"
else binaries="$BINARIES"; fi
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi
launch=()
[ "$np" -gt 1 ] && launch=(mpirun -np "$np")

printf '%s\n' "| scene | build | steps (kept mesh) | assembly s | set-up s | of which diagonals s | blocks s | Uzawa/FGMRES s | FGMRES / step | fluid s / step |"
printf '%s\n' "|---|---|---|---|---|---|---|---|---|---|"
for scene in $scenes; do
  dt=$(grep -m1 '^ *set Time step' "$top/prm/$scene.prm" | sed 's/.*= *//')
  for entry in $binaries; do
    label="${entry%%=*}"; fidus="${entry#*=}"
    run="$work/${scene}_$label"
    {
      echo "include $top/prm/$scene.prm"
      echo "set Output directory = $run"
      echo "subsection Time stepping"
      echo "  set End time = $(awk -v d="$dt" -v n="$steps" 'BEGIN { print d * (n - 0.5) }')"
      echo "end"
      echo "subsection Output"
      echo "  set Particle output interval = 0"
      echo "  set Field output interval = 0"
      echo "  set Checkpoint wall interval = 0"
      echo "  set Verbosity = verbose"
      echo "end"
    } > "$run.prm"
    if ! "${launch[@]}" "$fidus" "$run.prm" > "$run.log" 2>&1; then
      echo "| $scene | $label | failed: $(tail -1 "$run.log") |"
      continue
    fi
    # The k-th Stokes line of the log is step k's solve; a multigrid line
    # (if any) comes before it. statistics.csv says whether the step
    # remeshed and how many FGMRES iterations it took.
    awk -F, '
      FNR == 1 && FILENAME ~ /statistics.csv$/ {
        for (i = 1; i <= NF; ++i) col[$i] = i
        next
      }
      FILENAME ~ /statistics.csv$/ {
        remeshed[$1] = $col["remeshed"]; iters[$1] = $col["linear_iterations"]
        next
      }
      /multigrid: .*update/ {
        if (match($0, /diagonals [0-9.e+-]+/)) diag = substr($0, RSTART + 10, RLENGTH - 10)
        if (match($0, /blocks [0-9.e+-]+/)) blocks = substr($0, RSTART + 7, RLENGTH - 7)
      }
      /Stokes: assembly/ {
        # Named fields, not positions: the line also carries sub-times.
        a = 0; s = 0; u = 0
        if (match($0, /assembly [0-9.e+-]+/)) a = substr($0, RSTART + 9, RLENGTH - 9)
        if (match($0, /set-up [0-9.e+-]+/)) s = substr($0, RSTART + 7, RLENGTH - 7)
        if (match($0, /Uzawa\/FGMRES [0-9.e+-]+/)) u = substr($0, RSTART + 13, RLENGTH - 13)
        n = step++
        if (n > 0) {
          N++; A += a; S += s; D += diag; B += blocks; U += u; I += iters[n]
          if (remeshed[n] == 0) { K++; KA += a; KS += s; KD += diag; KB += blocks; KU += u; KI += iters[n] }
        }
        diag = 0; blocks = 0
      }
      END {
        if (N == 0) { print "| " scene " | " label " | no step | | | | | | | |"; exit }
        printf "| %s | %s | %d | %.3f | %.3f | %.3f | %.3f | %.3f | %.1f | %.3f |\n",
          scene, label, N, A / N, S / N, D / N, B / N, U / N, I / N, (A + S + U) / N
        if (K > 0)
          printf "| %s | %s | (%d kept) | %.3f | %.3f | %.3f | %.3f | %.3f | %.1f | %.3f |\n",
            scene, label, K, KA / K, KS / K, KD / K, KB / K, KU / K, KI / K, (KA + KS + KU) / K
      }' scene="$scene" label="$label" "$run/statistics.csv" "$run.log"
  done
done
