#!/bin/bash
# The device check (issue 45 item 3): the same frames through EGL on a GPU and through the CPU
# caster, side by side, at 1920x1080 on a 256³ series; their ΔE against each other and the ratio
# of their frame times; then `bench`'s zero-tolerance rows (Table 3) on each back end.
#
#   bench/gpu_check.sh [FILE.tsp]        (default: a generated 256³ × 4-step shock)
#
# Run it where a GPU is (the device tool's machine: `bash scripts/build.sh && bash
# bench/gpu_check.sh`); without one, `--gl egl` falls back to Mesa's software device and the
# script says so. Environment: TSPPLAY (default build/tspplay), SIZE (1920x1080), STEPS (0:3).
set -euo pipefail
cd "$(dirname "$0")/.."
tspplay=$(realpath "${TSPPLAY:-build/tspplay}")
size=${SIZE:-1920x1080}
steps=${STEPS:-0:3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

file=${1:-}
if [ -z "$file" ]; then
  echo "== generating a 256³ × 4-step shock"
  "$tspplay" generate shock --dims 256 --steps 4 -o "$work/shock.h5" >/dev/null
  "$tspplay" build "$work/shock.h5" --field shock -o "$work/shock.tsp" >/dev/null
  file=$work/shock.tsp
fi

echo "== the GPU, as the driver names it"
if command -v nvidia-smi >/dev/null; then nvidia-smi -L; else echo "(no nvidia-smi)"; fi

run() {  # NAME OPTIONS...: render into $work/NAME, passes 2 (the second times warm frames)
  local name=$1
  shift
  "$tspplay" render "$file" --steps "$steps" --size "$size" --passes 2 --reuse off "$@" \
    -o "$work/$name" >/dev/null
  python3 - "$work/$name/frames.json" "$name" <<'EOF'
import json, statistics, sys
j = json.load(open(sys.argv[1]))
ms = [f["ms"] for f in j["frames"] if f.get("pass", 1) == 2]
print(f"{sys.argv[2]:>4}: median {statistics.median(ms):9.2f} ms  caster {j['frames'][-1].get('caster')}"
      f"  context {j.get('context')}  renderer {j.get('renderer')}")
EOF
}

echo "== one render, two back ends ($size, steps $steps, lit defaults)"
run gpu --gl egl --backend gl
run cpu --gl osmesa --backend cpu

echo "== their pictures against each other (mean / p99 / max ΔE L*u*v*)"
for png in "$work"/gpu/step_*.png; do
  "$tspplay" diff "$png" "$work/cpu/$(basename "$png")" | tail -1 | sed "s|^|$(basename "$png"): |"
done
python3 - "$work/gpu/frames.json" "$work/cpu/frames.json" <<'EOF'
import json, statistics, sys
med = [statistics.median(f["ms"] for f in json.load(open(p))["frames"] if f.get("pass", 1) == 2)
       for p in sys.argv[1:]]
print(f"GPU (EGL) frame is {med[1] / med[0]:.2f}x the CPU caster's speed")
EOF

echo "== bench Table 3 (zero tolerance) with EGL and with OSMesa (auto: the GL caster on a GPU, else the CPU caster)"
for backend in gl cpu; do
  gl=egl
  [ $backend = cpu ] && gl=osmesa
  "$tspplay" bench "$file" --steps "$steps" --size 640x480 --gl $gl --targets 1 \
    -o "$work/bench_$backend" >/dev/null 2>&1 || echo "bench on $backend failed"
  python3 - "$work/bench_$backend/report.json" "$backend" <<'EOF' || true
import json, sys
j = json.load(open(sys.argv[1]))
for r in j.get("table3", []):
    print(sys.argv[2], {k: r[k] for k in r if k in ("renderer", "metric", "cache", "median_ms")})
EOF
done
