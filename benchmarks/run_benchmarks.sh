#!/usr/bin/env bash
# Build (Release, the default build type) and run the benchmark programs with the settings of
# docs/benchmarks.md. benchmarks/update_docs.sh calls this script and copies the end-of-run blocks
# of its outputs into docs/benchmarks.md.
# Usage: benchmarks/run_benchmarks.sh BUILD_DIR [OUTPUT_DIR (default BUILD_DIR/results)]
# Env: MIN_TIME (s, default 0.2), REPS (default 5), PAIRS (default 100000), TABLE1_SEEDS (default
#      16), FRAMES (bench_fcl_scenes, default 1000), FRAMES_1000 (its 1,000-ellipsoid sequence,
#      default FRAMES), QUERIES (bench_fcl_scenes, default 400); smaller values for smoke runs.
#      CCD_FRAMES (bench_ccd boxing frames, default 1000), CCD_RANDOM (bench_ccd random pairs,
#      default 2000).
#      PROGRAMS (default "bench_static bench_separating_planes bench_fcl_scenes bench_ccd"): the
#      programs to build and run, e.g. PROGRAMS=bench_fcl_scenes for that program alone.
#      WAIT_IDLE (s, default 600): first wait, up to that long, for the 1-minute load to fall to
#      0.5 or below (the load of a test run just ended takes about two minutes to decay); 0 does
#      not wait. A run that starts above 0.5 all the same says so in run_info.txt.
# A new BUILD_DIR is configured without tests and CLI. An existing one keeps its options (it may be
# someone's working build): only the benchmark targets are built, and it must be Release.
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
wait_idle=${WAIT_IDLE:-600}
[[ "${wait_idle}" =~ ^[0-9]+$ ]] || {
  echo "run_benchmarks.sh: WAIT_IDLE must be a whole number of seconds, not '${wait_idle}'" >&2
  exit 2
}
waited=0
read -r load_at_start _ </proc/loadavg
while ((waited < wait_idle)) && awk -v l="${load_at_start}" 'BEGIN { exit !(l > 0.5) }'; do
  sleep 10
  waited=$((waited + 10))
  read -r load_at_start _ </proc/loadavg
done
min_time=${MIN_TIME:-0.2}
reps=${REPS:-5}
pairs=${PAIRS:-100000}
table1_seeds=${TABLE1_SEEDS:-16}
frames=${FRAMES:-1000}
frames_1000=${FRAMES_1000:-${frames}}
queries=${QUERIES:-400}
ccd_frames=${CCD_FRAMES:-1000}
ccd_random=${CCD_RANDOM:-2000}
read -r -a programs <<<"${PROGRAMS:-bench_static bench_separating_planes bench_fcl_scenes bench_ccd}"
for p in "${programs[@]}"; do
  case "${p}" in
    bench_static | bench_separating_planes | bench_fcl_scenes | bench_ccd) ;;
    *)
      echo "$0: unknown program '${p}' in PROGRAMS" >&2
      exit 2
      ;;
  esac
done
[[ ${#programs[@]} -gt 0 ]] || {
  echo "$0: PROGRAMS is empty" >&2
  exit 2
}
runs() { [[ " ${programs[*]} " == *" $1 "* ]]; }

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
cmake --build "${build}" -j2 --target "${programs[@]}"
lib_after=$(lib_sources)
bench_after=$(bench_sources)
bin=$(mktemp -d)
trap 'rm -rf "${bin}"' EXIT
for p in "${programs[@]}"; do cp "${build}/benchmarks/${p}" "${bin}/"; done

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
  echo "settings: MIN_TIME=${min_time} REPS=${reps} PAIRS=${pairs} TABLE1_SEEDS=${table1_seeds}" \
    "FRAMES=${frames} FRAMES_1000=${frames_1000} QUERIES=${queries} CCD_FRAMES=${ccd_frames} CCD_RANDOM=${ccd_random}"
  echo "programs: ${programs[*]}"
  echo "load before: $(uptime | sed 's/^ *//') (after waiting ${waited} s for it to fall to 0.5)"
  # The timed loops assume an otherwise idle machine: a run started while something else was
  # running (a build, tests, another benchmark) says so, above its numbers. The load is the one
  # sampled when this script started (after the WAIT_IDLE wait), before its own build of the
  # benchmark targets.
  if awk -v l="${load_at_start}" 'BEGIN { exit !(l > 0.5) }'; then
    echo "WARNING: 1-minute load ${load_at_start} > 0.5 when the run was started: the machine was not idle," \
      "numbers may be noisy"
  fi
} | tee "${out}/run_info.txt"
common=(--benchmark_min_time="${min_time}" --benchmark_repetitions="${reps}"
        --benchmark_report_aggregates_only=true --benchmark_color=false --benchmark_out_format=json)
# bench_static's benchmarks are pure functions of fixed pairs, so their repetitions are run in
# random interleaved order: a slow spell of the host (seconds long here) then costs one repetition
# of several benchmarks instead of all repetitions of one, and the medians keep it out. The other
# programs run in registration order, as before: their benchmarks were not audited for state
# carried from one run to the next.
if runs bench_static; then
  "${bin}/bench_static" --pairs "${pairs}" "${common[@]}" --benchmark_enable_random_interleaving=true \
    --benchmark_out="${out}/bench_static.json" 2>&1 | tee "${out}/bench_static.txt"
fi
if runs bench_separating_planes; then
  "${bin}/bench_separating_planes" --table1_seeds "${table1_seeds}" "${common[@]}" \
    --benchmark_out="${out}/bench_separating_planes.json" 2>&1 | tee "${out}/bench_separating_planes.txt"
fi
if runs bench_fcl_scenes; then
  "${bin}/bench_fcl_scenes" --frames "${frames}" --frames_1000 "${frames_1000}" --queries "${queries}" "${common[@]}" \
    --benchmark_out="${out}/bench_fcl_scenes.json" 2>&1 | tee "${out}/bench_fcl_scenes.txt"
fi
if runs bench_ccd; then
  "${bin}/bench_ccd" --frames "${ccd_frames}" --random_pairs "${ccd_random}" "${common[@]}" \
    --benchmark_out="${out}/bench_ccd.json" 2>&1 | tee "${out}/bench_ccd.txt"
fi
{
  echo "load after:  $(uptime | sed 's/^ *//')"
  echo "finished: $(date -u +%FT%TZ), $((SECONDS - start)) s in all"
  [[ "$(lib_sources)" == "${lib_before}" ]] ||
    echo "NOTE: library sources changed during the run; the measured binaries were built from ${lib_after}"
} | tee -a "${out}/run_info.txt"
