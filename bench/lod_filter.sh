#!/usr/bin/env bash
# LaMar's selection filters (issue 31 item 4) against full resolution, in one run: for a camera
# inside the volume (--eye) and the orbit camera in perspective, the median frame ms of the
# filter's cut, its ratio to the full-resolution frame of the same view (the baseline, measured
# in the same run), its cut size and nodes per level, and its mean ΔE against full resolution
# (the last step's frame).
#   bench/lod_filter.sh FILE.tsp EYE_X,Y,Z [STEPS A:B] [SIZE WxH] [VIEW AZ,EL]
#     (defaults 0:7, 640x480, 30,10)
# Env: TSPPLAY (default build/tspplay), TF (default preset:auto), PASSES (default 3),
#      KS (the filters' factors, default "0.5 1 2 4").
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,11p' "$0"; exit 2; }
file=$1
eye=$2
steps=${3:-0:7}
size=${4:-640x480}
view=${5:-30,10}
tspplay=${TSPPLAY:-build/tspplay}
tf=${TF:-preset:auto}
passes=${PASSES:-3}
read -r -a ks <<< "${KS:-0.5 1 2 4}"
last=${steps#*:}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# median ms over the passes after the first; writes $out/$1
run() {
  local name=$1
  shift
  "$tspplay" render "$file" --tf "$tf" --steps "$steps" --size "$size" --view "$view" \
    --passes "$passes" "$@" -o "$out/$name" >/dev/null
  python3 -c "
import json, statistics
f = [x for x in json.load(open('$out/$name/frames.json'))['frames'] if x['pass'] > 1]
print(statistics.median(x['ms'] for x in f))"
}
delta_e() {  # mean ΔE of $2 against $1 at the last step
  "$tspplay" diff "$out/$1/step_$(printf %04d "$last").png" \
    "$out/$2/step_$(printf %04d "$last").png" --json |
    python3 -c "import json,sys; print(round(json.load(sys.stdin)['mean'], 2))"
}
cut() {
  python3 -c "
import json
l = json.load(open('$out/$1/frames.json'))['frames'][-1]['lod']
print(l['cut_size'], 'nodes, by level', l['nodes_per_level'])"
}

echo "file $file, TF $tf, steps $steps, $size, view $view, $passes passes (medians of passes 2..)"
for camera in eye orbit; do
  if [ "$camera" = eye ]; then
    opts=(--eye "$eye")
    filters=(distance fov)
    echo "camera inside the volume: --eye $eye"
  else
    opts=(--perspective)
    filters=(fov distance)
    echo "orbit camera, perspective"
  fi
  full=$(run "full_$camera" "${opts[@]}")
  printf '  full resolution: %.1f ms\n' "$full"
  for f in "${filters[@]}"; do
    for k in "${ks[@]}"; do
      name="${camera}_${f}_$k"
      ms=$(run "$name" "${opts[@]}" --lod-filter "$f:$k")
      printf '  %s:%s: %.1f ms, %.2fx faster than full resolution, mean dE %s; cut %s\n' \
        "$f" "$k" "$ms" "$(python3 -c "print($full / $ms)")" "$(delta_e "full_$camera" "$name")" \
        "$(cut "$name")"
    done
  done
done
