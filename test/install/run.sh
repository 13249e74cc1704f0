#!/usr/bin/env bash
# Install the built tree into a scratch prefix, then configure, build and run a downstream project
# that uses find_package(fcl_quadric) and pkg-config. Arguments: BUILD_DIR SOURCE_DIR.
set -euo pipefail
build=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
cmake -S "$src/test/install" -B "$work/downstream" -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log"
cmake --build "$work/downstream" > "$work/build.log"
"$work/downstream/downstream"
pcdir=$(dirname "$(find "$work/prefix" -name fcl_quadric.pc)")
PKG_CONFIG_PATH="$pcdir" pkg-config --exists --print-errors fcl_quadric
echo "pkg-config: $(PKG_CONFIG_PATH="$pcdir" pkg-config --modversion fcl_quadric)"
