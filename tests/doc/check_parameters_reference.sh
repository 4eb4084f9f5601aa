#!/bin/bash
# doc/manual/parameters.md is generated from `fidus --print-parameters` by
# contrib/doc/parameters_reference.py. This test regenerates it with the
# binary under test and fails, showing the difference, when the committed
# page is stale.
#
# Usage: tests/doc/check_parameters_reference.sh FIDUS SOURCE_DIR
set -u
fidus=${1:?usage: check_parameters_reference.sh FIDUS SOURCE_DIR}
source_dir=${2:?usage: check_parameters_reference.sh FIDUS SOURCE_DIR}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
page="$source_dir/doc/manual/parameters.md"
fresh=$(mktemp)
trap 'rm -f "$fresh"' EXIT
if ! python3 "$source_dir/contrib/doc/parameters_reference.py" --fidus "$fidus" --output "$fresh"; then
  echo "FAILED: contrib/doc/parameters_reference.py could not generate the reference"
  exit 1
fi
if ! diff -u "$page" "$fresh" > "$fresh.diff"; then
  head -n 60 "$fresh.diff"
  echo
  echo "FAILED: doc/manual/parameters.md does not match 'fidus --print-parameters'."
  echo "Refresh it with (from the source directory, after a build):"
  echo "  contrib/doc/parameters_reference.py --fidus build-release/fidus --output doc/manual/parameters.md"
  rm -f "$fresh.diff"
  exit 1
fi
rm -f "$fresh.diff"
echo "doc/manual/parameters.md matches fidus --print-parameters: OK"
