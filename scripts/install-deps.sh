#!/usr/bin/env bash
# The one list of system packages fcl_quadric needs (Debian 12). README's commands and
# .ci/run both call this script, so a fresh machine gets exactly what a developer has.
#   scripts/install-deps.sh               build, tests, benchmarks, CLI, OMPL layer
#   scripts/install-deps.sh --sanitizers  also clang-14 and its runtimes, for
#                                         scripts/ci-sanitizers.sh and the fuzz targets
set -euo pipefail
PKGS=(
  build-essential cmake ninja-build pkg-config
  libfcl-dev libccd-dev libeigen3-dev liboctomap-dev libompl-dev
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  nlohmann-json3-dev libcli11-dev libcairo2-dev
  libboost-dev libgmp-dev
  libbullet-dev
)
# Sanitizer and fuzz builds (scripts/ci-sanitizers.sh, docs/reliability.md): clang with its
# runtimes (libFuzzer, ASan/UBSan/TSan) and llvm-symbolizer for readable reports.
SANITIZER_PKGS=(clang-14 libclang-rt-14-dev llvm-14)
for arg in "$@"; do
  case "$arg" in
    --sanitizers) PKGS+=("${SANITIZER_PKGS[@]}") ;;
    *) echo "install-deps.sh: unknown option '$arg' (known: --sanitizers)" >&2; exit 2 ;;
  esac
done
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO=sudo; fi
export DEBIAN_FRONTEND=noninteractive
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  $SUDO apt-get update
  $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi
