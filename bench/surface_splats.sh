#!/usr/bin/env bash
# TetSplat's Table 1 on our meshes (issue 31 item 2): the boundary drawn as splats, frame time
# and splats drawn against the minimum splat size, as a ratio to drawing every leaf triangle
# (minimum 0) in the same run. With no probe the boundary hides the volume, so the frame is the
# surface pass.
#   bench/surface_splats.sh MESH FIELD [SURFACE_FIELD]
# MESH is any build input (a .vtu, .vtu.series, 'can_%d.hdf', ...); "sphere:N" makes a dense
# one first (bench/sphere_mesh.py: the hexahedra of an N^3 grid inside a ball, fields d and x).
# Env: TSPPLAY (build/tspplay), SIZE (1280x800), PXS ("0 2 4 8 16 32"), PASSES (4), STEP (0),
#      OUT (a temporary folder, removed unless set).
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,9p' "$0"; exit 2; }
mesh=$1 field=$2 sfield=${3:-$2}
tspplay=${TSPPLAY:-build/tspplay}
size=${SIZE:-1280x800}
pxs=${PXS:-"0 2 4 8 16 32"}
passes=${PASSES:-4}
step=${STEP:-0}
if [ -n "${OUT:-}" ]; then out=$OUT; mkdir -p "$out"; else out=$(mktemp -d); trap 'rm -rf "$out"' EXIT; fi
if [[ $mesh == sphere:* ]]; then
  /usr/bin/python3 "$(dirname "$0")/sphere_mesh.py" "${mesh#sphere:}" "$out/sphere.vtu" >/dev/null
  mesh=$out/sphere.vtu
fi
"$tspplay" build "$mesh" --field "$field" --resolution 64 -o "$out/m.tsp" >/dev/null
for px in $pxs; do
  "$tspplay" render "$out/m.tsp" --steps "$step" --passes "$passes" --size "$size" \
    --surface boundary --surface-mesh "$mesh" --surface-field "$sfield" --surface-px "$px" \
    -o "$out/px$px" >/dev/null
done
python3 - "$out" "$mesh" "$size" "$pxs" <<'PY'
import json, statistics, sys
out, mesh, size, pxs = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4].split()
rows = []
for px in pxs:
    frames = json.load(open(f"{out}/px{px}/frames.json"))["frames"]
    later = [f for f in frames if f["pass"] > 1]  # the first pass compiles and reads
    rows.append((px, later[-1]["surface_splats"], statistics.median(f["surface_ms"] for f in later),
                 statistics.median(f["ms"] for f in later)))
base = rows[0]
print(f"{mesh} at {size}: the boundary as splats, median of passes 2.., ratio to minimum {base[0]} px")
print(f"{'min px':>7} {'splats':>8} {'surface ms':>11} {'frame ms':>9} {'frames/s':>9} {'speed-up':>9}")
for px, n, sms, ms in rows:
    print(f"{px:>7} {n:>8} {sms:>11.1f} {ms:>9.1f} {1000 / ms:>9.1f} {base[3] / ms:>8.2f}x")
PY
