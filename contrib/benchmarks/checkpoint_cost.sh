#!/usr/bin/env bash
# Cost of checkpoints: runs a scene twice, without checkpoints and with one
# after every step ('Checkpoint interval = 1'), and prints a Markdown table:
# steps, run wall time of both, and per checkpoint its size (bytes of the
# mesh, multiplier and state) and the seconds to write it (the line fidus
# prints for each checkpoint), plus the cost of one resume (loading the
# newest checkpoint, from the 'checkpoint' row of the timing table).
# Usage: contrib/benchmarks/checkpoint_cost.sh [file.prm] [End time] [ranks]
#   default: prm/two_particles_2d.prm to its End time, 1 rank.
# FIDUS=<binary> uses another build; OLD=<binary> adds a third run of the
# scene with that binary (no checkpoints), for before/after timings.
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
prm="$(cd "$(dirname "${1:-$top/prm/two_particles_2d.prm}")" && pwd)/$(basename "${1:-$top/prm/two_particles_2d.prm}")"
end="${2:-}"; ranks="${3:-1}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
launch=()
[ "$ranks" -gt 1 ] && launch=(mpirun -np "$ranks")
work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT

# variant NAME CHECKPOINT-INTERVAL: the scene with its output in $work/NAME.
variant() {
  {
    sed "s|^\( *set Output directory *=\).*|\1 $work/$1|" "$prm"
    [ -n "$end" ] && printf 'subsection Time stepping\n  set End time = %s\nend\n' "$end"
    printf 'subsection Output\n  set Checkpoint interval = %s\n  set Checkpoint wall interval = 0\n  set Particle output interval = 0\n  set Field output interval = 0\nend\n' "$2"
  } > "$work/$1.prm"
}
seconds() { awk -F, 'END { print $12 }' "$1/statistics.csv"; }

variant plain 0
variant checkpointed 1
"${launch[@]}" "$fidus" "$work/plain.prm" > "$work/plain.log"
"${launch[@]}" "$fidus" "$work/checkpointed.prm" > "$work/checkpointed.log"
# Resume from the last checkpoint with nothing left to do: the cost of a load.
"${launch[@]}" "$fidus" --resume "$work/checkpointed.prm" > "$work/resume.log"

steps=$(awk -F, 'END { print $1 }' "$work/plain/statistics.csv")
echo "scene: $prm${end:+, End time $end}, $ranks rank(s), $steps steps"
echo
echo "| run | wall s |"
echo "|---|---|"
if [ -n "${OLD:-}" ]; then
  variant old 0
  sed -i '/Checkpoint/d; /Progress wall/d' "$work/old.prm"
  "${launch[@]}" "$OLD" "$work/old.prm" > "$work/old.log"
  echo "| $OLD, no checkpoints | $(seconds "$work/old") |"
fi
echo "| no checkpoints | $(seconds "$work/plain") |"
echo "| checkpoint after every step | $(seconds "$work/checkpointed") |"
echo
grep '^checkpoint ' "$work/checkpointed.log" | sed 's/.*: \([0-9]*\) bytes, \([0-9.]*\) s/\1 \2/' |
  awk -v load="$(grep -E '^\| checkpoint ' "$work/resume.log" | awk -F'|' '{ gsub(/ /, "", $4); print $4 }')" '
    { n++; b += $1; s += $2; if ($1 > bmax) bmax = $1; if ($2 > smax) smax = $2 }
    END {
      print "| checkpoints | mean bytes | largest bytes | mean s | largest s | load s (resume) |"
      print "|---|---|---|---|---|---|"
      printf "| %d | %.0f | %d | %.4f | %.4f | %s |\n", n, b / n, bmax, s / n, smax, load
    }'
