#!/usr/bin/env bash
# Shared set-up of scripts/run.sh and scripts/test.sh (sourced by both):
# install the Debian packages that are missing, configure (Release) and
# build into build/. Idempotent: a second call only rebuilds what changed.
set -euo pipefail

CYCLOID_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
CYCLOID_BUILD=${CYCLOID_BUILD:-$CYCLOID_ROOT/build}

CYCLOID_PACKAGES=(
  build-essential cmake ccache
  libdeal.ii-dev libgmsh-dev gmsh libmumps-dev
  openmpi-bin libgtest-dev numdiff doxygen
  python3 python3-numpy python3-matplotlib python3-vtk9 python3-h5py
  python3-ezdxf python3-gmsh
)

cycloid_install_packages() {
  local missing=() p
  for p in "${CYCLOID_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" \
      || missing+=("$p")
  done
  if ((${#missing[@]} == 0)); then
    return 0
  fi
  echo "[setup] installing Debian packages: ${missing[*]}"
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || {
      echo "[setup] error: need root or sudo to install ${missing[*]}" >&2
      exit 1
    }
    sudo=sudo
  fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
}

cycloid_build() {
  if [ ! -f "$CYCLOID_BUILD/CMakeCache.txt" ]; then
    echo "[setup] configuring into $CYCLOID_BUILD"
    cmake -S "$CYCLOID_ROOT" -B "$CYCLOID_BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
  fi
  echo "[setup] building (Release)"
  cmake --build "$CYCLOID_BUILD" -j "$(nproc)" -- --no-print-directory 2>&1 \
    | grep -vE '^\[ *[0-9]+%\]|^Consolidate compiler generated' || true
  test -x "$CYCLOID_BUILD/cycloid-contact" || {
    echo "[setup] error: the build failed (no $CYCLOID_BUILD/cycloid-contact)" >&2
    exit 1
  }
}

# mpirun as root needs --allow-run-as-root; with fewer cores than ranks it
# needs --oversubscribe.
cycloid_mpirun() {
  local np=$1
  shift
  local flags=()
  [ "$(id -u)" -eq 0 ] && flags+=(--allow-run-as-root)
  [ "$(nproc)" -lt "$np" ] && flags+=(--oversubscribe)
  mpirun "${flags[@]}" -np "$np" "$@"
}

cycloid_install_packages
cycloid_build
