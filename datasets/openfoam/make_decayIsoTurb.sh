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
# shellcheck source=foam_case.sh
source "$here/foam_case.sh"
examples="${FOAM_EXAMPLES:-/usr/share/doc/openfoam-examples/examples}"
tutorial="$examples/incompressible/pimpleFoam/LES/decayIsoTurb"
[ -d "$tutorial" ] || { echo "$0: $tutorial not found (apt-get install openfoam-examples)" >&2; exit 1; }

foam_case_args "$@"
foam_python
foam_load pimpleFoam

rm -rf "$run_dir"
cp -r "$tutorial" "$run_dir"
cd "$run_dir"
find . -name '*.gz' -exec gunzip {} +
# 0.2 s of the decay (the tutorial runs 1 s), every 5th step, ASCII for the importer.
sed -i 's/^endTime .*/endTime         0.2;/; s/^writeInterval .*/writeInterval   5;/;
        s/^writeFormat .*/writeFormat     ascii;/' system/controlDict
cp -r 0.orig 0

stage mesh createBoxTurb -createBlockMesh   # the 64³ box
stage turbulence createBoxTurb              # the initial velocity field
stage cellCentres postProcess -func writeCellCentres -time 0
stage solver pimpleFoam
stage import "$PYTHON" "$here/foam_to_h5.py" "$run_dir" -o "$out_dir/$case_name.h5" \
  --field p --field k --case-name "$case_name"
foam_finish
