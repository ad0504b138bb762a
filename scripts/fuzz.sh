#!/usr/bin/env bash
# Fuzzes every reader with libFuzzer (clang, AddressSanitizer + UBSan) for SECONDS each
# (default 60), starting from the committed corpus in fuzz/corpus/<target>. New interesting
# inputs go to build-fuzz/corpus/<target>, crashes to build-fuzz/crashes/<target>/ (add a crash
# to fuzz/corpus/<target>/ once it is fixed: the normal test suite replays that corpus).
# Prints, per target, the execution rate, coverage (edges) and corpus size libFuzzer reports.
#   JOBS=N bash scripts/fuzz.sh [SECONDS] [TARGET ...]  TARGET: vti vtu vts plot3d vtkhdf_mesh series tf raw hdf5
#                                                    tsp calibration script png vtm
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH=${1:-60}
shift || true
TARGETS=("$@")
[ ${#TARGETS[@]} -eq 0 ] && TARGETS=(vti vtu vts plot3d vtkhdf_mesh series tf raw hdf5 tsp calibration script png vtm)
bash scripts/install-deps.sh
missing=()
for p in clang libclang-rt-14-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DTSP_FUZZ=ON -DTSP_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target $(printf '%s_fuzz ' "${TARGETS[@]}") >/dev/null
# HDF5 prints nothing (the readers silence it); leaks in Mesa/HDF5 are not ours to fix. A
# request larger than the allocator can serve returns null, as malloc does outside the sanitizer
# (HDF5 asks for sizes a crafted file claims and handles the failure).
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:allocator_may_return_null=1
# Each target runs for the whole SECONDS: libFuzzer's fork mode records a crash, timeout or
# out-of-memory input in build-fuzz/crashes/<target>/ and goes on. Afterwards every recorded
# input is replayed alone and classified: a report whose first frames (below the sanitizer's
# interceptor, libFuzzer, libc and the allocator) are in libhdf5 is HDF5's own parsing of
# crafted metadata (fuzz/known/README.md) — a crash, a hang or a huge allocation; a report
# anywhere else is ours and fails the run. JOBS targets run at once.
JOBS=${JOBS:-1}
# Whose code a replayed report stops in: the first stack frame outside the sanitizer, libFuzzer,
# libc and the allocator ("libhdf5", "ours" or "none" when the report has no stack).
first_frame() {
  grep -E '^ +#[0-9]+ ' "$1" |
    grep -vE '__sanitizer|fuzzer::|__interceptor|asan_|ubsan|libc\.so|/libc-|nptl/|sysdeps/|stdlib/|signal/| in malloc | in calloc | in realloc | in operator new' |
    head -1 | awk '{ if ($0 ~ /libhdf5/) print "libhdf5"; else if ($0 == "") print "none"; else print "ours" }'
}
fuzz_one() {
  local t=$1 log="build-fuzz/$1.log" summary="build-fuzz/$1.summary"
  mkdir -p "build-fuzz/corpus/$t" "build-fuzz/crashes/$t"
  (cd "build-fuzz/crashes/$t" && "../../${t}_fuzz" -max_total_time="$SECONDS_EACH" -fork=1 \
     -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 -timeout=20 -rss_limit_mb=2048 \
     -print_final_stats=1 "../../corpus/$t" "../../../fuzz/corpus/$t") >"$log" 2>&1 || true
  local ours=0 hdf5=0 f rlog
  for f in "build-fuzz/crashes/$t"/crash-* "build-fuzz/crashes/$t"/timeout-* \
           "build-fuzz/crashes/$t"/oom-* "build-fuzz/crashes/$t"/leak-*; do
    [ -e "$f" ] || continue
    rlog="$f.replay"
    "build-fuzz/${t}_fuzz" -timeout=20 -rss_limit_mb=2048 "$f" >"$rlog" 2>&1 && continue  # no longer reproduces
    if [ "$(first_frame "$rlog")" = libhdf5 ]; then
      hdf5=$((hdf5 + 1))
    else
      ours=$((ours + 1))
      echo "fuzz $t: FINDING $f (see $rlog)"
    fi
  done
  local rate cov corp
  rate=$(grep -o 'exec/s:\? [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || echo "?")
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo "?")
  corp=$(grep -o 'corp: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo "?")
  echo "fuzz $t: ${SECONDS_EACH}s, ${rate:-?} executions/s at the end, coverage $cov edges, corpus $corp inputs," \
       "findings: $ours ours, $hdf5 inside libhdf5" | tee "$summary"
  [ "$ours" -eq 0 ]
}
status=0
pids=()
for t in "${TARGETS[@]}"; do
  fuzz_one "$t" &
  pids+=($!)
  if [ ${#pids[@]} -ge "$JOBS" ]; then
    wait "${pids[0]}" || status=1
    pids=("${pids[@]:1}")
  fi
done
for p in "${pids[@]}"; do wait "$p" || status=1; done
exit $status
