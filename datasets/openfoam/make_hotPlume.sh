#!/usr/bin/env bash
# Makes OUTDIR/hotPlume.h5: runs the OpenFOAM case datasets/openfoam/hotPlume (blockMesh,
# topoSet, buoyantBoussinesqPimpleFoam on one process at nice 19) in a scratch copy under
# OUTDIR and imports the temperature T of every written time with foam_to_h5.py.
#
# Usage: make_hotPlume.sh OUTDIR [--keep]
#   --keep   keep the run directory OUTDIR/hotPlume.run (about 1.5 GB of ASCII fields)
# Needs: Debian openfoam (v1912), python3 with numpy and h5py (python3-numpy python3-h5py).
# Environment: PYTHON (interpreter with numpy + h5py; default: the first of python3,
# /usr/bin/python3 that has them), FOAM_BASHRC (default /usr/share/openfoam/etc/bashrc).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
case_name=hotPlume
usage() { echo "usage: $0 OUTDIR [--keep]" >&2; exit 2; }
[ $# -ge 1 ] || usage
out_dir="$1"
keep=0
[ $# -ge 2 ] && { [ "$2" = "--keep" ] && keep=1 || usage; }

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
if [ -z "${PYTHON:-}" ]; then
  echo "$0: no python3 with numpy and h5py (apt-get install python3-numpy python3-h5py)" >&2
  exit 1
fi

bashrc="${FOAM_BASHRC:-/usr/share/openfoam/etc/bashrc}"
[ -f "$bashrc" ] || { echo "$0: $bashrc not found (apt-get install openfoam)" >&2; exit 1; }
# Debian's bashrc complains about helper scripts it does not ship; the variables it sets
# (WM_PROJECT_DIR, ...) are all the solvers need.
set +u
# shellcheck disable=SC1090
source "$bashrc" >/dev/null 2>&1 || true
set -u
if ! command -v buoyantBoussinesqPimpleFoam >/dev/null; then
  echo "$0: OpenFOAM solvers not on PATH after sourcing $bashrc" >&2
  exit 1
fi

rm -rf "$run_dir"
mkdir -p "$run_dir"
cp -r "$here/$case_name/0" "$here/$case_name/constant" "$here/$case_name/system" "$run_dir/"
cd "$run_dir"

stage() {  # stage NAME COMMAND...: runs COMMAND at nice 19, logs to log.NAME, prints the time
  local name="$1"; shift
  local t0=$SECONDS
  if ! nice -n 19 "$@" >"log.$name" 2>&1; then
    echo "$0: $name failed; see $run_dir/log.$name" >&2
    tail -20 "log.$name" >&2
    exit 1
  fi
  echo "$name: $((SECONDS - t0)) s" >&2
}

stage blockMesh blockMesh
stage topoSet topoSet
# Cell centres in 0/C let the importer check the cell order against the lattice.
stage cellCentres postProcess -func writeCellCentres -time 0
stage solver buoyantBoussinesqPimpleFoam
stage import "$PYTHON" "$here/foam_to_h5.py" . -o "$out_dir/$case_name.h5" --field T \
  --case-name "$case_name"

if [ "$keep" -eq 0 ]; then
  cd "$out_dir"
  rm -rf "$run_dir"
fi
echo "wrote $out_dir/$case_name.h5" >&2
