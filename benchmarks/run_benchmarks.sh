#!/usr/bin/env bash
# Build (Release, the default build type) and run the benchmark programs with the settings of
# docs/benchmarks.md.
# Usage: benchmarks/run_benchmarks.sh BUILD_DIR [OUTPUT_DIR (default BUILD_DIR/results)]
# Env: MIN_TIME (s, default 0.2), REPS (default 3), PAIRS (default 100000; smaller for CI smoke runs).
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

mkdir -p "${out}"
# The library may change under the benchmarks: record which sources were built and measured.
fingerprint=$(cd "${src}" && find src include -type f | LC_ALL=C sort | xargs cat | sha256sum | cut -c1-16)
cmake -S "${src}" -B "${build}" -DFCL_QUADRIC_BUILD_TESTS=OFF -DFCL_QUADRIC_BUILD_CLI=OFF
cmake --build "${build}" -j2 --target bench_static bench_separating_planes
after=$(cd "${src}" && find src include -type f | LC_ALL=C sort | xargs cat | sha256sum | cut -c1-16)
{
  date -u +%FT%TZ
  echo "library sources (src/, include/) sha256: ${fingerprint}"
  [[ "${after}" == "${fingerprint}" ]] || echo "WARNING: sources changed during the build (now ${after})"
  uptime
} | tee "${out}/run_info.txt"
common=(--benchmark_min_time="${min_time}" --benchmark_repetitions="${reps}"
        --benchmark_report_aggregates_only=true --benchmark_color=false --benchmark_out_format=json)
"${build}/benchmarks/bench_static" --pairs "${pairs}" "${common[@]}" \
  --benchmark_out="${out}/bench_static.json" | tee "${out}/bench_static.txt"
"${build}/benchmarks/bench_separating_planes" "${common[@]}" \
  --benchmark_out="${out}/bench_separating_planes.json" | tee "${out}/bench_separating_planes.txt"
