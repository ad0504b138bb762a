#!/usr/bin/env bash
# Makes OUTDIR/hotRoom/hotRoom.run.vtm.series: runs OpenFOAM's hotRoom tutorial (heatTransfer/
# buoyantBoussinesqPimpleFoam/hotRoom, Debian openfoam-examples: a 10 x 6 x 4 m room of 20 x 10 x
# 20 hexahedra with a heater, buoyancy-driven flow) for its 2000 s on one process at nice 19 and
# writes every 400 s with foamToVTK (T, U, p_rgh; 6 steps, a .vtu per step; 20 s). A hexahedral mesh
# for `tspplay build OUTDIR/hotRoom/*.vtm.series --field T`.
#
# Usage: make_hotRoom.sh OUTDIR [--keep]
#   --keep   keep the run directory OUTDIR/hotRoom.run
# Needs: Debian openfoam (v1912) and openfoam-examples. Environment: FOAM_BASHRC, FOAM_EXAMPLES
# (default /usr/share/doc/openfoam-examples/examples).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
case_name=hotRoom
# shellcheck source=foam_case.sh
source "$here/foam_case.sh"
examples="${FOAM_EXAMPLES:-/usr/share/doc/openfoam-examples/examples}"
tutorial="$examples/heatTransfer/buoyantBoussinesqPimpleFoam/hotRoom"
[ -d "$tutorial" ] || { echo "$0: $tutorial not found (apt-get install openfoam-examples)" >&2; exit 1; }

foam_case_args "$@"
foam_load buoyantBoussinesqPimpleFoam

rm -rf "$run_dir"
cp -r "$tutorial" "$run_dir"
cd "$run_dir"
find . -name '*.gz' -exec gunzip {} +
cp 0/T.orig 0/T

stage mesh blockMesh
stage fields setFields      # the heater's hot cells
stage solver buoyantBoussinesqPimpleFoam
foam_to_vtk '(T U p_rgh)'
