#!/usr/bin/env bash
# tspplay-mpi render against the serial render (issue 45 item 2): one movie of STEPS steps at
# SIZE, rendered and encoded by `tspplay render` and by `mpirun -np N tspplay-mpi render` for each
# N; prints each wall time, its ratio to the serial time, and checks the PNGs are the same bytes.
#   bench/mpi_render.sh [FILE.tsp] [RANKS...]     (default: a generated 64-step shock; 2 3)
# Env: TSPPLAY, TSPPLAY_MPI (default build/tspplay, build/tspplay-mpi), SIZE (640x480), STEPS
# (64, for the generated file), DIMS (64), OPTIONS (more render options, default "--tf
# preset:filled"), MPIRUN (default mpirun --oversubscribe, and --allow-run-as-root as root).
set -euo pipefail
tspplay=${TSPPLAY:-build/tspplay}
tspplay_mpi=${TSPPLAY_MPI:-build/tspplay-mpi}
size=${SIZE:-640x480}
options=${OPTIONS:---tf preset:filled}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ $# -ge 1 ] && [ "${1%.tsp}" != "$1" ]; then
  file=$1
  shift
else
  file=$work/shock.tsp
  "$tspplay" generate shock --dims "${DIMS:-64}" --steps "${STEPS:-64}" -o "$work/shock.h5" >/dev/null
  "$tspplay" build "$work/shock.h5" -o "$file" >/dev/null
fi
ranks=("$@")
[ ${#ranks[@]} -gt 0 ] || ranks=(2 3)
mpirun=${MPIRUN:-mpirun --oversubscribe$([ "$(id -u)" = 0 ] && echo " --allow-run-as-root")}

seconds() {  # wall seconds of "$@", its output dropped
  local t0 t1
  t0=$(date +%s.%N)
  "$@" >/dev/null
  t1=$(date +%s.%N)
  python3 -c "print(f'{$t1 - $t0:.2f}')"
}

# shellcheck disable=SC2086  # options and mpirun are word lists
{
  steps=$("$tspplay" info "$file" --json | python3 -c "import json,sys; print(json.load(sys.stdin)['steps'])")
  echo "file $file ($steps steps), $size, $options, movie .mp4; $(nproc) cores"
  serial=$(seconds "$tspplay" render "$file" --size "$size" $options -o "$work/serial" --movie "$work/serial.mp4")
  echo "serial tspplay render: $serial s"
  for n in "${ranks[@]}"; do
    t=$(seconds $mpirun -np "$n" "$tspplay_mpi" render "$file" --size "$size" $options \
      -o "$work/mpi$n" --movie "$work/mpi$n.mp4")
    same=same
    for png in "$work/serial"/step_*.png; do
      cmp -s "$png" "$work/mpi$n/$(basename "$png")" || same=DIFFERENT
    done
    echo "mpirun -np $n tspplay-mpi render: $t s, $(python3 -c "print(f'{$serial / $t:.2f}')")x the serial speed; PNGs $same bytes"
  done
}
