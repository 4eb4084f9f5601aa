# Sourced by the long stress scripts (dense_suspension.sh, suspension_3d.sh):
# choose the working folder and, with RESUME=1, continue an earlier run.
#   WORK=<dir>  work in <dir> (kept) instead of a temporary folder
#   RESUME=1    with the same WORK: 'fidus --resume' the run there, print the
#               summary, copy the output to KEEP if set, and exit
# Usage: long_run_prepare <prm file name>; sets $work. Needs $top and $fidus.
long_run_prepare() {
  local prm_name="$1"
  if [ -n "${WORK:-}" ]; then
    mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
  else
    work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT
  fi
  if [ -n "${RESUME:-}" ]; then
    [ -f "$work/$prm_name" ] || { echo "RESUME=1 needs WORK=<dir> of an earlier run" >&2; exit 1; }
    local status=0
    "$fidus" --resume "$work/$prm_name" || status=$?
    "$top/contrib/benchmarks/summarize_run.sh" "$work/out"
    if [ -n "${KEEP:-}" ]; then mkdir -p "$KEEP" && cp -r "$work/out/." "$KEEP/"; fi
    exit $status
  fi
}
