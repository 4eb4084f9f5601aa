#!/bin/bash
# Every ```prm block of doc/manual, doc/cookbooks and doc/README.md passes
# `fidus --validate`; every ```prm-fragment block names known entries.
# The convention is described in check_prm_blocks.py.
#
# Usage: tests/doc/check_prm_blocks.sh FIDUS SOURCE_DIR
set -u
here="$(cd "$(dirname "$0")" && pwd)"
exec python3 "$here/check_prm_blocks.py" "${1:?usage: check_prm_blocks.sh FIDUS SOURCE_DIR}" \
  "${2:?usage: check_prm_blocks.sh FIDUS SOURCE_DIR}"
