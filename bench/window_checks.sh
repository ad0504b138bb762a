#!/usr/bin/env bash
# The window's other targets of issue 27, measured on FILE in a real GLFW window under Xvfb:
#  - quality slider: `quality Q` while playing (tuning in the window's frames): frames drawn per
#    second while it tunes, seconds to tune, and seconds from the end of tuning to a tuned rung
#    drawn (the player's own `tuning` and `playback` stats);
#  - paused: seconds from the last input (pause) to a full-quality frame (`lod.full_quality_after_s`);
#  - idle: CPU time of the process over IDLE_SECONDS with nothing changing (% of one core, from
#    /proc/PID/stat);
#  - recording: `record m.mp4` held for RECORD_SECONDS of wall time while playing; ffprobe's
#    duration of the movie against that time.
#   bench/window_checks.sh FILE.tsp [extra play options...]
# Env: TSPPLAY (build/tspplay), SIZE (1280x800), TF (preset:filled), QUALITY (1),
#      IDLE_SECONDS (5), RECORD_SECONDS (10), OUT (a temporary folder, removed unless set).
set -euo pipefail
[ $# -ge 1 ] || { sed -n '2,13p' "$0"; exit 2; }
file=$1
shift
tspplay=${TSPPLAY:-build/tspplay}
size=${SIZE:-1280x800}
tf=${TF:-preset:filled}
quality=${QUALITY:-1}
idle_s=${IDLE_SECONDS:-5}
record_s=${RECORD_SECONDS:-10}
if [ -n "${OUT:-}" ]; then out=$OUT; mkdir -p "$out"; else out=$(mktemp -d); trap 'rm -rf "$out"' EXIT; fi
w=${size%x*} h=${size#*x}
rm -f "$out"/*.json "$out"/m.mp4 "$out"/ready

# The script: tune while playing (the window drawing), play, pause, let it refine, signal the
# idle measurement, wait, then record while playing. `wait-seconds` runs frames (or sleeps when
# nothing changes), so the wall time between two actions is the time asked.
cat > "$out/script.txt" <<EOF
panels off
speed 24
quality 0
play
wait-seconds 1
stats $out/before.json
quality $quality
stats $out/tuned.json
wait-seconds 2
stats $out/playing.json
pause
wait-seconds 1.5
stats $out/paused.json
screenshot $out/ready.png
wait-seconds $((idle_s + 3))
play
record $out/m.mp4
wait-seconds $record_s
record stop
stats $out/recorded.json
quit
EOF
# (`quality` blocks the script, not the window: the window keeps drawing frames while it tunes.)
xvfb-run -a -s "-screen 0 ${w}x${h}x24 -noreset" "$tspplay" play "$file" --tf "$tf" \
  --size "$size" --script "$out/script.txt" "$@" > "$out/play.log" 2>&1 &
pid=$!
# the idle window: the screenshot after the pause marks the start
for _ in $(seq 600); do [ -s "$out/ready.png" ] && break; sleep 0.1; done
sleep 1
player=$(pgrep -n -f "tspplay play $file" || true)
a=$(awk '{print $14+$15}' "/proc/$player/stat")
sleep "$idle_s"
b=$(awk '{print $14+$15}' "/proc/$player/stat")
wait "$pid" || { echo "$0: play failed:"; tail -5 "$out/play.log"; exit 1; } >&2
tck=$(getconf CLK_TCK)
movie_s=$(ffprobe -v error -show_entries format=duration -of csv=p=0 "$out/m.mp4")

python3 - "$out" "$file" "$size" "$tf" "$quality" "$((b - a))" "$tck" "$idle_s" "$movie_s" "$record_s" <<'PY'
import json, sys
out, file, size, tf, quality, ticks, tck, idle_s, movie_s, record_s = sys.argv[1:]
j = lambda n: json.load(open(f"{out}/{n}.json"))
tuned, playing, paused = j("tuned"), j("playing"), j("paused")
t = tuned["tuning"]
print(f"{file} at {size}, {tf}, quality {quality}")
print(f"  quality slider: tuned in {t['seconds']:.1f} s, {t['frames_while_tuning']} frames drawn meanwhile "
      f"({t['frames_while_tuning'] / max(t['seconds'], 1e-9):.1f} frames/s); 2 s later playing "
      f"'{playing['playback']['rung']['name']}' at {playing['fps']:.1f} frames/s")
print(f"  paused: full quality {paused['lod']['full_quality_after_s']:.2f} s after the pause "
      f"(full_quality {paused['lod']['full_quality']})")
print(f"  idle: {int(ticks) / int(tck) / float(idle_s) * 100:.1f} % of a core over {idle_s} s")
print(f"  recording: {float(record_s):.1f} s of wall time -> movie of {float(movie_s):.3f} s")
PY
