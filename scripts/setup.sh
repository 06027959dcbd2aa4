#!/usr/bin/env bash
# fibra set-up: installs the Debian packages fibra needs (when missing), configures and
# builds a Release tree in build/. Idempotent and quiet when everything is present.
#   bash scripts/setup.sh            # library, program, tests, benches
#   FIBRA_WITH_PETSC=1 bash scripts/setup.sh   # also Debian's petsc-dev (~115 packages, with
#                                    # MUMPS and hypre), for bench_petsc_solves (optional)
# Environment: FIBRA_BUILD_DIR (default build), FIBRA_JOBS (default: all cores),
# FIBRA_WITH_PETSC (1: install petsc-dev too; nothing else needs it).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${FIBRA_BUILD_DIR:-$here/build}
jobs=${FIBRA_JOBS:-$(nproc)}

packages=(build-essential cmake ninja-build ccache pkg-config
          libeigen3-dev libtbb-dev libsuitesparse-dev libopenblas-dev libmumps-seq-dev
          libscotch-dev
          doctest-dev nlohmann-json3-dev zlib1g-dev gnuplot-nox)
if [ "${FIBRA_WITH_PETSC:-0}" = 1 ]; then
  packages+=(petsc-dev)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "fibra setup: installing ${missing[*]}" >&2
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# CHOLMOD's supernodal factorisation spends its time in BLAS: make sure the system BLAS is
# OpenBLAS rather than the reference implementation (about 17x slower here).
blas=$(readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3 2>/dev/null || true)
case "$blas" in *openblas*) ;; *) echo "fibra setup: warning: libblas.so.3 is $blas, not OpenBLAS" >&2 ;; esac

if [ ! -f "$build/build.ninja" ]; then
  cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
elif [ "${FIBRA_WITH_PETSC:-0}" = 1 ] && ! grep -q bench_petsc_solves "$build/build.ninja"; then
  cmake "$build" >/dev/null  # PETSc installed after the tree was configured: find it now
fi
if ! cmake --build "$build" -j "$jobs" >"$build/build.log" 2>&1; then
  grep -vE '^\[[0-9]+/[0-9]+\] ' "$build/build.log" >&2
  echo "fibra setup: build failed (full log: $build/build.log)" >&2
  exit 1
fi
