#!/usr/bin/env bash
# Installs what fidus needs on a fresh Debian (bookworm) machine, and nothing
# when it is all there already. Used by contrib/run.sh and contrib/test.sh.
set -euo pipefail
# bc and time: the benchmark scripts' arithmetic and peak-memory readings.
# libopenblas0-serial: Debian's alternatives then give it to MUMPS (the
# cut element's direct solver) in place of the reference BLAS; twice as
# fast on 3D fronts, the same results to round-off
# (contrib/benchmarks/blas_choice.sh, doc/performance.md). Serial, so that
# MPI ranks do not compete with BLAS threads for the cores.
# libmumps-dev: MUMPS's C interface, which the cut element calls (deal.II's
# Trilinos depends on it already).
packages=(libdeal.ii-dev numdiff libeigen3-dev libboost-dev ccache
          python3-matplotlib clang-format cmake g++ make openmpi-bin procps
          bc time libopenblas0-serial libmumps-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "fidus: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
