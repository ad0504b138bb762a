#!/usr/bin/env bash
# Makes OUTDIR/decayIsoTurb.h5: runs OpenFOAM's LES tutorial of decaying homogeneous isotropic
# turbulence (incompressible/pimpleFoam/LES/decayIsoTurb, Debian openfoam-examples: a 64³
# periodic box, Comte-Bellot & Corrsin initial spectrum) for 0.2 s on one process at nice 19,
# writing every 5th of its 0.001 s steps in ASCII, and imports the pressure p and the subgrid
# kinetic energy k of every written time with foam_to_h5.py (41 steps).
#
# Usage: make_decayIsoTurb.sh OUTDIR [--keep]
#   --keep   keep the run directory OUTDIR/decayIsoTurb.run
# Needs: Debian openfoam (v1912) and openfoam-examples, python3 with numpy and h5py.
# Environment: PYTHON, FOAM_BASHRC, FOAM_EXAMPLES (default
# /usr/share/doc/openfoam-examples/examples).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
case_name=decayIsoTurb
usage() { echo "usage: $0 OUTDIR [--keep]" >&2; exit 2; }
[ $# -ge 1 ] || usage
out_dir="$1"
keep=0
[ $# -ge 2 ] && { [ "$2" = "--keep" ] && keep=1 || usage; }
examples="${FOAM_EXAMPLES:-/usr/share/doc/openfoam-examples/examples}"
tutorial="$examples/incompressible/pimpleFoam/LES/decayIsoTurb"
[ -d "$tutorial" ] || { echo "$0: $tutorial not found (apt-get install openfoam-examples)" >&2; exit 1; }

mkdir -p "$out_dir"
out_dir="$(cd "$out_dir" && pwd)"
run_dir="$out_dir/$case_name.run"

if [ -z "${PYTHON:-}" ]; then
  for p in python3 /usr/bin/python3; do
    if command -v "$p" >/dev/null && "$p" -c 'import numpy, h5py' 2>/dev/null; then
      PYTHON="$p"; break
    fi
  done
fi
[ -n "${PYTHON:-}" ] || { echo "$0: no python3 with numpy and h5py" >&2; exit 1; }

bashrc="${FOAM_BASHRC:-/usr/share/openfoam/etc/bashrc}"
[ -f "$bashrc" ] || { echo "$0: $bashrc not found (apt-get install openfoam)" >&2; exit 1; }
set +u
# shellcheck disable=SC1090
source "$bashrc" >/dev/null 2>&1 || true
set -u
command -v pimpleFoam >/dev/null || { echo "$0: OpenFOAM not on PATH after $bashrc" >&2; exit 1; }

rm -rf "$run_dir"
cp -r "$tutorial" "$run_dir"
cd "$run_dir"
find . -name '*.gz' -exec gunzip {} +
# 0.2 s of the decay (the tutorial runs 1 s), every 5th step, ASCII for the importer.
sed -i 's/^endTime .*/endTime         0.2;/; s/^writeInterval .*/writeInterval   5;/;
        s/^writeFormat .*/writeFormat     ascii;/' system/controlDict
cp -r 0.orig 0

stage() {  # stage NAME COMMAND...: runs COMMAND at nice 19, logs to log.NAME
  local name="$1"; shift
  local t0=$SECONDS
  if ! nice -n 19 "$@" >"log.$name" 2>&1; then
    echo "$0: $name failed; see $run_dir/log.$name" >&2
    tail -20 "log.$name" >&2
    exit 1
  fi
  echo "$name: $((SECONDS - t0)) s"
}
stage mesh createBoxTurb -createBlockMesh   # the 64³ box
stage turbulence createBoxTurb              # the initial velocity field
stage cellCentres postProcess -func writeCellCentres -time 0
stage solver pimpleFoam
stage import "$PYTHON" "$here/foam_to_h5.py" "$run_dir" -o "$out_dir/$case_name.h5" \
  --field p --field k --case-name "$case_name"
[ "$keep" = 1 ] || { cd "$out_dir"; rm -rf "$run_dir"; }
echo "wrote $out_dir/$case_name.h5"
