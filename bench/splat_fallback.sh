#!/usr/bin/env bash
# The splat fallback (issue 14 item 4) against what it replaces, in one run:
#  1. fixed cuts at one size: the coarsest textured cut (--lod K, K the top level) against splat
#     cuts of several minimum splat sizes — median frame ms, the ratio to the coarsest cut, and
#     mean ΔE against full resolution (the last step's frame);
#  2. the controller under a target below the coarsest cut: --lod-fallback scale against splats —
#     median frame ms of the second pass, its share of the target, and mean ΔE of the last frame.
#   bench/splat_fallback.sh FILE.tsp [STEPS A:B] [SIZE WxH] [TARGETS_MS...]
#     (defaults 0:15, 1280x800, 20 10)
# Env: TSPPLAY (default build/tspplay), TF (default preset:filled), PASSES (default 3).
set -euo pipefail
[ $# -ge 1 ] || { sed -n '2,11p' "$0"; exit 2; }
file=$1
steps=${2:-0:15}
size=${3:-1280x800}
shift $(( $# < 3 ? $# : 3 ))
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(20 10)
tspplay=${TSPPLAY:-build/tspplay}
tf=${TF:-preset:filled}
passes=${PASSES:-3}
last=${steps#*:}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
top=$("$tspplay" info "$file" --json | python3 -c "import json,sys; print(len(json.load(sys.stdin)['lod_levels']) - 1)")

# median ms over the passes after the first, and the share of the target; writes $out/$1
run() {
  local name=$1
  shift
  "$tspplay" render "$file" --tf "$tf" --steps "$steps" --size "$size" --passes "$passes" "$@" \
    -o "$out/$name" >/dev/null
  python3 -c "
import json, statistics
f = [x for x in json.load(open('$out/$name/frames.json'))['frames'] if x['pass'] > 1]
print(statistics.median(x['ms'] for x in f))"
}
delta_e() {
  "$tspplay" diff "$out/full/step_$(printf %04d "$last").png" \
    "$out/$1/step_$(printf %04d "$last").png" --json |
    python3 -c "import json,sys; print(round(json.load(sys.stdin)['mean'], 2))"
}

echo "file $file, TF $tf, steps $steps, $size, $passes passes (medians of passes 2..)"
full=$(run full)
coarse=$(run coarsest --lod "$top")
printf 'full resolution: %.1f ms\n' "$full"
printf 'coarsest textured cut (--lod %s): %.1f ms, mean dE %s\n' "$top" "$coarse" "$(delta_e coarsest)"
for px in 100000 200 100 50 0; do
  ms=$(run "splat$px" --lod "splat:$px")
  splats=$(python3 -c "import json; print(json.load(open('$out/splat$px/frames.json'))['frames'][-1]['lod']['splats'])")
  printf 'splats, minimum %s px (%s splats): %.1f ms, %.2fx faster than the coarsest cut, mean dE %s\n' \
    "$px" "$splats" "$ms" "$(python3 -c "print($coarse / $ms)")" "$(delta_e "splat$px")"
done
for target in "${targets[@]}"; do
  for fb in scale splats; do
    ms=$(run "$fb$target" --target-ms "$target" --lod-fallback "$fb")
    printf 'target %s ms, fallback %s: median %.1f ms (%.0f %% of the target), mean dE %s\n' \
      "$target" "$fb" "$ms" "$(python3 -c "print(100 * $ms / $target)")" "$(delta_e "$fb$target")"
  done
done
