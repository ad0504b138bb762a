#!/usr/bin/env bash
# Playback from a cold page cache under read-bandwidth limits: OTHER.tsp against BASELINE.tsp
# (e.g. built with and without --compress), steps/s over the rendered frames, and their ratio.
#   bench/cold_playback.sh BASELINE.tsp OTHER.tsp [MIB_PER_S ...]   (default: 0 200 100 50)
# 0 = no limit. A limit needs root and cgroup v1's blkio controller (the kernel throttles this
# script's reads from the disk holding the files); each run first drops the file's pages
# (dd iflag=nocache). Env: TSPPLAY (default build/tspplay), TF (default preset:filled), ROUNDS (2).
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,7p' "$0"; exit 2; }
base=$1 other=$2
shift 2
limits=("$@")
[ ${#limits[@]} -gt 0 ] || limits=(0 200 100 50)
tspplay=${TSPPLAY:-build/tspplay}
tf=${TF:-preset:filled}
rounds=${ROUNDS:-2}
cg=/sys/fs/cgroup/blkio/tspplay-cold-playback
dev=$(stat -c '%d' "$base")
dev="$((dev >> 8)):$((dev & 255))"
out=$(mktemp -d)
trap 'rm -rf "$out"; [ -d "$cg" ] && echo "$dev 0" > "$cg/blkio.throttle.read_bps_device" || true' EXIT

# steps/s of one cold run of FILE, in the throttled group when it exists
steps_per_s() {
  dd if="$1" iflag=nocache count=0 2>/dev/null
  bash -c "[ -d '$cg' ] && echo \$\$ > '$cg/tasks'; exec '$tspplay' render '$1' --tf '$tf' -o '$out/r'" \
    >/dev/null 2>&1
  python3 -c "
import json
f = json.load(open('$out/r/frames.json'))['frames']
print('%.3f' % (len(f) / (sum(x['ms'] for x in f) / 1000)))"
}

for bw in "${limits[@]}"; do
  if [ "$bw" != 0 ]; then
    mkdir -p "$cg" || { echo "$0: no cgroup v1 blkio controller (a limit needs it)" >&2; exit 1; }
    echo "$dev $((bw * 1048576))" > "$cg/blkio.throttle.read_bps_device"
  elif [ -d "$cg" ]; then
    echo "$dev 0" > "$cg/blkio.throttle.read_bps_device"
  fi
  b=() o=()
  for ((r = 0; r < rounds; ++r)); do
    b+=("$(steps_per_s "$base")")
    o+=("$(steps_per_s "$other")")
  done
  python3 -c "
b = [float(x) for x in '${b[*]}'.split()]; o = [float(x) for x in '${o[*]}'.split()]
mb, mo = sorted(b)[len(b) // 2], sorted(o)[len(o) // 2]
lim = 'none' if '$bw' == '0' else '$bw MiB/s'
print(f'read limit {lim}: baseline {b} steps/s, other {o} steps/s, other/baseline {mo / mb:.2f}x')"
done
