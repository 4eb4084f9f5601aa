# Shared set-up of the tests of the contrib/ drivers, sourced by
# run_<driver>_test.sh with the arguments path/to/fidus path/to/repo:
# sets fidus and repo (absolute), python (PYTHON, default python3), moves
# into a fresh temporary folder (removed at exit unless FIDUS_KEEP=1), and
# defines check(), which counts passes and failures.
set -u
fidus="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
repo="$(cd "$2" && pwd)"
python="${PYTHON:-python3}"
work="$(mktemp -d)"
if [ "${FIDUS_KEEP:-0}" = 1 ]; then
  echo "keeping $work"
else
  trap 'rm -rf "$work"' EXIT
fi
cd "$work"
failures=0
passes=0

check() {  # check NAME COMMAND...: run COMMAND, report ok/FAILED
  local name="$1"; shift
  if "$@"; then
    passes=$((passes + 1)); echo "ok: $name"
  else
    failures=$((failures + 1)); echo "FAILED: $name"
  fi
}
