#!/usr/bin/env bash
# Leven's Fig. 14 on our meshes (issue 31 item 1): the adaptive octree's size and build time
# against the threshold E, and its picture against the uniform build of the same finest grid,
# built and rendered in the same run (the baseline: ratios adaptive / uniform).
#   bench/adaptive_octree.sh MESH FIELD RESOLUTION
# MESH is any mesh input (a .vtu, .vtu.series, 'can_%d.hdf', ...); "graded:N:R:T[:SIGMA[:CX,CY,CZ]]"
# makes one first (bench/graded_mesh.py: an N^3 hexahedral grid whose central 2^3 cells are split R^3,
# T steps, field f, a Gaussian of width SIGMA about the centre C). RESOLUTION is the finest grid's longest edge; UNIFORM=0 skips the uniform build (for
# grids it cannot hold), and then only the adaptive rows are printed, with each build's peak
# memory.
# Env: TSPPLAY (build/tspplay), BUILD_ARGS (more build options for both builds, e.g.
#      "--brick 16"), ERRORS ("0 0.1% 1% 5% 20%"), SIZE (640x480), TF (preset:filled),
#      UNIFORM (1), OUT (a temporary folder, removed unless set).
set -euo pipefail
[ $# -ge 3 ] || { sed -n '2,13p' "$0"; exit 2; }
mesh=$1 field=$2 res=$3
tspplay=${TSPPLAY:-build/tspplay}
errors=${ERRORS:-"0 0.1% 1% 5% 20%"}
size=${SIZE:-640x480}
uniform=${UNIFORM:-1}
if [ -n "${OUT:-}" ]; then out=$OUT; mkdir -p "$out"; else out=$(mktemp -d); trap 'rm -rf "$out"' EXIT; fi
if [[ $mesh == graded:* ]]; then
  IFS=: read -r _ n r t sigma centre <<<"$mesh"
  /usr/bin/python3 "$(dirname "$0")/graded_mesh.py" "$n" "$r" "$t" "$out/graded" $sigma $centre >/dev/null
  mesh=$out/graded/graded.vtu.series
fi
timed() {  # timed NAME CMD...: runs CMD, keeps its output and "seconds peak-KiB" in NAME.*
  local name=$1; shift
  /usr/bin/time -f "%e %M" -o "$out/$name.time" "$@" >"$out/$name.log" 2>&1 || { cat "$out/$name.log"; exit 1; }
}
view="--size $size --tf ${TF:-preset:filled}"
if [ "$uniform" = 1 ]; then
  timed uniform "$tspplay" build "$mesh" --field "$field" --resolution "$res" ${BUILD_ARGS:-} -o "$out/uniform.tsp"
  # The same value range for every picture: the uniform file's.
  range=$(/usr/bin/python3 -c "import h5py,sys; f=h5py.File(sys.argv[1]); print('%r:%r' % tuple(f.attrs['value_range']))" "$out/uniform.tsp")
  "$tspplay" render "$out/uniform.tsp" $view --tf-range "$range" -o "$out/r_uniform" >/dev/null
fi
k=0
for e in $errors; do
  timed "a$k" "$tspplay" build "$mesh" --field "$field" --resolution "$res" ${BUILD_ARGS:-} --octree-error "$e" -o "$out/a$k.tsp"
  if [ "$uniform" = 1 ]; then
    "$tspplay" render "$out/a$k.tsp" $view --tf-range "$range" -o "$out/r_a$k" >/dev/null
  fi
  k=$((k + 1))
done
python3 - "$out" "$mesh" "$res" "$uniform" $errors <<'PY'
import glob, json, os, re, subprocess, sys
out, mesh, res, uniform, errors = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4] == "1", sys.argv[5:]
tspplay = os.environ.get("TSPPLAY", "build/tspplay")
def timing(name):
    s, kib = open(f"{out}/{name}.time").read().split()[-2:]
    return float(s), int(kib) / 1024
def mb(path):
    return os.path.getsize(path) / 1e6
def delta(a, b):
    worst = None
    for pa in sorted(glob.glob(f"{out}/{a}/step_*.png")):
        d = json.loads(subprocess.run([tspplay, "diff", pa, pa.replace(a, b), "--json"],
                                      capture_output=True, text=True, check=True).stdout)
        worst = d if worst is None or d["mean"] > worst["mean"] else worst
    return worst
print(f"{mesh}, finest grid {res} on the longest edge (adaptive vs uniform, same run)")
if uniform:
    us, ukib = timing("uniform")
    print(f"uniform build: {mb(out + '/uniform.tsp'):.1f} MB file, {us:.2f} s, peak {ukib:.0f} MiB")
print(f"{'E':>6} {'nodes':>11} {'stopped':>8} {'file MB':>8} {'size':>7} {'build s':>8} {'time':>7} {'peak MiB':>9}"
      + (f" {'dE mean':>8} {'dE p99':>7}" if uniform else ""))
for k, e in enumerate(errors):
    log = open(f"{out}/a{k}.log").read()
    m = re.search(r"(\d+) of (\d+) nodes hold data, (\d+) stopped", log)
    s, kib = timing(f"a{k}")
    row = f"{e:>6} {m.group(1) + '/' + m.group(2):>11} {m.group(3):>8} {mb(f'{out}/a{k}.tsp'):>8.1f}"
    row += f" {mb(f'{out}/a{k}.tsp') / mb(out + '/uniform.tsp'):>6.2f}x" if uniform else f" {'':>7}"
    row += f" {s:>8.2f}" + (f" {s / us:>6.2f}x" if uniform else f" {'':>7}") + f" {kib:>9.0f}"
    if uniform:
        d = delta("r_uniform", f"r_a{k}")
        row += f" {d['mean']:>8.3f} {d['p99']:>7.2f}"
    print(row)
PY
