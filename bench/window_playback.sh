#!/usr/bin/env bash
# Playing in the window (issue 27's targets): `tspplay play` in a real GLFW window under Xvfb,
# panels hidden, playing at SPEED steps/s for SECONDS, against the same window playing at full
# quality every frame (--quality 0 --lod off: the baseline, measured in the same run). For each:
# frames/s and distinct steps shown per second (the player's own stats, sampled every
# SECONDS/SHOTS), and screenshots taken *while playing* compared with `tspplay render` of the
# same step at full quality (held-out pictures: not the tuning's probe steps' frames).
#   bench/window_playback.sh FILE.tsp [extra play options...]
# Env: TSPPLAY (build/tspplay), SIZE (1280x800), TF (preset:filled), SPEED (24), PLAY_SECONDS (10),
#      SHOTS (5), QUALITY (1), SHADE (on: play's default lighting; the references are rendered
#      with the same), OUT (a temporary folder, removed unless set).
set -euo pipefail
[ $# -ge 1 ] || { sed -n '2,12p' "$0"; exit 2; }
file=$1
shift
tspplay=${TSPPLAY:-build/tspplay}
size=${SIZE:-1280x800}
tf=${TF:-preset:filled}
speed=${SPEED:-24}
seconds=${PLAY_SECONDS:-10}
shots=${SHOTS:-5}
quality=${QUALITY:-1}
shade=${SHADE:-on}
if [ -n "${OUT:-}" ]; then out=$OUT; mkdir -p "$out"; else out=$(mktemp -d); trap 'rm -rf "$out"' EXIT; fi
w=${size%x*} h=${size#*x}

# play LABEL QUALITY OPTIONS...: one window session (`quality` first: it waits for the tuning);
# writes $out/LABEL/{play.log,stats_*.json,shot_*.png}
play() {
  local label=$1 q=$2
  shift 2
  local dir=$out/$label
  mkdir -p "$dir"
  {
    echo "panels off"
    echo "speed $speed"
    echo "quality $q"
    echo "play"
    echo "wait-seconds 1"
    local wait
    wait=$(python3 -c "print($seconds / $shots)")
    for ((i = 0; i < shots; ++i)); do
      echo "wait-seconds $wait"
      echo "screenshot $dir/shot_$i.png"
      echo "stats $dir/stats_$i.json"
    done
    echo "quit"
  } > "$dir/script.txt"
  xvfb-run -a -s "-screen 0 ${w}x${h}x24 -noreset" "$tspplay" play "$file" --tf "$tf" \
    --size "$size" --shade "$shade" --script "$dir/script.txt" "$@" > "$dir/play.log" 2>&1 ||
    { echo "$0: play $label failed:"; tail -5 "$dir/play.log"; exit 1; } >&2
}

# the full-quality render of each screenshot's step, and their difference
compare() {
  local dir=$out/$1
  grep -o 'saved [^ ]*shot_[0-9]*\.png (step [0-9]*)' "$dir/play.log" | while read -r _ png _ step; do
    step=${step%)}
    "$tspplay" render "$file" --tf "$tf" --size "$size" --shade "$shade" --steps "$step" \
      -o "$dir/ref_$step" >/dev/null 2>&1
    local ref
    ref=$(ls "$dir/ref_$step"/*.png | head -1)
    printf '%s %s ' "$step" "$png"
    "$tspplay" diff "$png" "$ref" --json | python3 -c "import json,sys; d=json.load(sys.stdin); print(d['mean'], d['p99'])"
  done > "$dir/diffs.txt"
}

play tuned "$quality" "$@"
play baseline 0 --lod off "$@"
compare tuned
compare baseline

python3 - "$out" "$file" "$size" "$tf" "$speed" "$quality" <<'EOF'
import glob, json, sys
out, file, size, tf, speed, quality = sys.argv[1:]
def summary(label):
    stats = [json.load(open(p)) for p in sorted(glob.glob(f"{out}/{label}/stats_*.json"))]
    diffs = [l.split() for l in open(f"{out}/{label}/diffs.txt") if l.strip()]
    fps = sum(s["fps"] for s in stats) / len(stats)
    shown = sum(s["playback"]["steps_shown_per_s"] for s in stats) / len(stats)
    de = [float(d[2]) for d in diffs]
    p99 = [float(d[3]) for d in diffs]
    rung = stats[-1]["playback"].get("rung", {})
    return fps, shown, de, p99, rung, stats[-1]
t = summary("tuned")
b = summary("baseline")
print(f"{file} at {size}, {tf}, speed {speed} steps/s, quality target {quality}")
for name, s in (("tuned", t), ("baseline (full quality)", b)):
    fps, shown, de, p99, rung, last = s
    print(f"  {name:24s} {fps:6.1f} frames/s  {shown:5.1f} steps shown/s  "
          f"mean dE of shots {sum(de)/len(de):.2f} (max {max(de):.2f}, p99 up to {max(p99):.1f})"
          + (f"  rung '{rung.get('name')}' predicted dE {rung.get('predicted_de'):.2f}" if rung else ""))
print(f"  tuned / baseline: {t[0]/max(b[0],1e-9):.2f}x frames/s, {t[1]/max(b[1],1e-9):.2f}x steps shown/s")
ladder = t[5]["playback"].get("ladder", [])
if ladder:
    print("  ladder (probe ms, mean dE, frames played):",
          "; ".join(f"{r['name']}: {r['probe_ms']:.0f} ms, {r['mean_de']:.2f}, {r['frames']}" for r in ladder))
EOF
