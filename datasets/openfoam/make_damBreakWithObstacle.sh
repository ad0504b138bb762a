#!/usr/bin/env bash
# Makes OUTDIR/damBreakWithObstacle/damBreakWithObstacle.run.vtm.series: runs OpenFOAM's
# damBreakWithObstacle tutorial (multiphase/interIsoFoam/damBreakWithObstacle, Debian
# openfoam-examples: a water column collapsing onto an obstacle in a 1 m box of 16³ hexahedra
# with the obstacle's cells removed — a hole — and adaptive refinement (up to 2 levels) that
# follows the interface, so the mesh changes every step and its refined cells arrive as
# polyhedra) for END seconds (default 0.2; the tutorial runs 1) on one process at nice 19,
# writing every 0.02 s with foamToVTK (alpha.water, p_rgh, U).
#
# Usage: make_damBreakWithObstacle.sh OUTDIR [--keep] [END]
# Needs: Debian openfoam (v1912) and openfoam-examples. Environment: FOAM_BASHRC, FOAM_EXAMPLES.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
case_name=damBreakWithObstacle
# shellcheck source=foam_case.sh
source "$here/foam_case.sh"
examples="${FOAM_EXAMPLES:-/usr/share/doc/openfoam-examples/examples}"
tutorial="$examples/multiphase/interIsoFoam/damBreakWithObstacle"
[ -d "$tutorial" ] || { echo "$0: $tutorial not found (apt-get install openfoam-examples)" >&2; exit 1; }

end=0.2
args=()
for a in "$@"; do
  if [[ "$a" =~ ^[0-9.]+$ ]]; then end="$a"; else args+=("$a"); fi
done
foam_case_args "${args[@]}"
foam_load interIsoFoam

rm -rf "$run_dir"
cp -r "$tutorial" "$run_dir"
cd "$run_dir"
find . -name '*.gz' -exec gunzip {} +
sed -i "s/^endTime .*/endTime         $end;/" system/controlDict
cp -r 0.orig 0

stage mesh blockMesh
stage obstacle topoSet
stage hole subsetMesh -overwrite c0 -patch walls   # the obstacle's cells removed
stage fields setFields                              # the water column
stage solver interIsoFoam
foam_to_vtk '(alpha.water p_rgh U)'
