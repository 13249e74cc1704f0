#!/usr/bin/env bash
# Build (Release, the default build type) and run the benchmark programs with the settings of
# docs/benchmarks.md. benchmarks/update_docs.sh calls this script and copies the end-of-run blocks
# of its outputs into docs/benchmarks.md.
# Usage: benchmarks/run_benchmarks.sh BUILD_DIR [OUTPUT_DIR (default BUILD_DIR/results)]
# Env: MIN_TIME (s, default 0.2), REPS (default 3), PAIRS (default 100000), TABLE1_SEEDS (default
#      16); smaller PAIRS / TABLE1_SEEDS / MIN_TIME / REPS for smoke runs.
# A new BUILD_DIR is configured without tests and CLI. An existing one keeps its options (it may be
# someone's working build): only the two benchmark targets are built, and it must be Release.
# The programs run from a copy of the binaries, so a rebuild of BUILD_DIR during the run cannot
# change what is measured. OUTPUT_DIR receives run_info.txt (date, fingerprints of the measured
# sources, machine, settings, load before and after) and, per program, its console output (.txt,
# stdout and stderr) and Google Benchmark's JSON (.json).
set -euo pipefail
if [[ $# -lt 1 ]]; then
  echo "usage: $0 BUILD_DIR [OUTPUT_DIR]" >&2
  exit 2
fi
src=$(cd "$(dirname "$0")/.." && pwd)
build=$1
out=${2:-${build}/results}
min_time=${MIN_TIME:-0.2}
reps=${REPS:-3}
pairs=${PAIRS:-100000}
table1_seeds=${TABLE1_SEEDS:-16}

# The library may change under the benchmarks: record which sources were built and measured.
lib_sources() { (cd "${src}" && find src include -type f | LC_ALL=C sort | xargs cat | sha256sum | cut -c1-16); }
bench_sources() {
  (cd "${src}" && find benchmarks -maxdepth 1 -type f \( -name '*.cpp' -o -name '*.h' \) | LC_ALL=C sort |
    xargs cat | sha256sum | cut -c1-16)
}

mkdir -p "${out}"
start=${SECONDS}
lib_before=$(lib_sources)
bench_before=$(bench_sources)
if [[ -f "${build}/CMakeCache.txt" ]]; then
  grep -q '^FCL_QUADRIC_BUILD_BENCHMARKS:BOOL=ON$' "${build}/CMakeCache.txt" || {
    echo "$0: ${build} is configured with FCL_QUADRIC_BUILD_BENCHMARKS off" >&2
    exit 1
  }
else
  cmake -S "${src}" -B "${build}" -DFCL_QUADRIC_BUILD_TESTS=OFF -DFCL_QUADRIC_BUILD_CLI=OFF
fi
cmake --build "${build}" -j2 --target bench_static bench_separating_planes
lib_after=$(lib_sources)
bench_after=$(bench_sources)
bin=$(mktemp -d)
trap 'rm -rf "${bin}"' EXIT
cp "${build}/benchmarks/bench_static" "${build}/benchmarks/bench_separating_planes" "${bin}/"

cache_value() { sed -n "s/^$1:[A-Z]*=//p" "${build}/CMakeCache.txt"; }
build_type=$(cache_value CMAKE_BUILD_TYPE)
compiler=$(cache_value CMAKE_CXX_COMPILER)
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
mhz=$(sed -n 's/^cpu MHz[[:space:]]*: //p' /proc/cpuinfo | head -1)
os=$(sed -n 's/^PRETTY_NAME="\(.*\)"$/\1/p' /etc/os-release 2>/dev/null || true)
{
  echo "started:  $(date -u +%FT%TZ)"
  echo "library sources (src/, include/) sha256: ${lib_before}"
  [[ "${lib_after}" == "${lib_before}" ]] || echo "WARNING: library sources changed during the build (now ${lib_after})"
  echo "benchmark sources (benchmarks/*.cpp, *.h) sha256: ${bench_before}"
  [[ "${bench_after}" == "${bench_before}" ]] ||
    echo "WARNING: benchmark sources changed during the build (now ${bench_after})"
  echo "machine:  ${cpu:-unknown CPU} (${mhz%.*} MHz), $(nproc) logical CPUs, ${os:-unknown OS}"
  echo "build:    CMAKE_BUILD_TYPE=${build_type:-<none>}, $("${compiler:-c++}" --version | head -1)"
  [[ "${build_type}" == "Release" ]] || echo "WARNING: not a Release build"
  echo "settings: MIN_TIME=${min_time} REPS=${reps} PAIRS=${pairs} TABLE1_SEEDS=${table1_seeds}"
  echo "load before: $(uptime | sed 's/^ *//')"
} | tee "${out}/run_info.txt"
common=(--benchmark_min_time="${min_time}" --benchmark_repetitions="${reps}"
        --benchmark_report_aggregates_only=true --benchmark_color=false --benchmark_out_format=json)
"${bin}/bench_static" --pairs "${pairs}" "${common[@]}" \
  --benchmark_out="${out}/bench_static.json" 2>&1 | tee "${out}/bench_static.txt"
"${bin}/bench_separating_planes" --table1_seeds "${table1_seeds}" "${common[@]}" \
  --benchmark_out="${out}/bench_separating_planes.json" 2>&1 | tee "${out}/bench_separating_planes.txt"
{
  echo "load after:  $(uptime | sed 's/^ *//')"
  echo "finished: $(date -u +%FT%TZ), $((SECONDS - start)) s in all"
  [[ "$(lib_sources)" == "${lib_before}" ]] ||
    echo "NOTE: library sources changed during the run; the measured binaries were built from ${lib_after}"
} | tee -a "${out}/run_info.txt"
