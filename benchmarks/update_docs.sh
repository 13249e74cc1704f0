#!/usr/bin/env bash
# Regenerates every measured number of docs/benchmarks.md from one real run.
#
# Runs benchmarks/run_benchmarks.sh BUILD_DIR into benchmarks/results/TAG/ (the folder is replaced
# when the run succeeds; the files of programs this run did not run, e.g. bench_quadric_shapes.txt,
# are carried over from the old folder), then replaces everything between the marker lines
#   <!-- BEGIN GENERATED: NAME -->
#   <!-- END GENERATED: NAME -->
# of docs/benchmarks.md with block NAME of the run's output in a ```text fence. Blocks:
#   run-info          results/TAG/run_info.txt, whole
#   static-summary    bench_static.txt, "== Summary: ..."   (up to the next blank line)
#   static-targets    bench_static.txt, "== Targets ..."
#   static-agreement  bench_static.txt, "== Agreement ..."
#   planes-summary    bench_separating_planes.txt, "== Summary: ..."
#   table1            bench_separating_planes.txt, "== Table 1 ..."
#   table2            bench_separating_planes.txt, "== Table 2 ..."
#   fcl-scenes-run-info   results/TAG/run_info.txt, whole (the conditions of the FCL-scenes numbers,
#                         which may come from a run of bench_fcl_scenes alone, see BLOCKS)
#   fcl-scenes-summary    bench_fcl_scenes.txt, "== FCL scenes summary ..."
#   fcl-scenes-results    bench_fcl_scenes.txt, "== FCL scenes: results ..."
#   fcl-scenes-aim        bench_fcl_scenes.txt, "== FCL scenes: aim ..."
#   ccd-run-info          results/TAG/bench_ccd_run_info.txt if present (a run of bench_ccd alone,
#                         kept next to the full run's outputs), else results/TAG/run_info.txt
#   ccd-summary           bench_ccd.txt, "== CCD summary ..."
#   ccd-boxing            bench_ccd.txt, "== CCD boxing ..."
#   ccd-fcl               bench_ccd.txt, "== CCD vs FCL ..."
#   ccd-arm               bench_ccd.txt, "== CCD robot arm ..."
#   ccd-aim               bench_ccd.txt, "== CCD aim ..."
# Fails, leaving the document untouched, if a block is missing from the output, or a marker is
# missing, duplicated, unknown or unbalanced in the document.
#
# Usage: benchmarks/update_docs.sh BUILD_DIR
# Env:   TAG (default xeon-2core-vm): the machine, i.e. the results folder name.
#        DOC (default docs/benchmarks.md of this checkout): the document to rewrite.
#        SKIP_RUN=1: no run; regenerate the document from the results already in the folder.
#        RESULTS: the results folder (default benchmarks/results/TAG).
#        BLOCKS: the blocks to replace (default: all); the others are kept as they are (their
#          markers are still checked). E.g. the FCL-scenes section alone, from a run of that
#          program alone outside the results folder:
#            PROGRAMS=bench_fcl_scenes benchmarks/run_benchmarks.sh BUILD_DIR /tmp/fcl-scenes
#            SKIP_RUN=1 RESULTS=/tmp/fcl-scenes \
#              BLOCKS="fcl-scenes-run-info fcl-scenes-summary fcl-scenes-results fcl-scenes-aim" \
#              benchmarks/update_docs.sh BUILD_DIR
#          The continuous-collision section alone, kept in the results folder:
#            PROGRAMS=bench_ccd benchmarks/run_benchmarks.sh BUILD_DIR /tmp/ccd
#            cp /tmp/ccd/bench_ccd.txt /tmp/ccd/bench_ccd.json benchmarks/results/TAG/
#            cp /tmp/ccd/run_info.txt benchmarks/results/TAG/bench_ccd_run_info.txt
#            SKIP_RUN=1 BLOCKS="ccd-run-info ccd-summary ccd-boxing ccd-fcl ccd-arm ccd-aim" \
#              benchmarks/update_docs.sh BUILD_DIR
#        MIN_TIME, REPS, PAIRS, TABLE1_SEEDS, FRAMES, FRAMES_1000, QUERIES, CCD_FRAMES, CCD_RANDOM,
#          PROGRAMS: passed on to run_benchmarks.sh (smoke runs).
set -euo pipefail
die() {
  echo "update_docs.sh: $*" >&2
  exit 1
}
[[ $# -eq 1 ]] || {
  echo "usage: $0 BUILD_DIR" >&2
  exit 2
}
src=$(cd "$(dirname "$0")/.." && pwd)
build=$1
tag=${TAG:-xeon-2core-vm}
doc=${DOC:-${src}/docs/benchmarks.md}
[[ "${tag}" =~ ^[A-Za-z0-9][A-Za-z0-9._-]*$ ]] || die "bad TAG '${tag}' (letters, digits, . _ -)"
[[ -f "${doc}" ]] || die "no document ${doc}"
results=${RESULTS:-${src}/benchmarks/results/${tag}}

work=$(mktemp -d)
staging=""
cleanup() {
  rm -rf "${work}"
  [[ -z "${staging}" ]] || rm -rf "${staging}"
}
trap cleanup EXIT

if [[ "${SKIP_RUN:-0}" != 1 ]]; then
  # Run into a staging folder next to the results, and replace the old results only on success.
  mkdir -p "${src}/benchmarks/results"
  staging=$(mktemp -d "${src}/benchmarks/results/.${tag}.run.XXXXXX")
  "${src}/benchmarks/run_benchmarks.sh" "${build}" "${staging}" || die "benchmark run failed"
  # Keep the old folder's files of programs this run did not run: a file belongs to the program
  # its name starts with (bench_ccd.txt, bench_ccd.json and bench_ccd_run_info.txt to bench_ccd).
  if [[ -d "${results}" ]]; then
    for f in "${results}"/*; do
      [[ -f "${f}" ]] || continue
      name=$(basename "${f}")
      program=${name%%.*}
      program=${program%_run_info}
      if ! compgen -G "${staging}/${program}.*" >/dev/null; then cp -p "${f}" "${staging}/"; fi
    done
  fi
  rm -rf "${results}"
  mv "${staging}" "${results}"
  staging=""
  chmod 755 "${results}"
fi
[[ -d "${results}" ]] || die "no results in ${results}"

# block NAME FILE HEADER: the lines from the one line starting with HEADER to the next blank line.
block() {
  local name=$1 file=${results}/$2 header=$3
  [[ -f "${file}" ]] || die "block ${name}: no ${file}"
  awk -v header="${header}" '
    { gsub(/\033\[[0-9;]*m/, "") }  # colour escapes, should there be any
    index($0, header) == 1 { found++; inside = 1 }
    inside && /^[[:space:]]*$/ { inside = 0 }
    inside { print }
    END { exit found == 1 ? 0 : 1 }' "${file}" >"${work}/${name}.txt" ||
    die "block ${name}: expected exactly one line starting with '${header}' in ${file}"
}
names=(run-info static-summary static-targets static-agreement planes-summary table1 table2
       fcl-scenes-run-info fcl-scenes-summary fcl-scenes-results fcl-scenes-aim
       ccd-run-info ccd-summary ccd-boxing ccd-fcl ccd-arm ccd-aim)
read -r -a replace <<<"${BLOCKS:-${names[*]}}"
for b in "${replace[@]}"; do
  [[ " ${names[*]} " == *" ${b} "* ]] || die "unknown block '${b}' in BLOCKS"
done
wanted() { [[ " ${replace[*]} " == *" $1 "* ]]; }
run_info() {
  local file=${results}/${2:-run_info.txt}
  [[ -s "${file}" ]] || die "block $1: no ${file}"
  sed 's/\x1b\[[0-9;]*m//g' "${file}" >"${work}/$1.txt"
}
if wanted run-info; then run_info run-info; fi
if wanted static-summary; then block static-summary bench_static.txt "== Summary:"; fi
if wanted static-targets; then block static-targets bench_static.txt "== Targets"; fi
if wanted static-agreement; then block static-agreement bench_static.txt "== Agreement"; fi
if wanted planes-summary; then block planes-summary bench_separating_planes.txt "== Summary:"; fi
if wanted table1; then block table1 bench_separating_planes.txt "== Table 1"; fi
if wanted table2; then block table2 bench_separating_planes.txt "== Table 2"; fi
if wanted fcl-scenes-run-info; then run_info fcl-scenes-run-info; fi
if wanted fcl-scenes-summary; then block fcl-scenes-summary bench_fcl_scenes.txt "== FCL scenes summary"; fi
if wanted fcl-scenes-results; then block fcl-scenes-results bench_fcl_scenes.txt "== FCL scenes: results"; fi
if wanted fcl-scenes-aim; then block fcl-scenes-aim bench_fcl_scenes.txt "== FCL scenes: aim"; fi
if wanted ccd-run-info; then
  if [[ -f "${results}/bench_ccd_run_info.txt" ]]; then
    run_info ccd-run-info bench_ccd_run_info.txt
  else
    run_info ccd-run-info
  fi
fi
if wanted ccd-summary; then block ccd-summary bench_ccd.txt "== CCD summary"; fi
if wanted ccd-boxing; then block ccd-boxing bench_ccd.txt "== CCD boxing"; fi
if wanted ccd-fcl; then block ccd-fcl bench_ccd.txt "== CCD vs FCL"; fi
if wanted ccd-arm; then block ccd-arm bench_ccd.txt "== CCD robot arm"; fi
if wanted ccd-aim; then block ccd-aim bench_ccd.txt "== CCD aim"; fi

awk -v dir="${work}" -v names="${names[*]}" -v replace="${replace[*]}" '
  function fail(message) {
    printf "update_docs.sh: %s:%d: %s\n", FILENAME, FNR, message > "/dev/stderr"
    failed = 1
    exit 1
  }
  BEGIN {
    n = split(names, list, " ")
    for (i = 1; i <= n; i++) known[list[i]] = 1
    m = split(replace, chosen, " ")
    for (i = 1; i <= m; i++) wanted[chosen[i]] = 1
    fence = "```"
  }
  /^<!-- BEGIN GENERATED: [A-Za-z0-9_-]+ -->$/ {
    if (open != "") fail("BEGIN of " $4 " inside block " open)
    if (!($4 in known)) fail("unknown block " $4)
    if ($4 in seen) fail("second BEGIN of block " $4)
    seen[$4] = 1
    open = $4
    print
    keep = !($4 in wanted)  # a block not being replaced keeps its text
    if (keep) next
    print fence "text"
    file = dir "/" open ".txt"
    while ((status = (getline line < file)) > 0) print line
    if (status < 0) fail("cannot read " file)
    close(file)
    print fence
    next
  }
  /^<!-- END GENERATED: [A-Za-z0-9_-]+ -->$/ {
    if (open == "") fail("END of " $4 " without BEGIN")
    if ($4 != open) fail("END of " $4 " inside block " open)
    open = ""
    print
    next
  }
  /^[[:space:]]*<!--[[:space:]]*(BEGIN|END)[[:space:]]+GENERATED/ { fail("malformed marker: " $0) }
  open == "" || keep { print }
  END {
    if (failed) exit 1
    if (open != "") { printf "update_docs.sh: block %s has no END marker\n", open > "/dev/stderr"; exit 1 }
    for (i = 1; i <= n; i++) {
      if (!(list[i] in seen)) {
        printf "update_docs.sh: no marker for block %s in the document\n", list[i] > "/dev/stderr"
        exit 1
      }
    }
  }' "${doc}" >"${work}/doc.md" || die "${doc} not changed"
cat "${work}/doc.md" >"${doc}"
echo "update_docs.sh: ${doc} regenerated from ${results}"
