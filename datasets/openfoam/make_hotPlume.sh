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
# shellcheck source=foam_case.sh
source "$here/foam_case.sh"
foam_case_args "$@"
foam_python
foam_load buoyantBoussinesqPimpleFoam

rm -rf "$run_dir"
mkdir -p "$run_dir"
cp -r "$here/$case_name/0" "$here/$case_name/constant" "$here/$case_name/system" "$run_dir/"
cd "$run_dir"

stage blockMesh blockMesh
stage topoSet topoSet
# Cell centres in 0/C let the importer check the cell order against the lattice.
stage cellCentres postProcess -func writeCellCentres -time 0
stage solver buoyantBoussinesqPimpleFoam
stage import "$PYTHON" "$here/foam_to_h5.py" . -o "$out_dir/$case_name.h5" --field T \
  --case-name "$case_name"

foam_finish
