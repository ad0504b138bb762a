#!/usr/bin/env bash
# Installs the Debian 12 packages tspplay needs. Idempotent and quiet when all are present.
#   install-deps.sh             (a --movie argument from older scripts is accepted and ignored:
#                               ffmpeg, which `render --movie` and the demo encode with, is always
#                               installed, and the suite decodes a movie with it)
#   install-deps.sh --mpi       also Open MPI, for tspplay-mpi (the MPI build, docs/mpi.md): the
#                               next build makes it and the suite then runs its tests
set -euo pipefail
PKGS=(
  cmake ninja-build g++ pkg-config
  libhdf5-dev hdf5-tools zlib1g-dev libpugixml-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  liblcms2-dev libpng-dev libglm-dev libosmesa6-dev libglfw3-dev libimgui-dev
  libhwy-dev  # Google Highway: the CPU ray caster's SIMD lanes, dispatched at run time
  libegl-dev libegl-mesa0  # EGL: render --gl egl (a GPU without a display; Mesa's llvmpipe here)
  libgl-dev  # <GL/glcorearb.h>: the GL 3.3 core types and enums of our loader (src/gl/gl_api.h)
  xvfb xauth  # xvfb-run: a virtual X display for the GLFW (window) tests when DISPLAY is unset
  ffmpeg      # movies: render --movie, the demo's movie, and the suite's movie test
  xdotool     # real X key and mouse events for the player tests under Xvfb
  pybind11-dev python3-dev  # the Python module tspplay (src/python, docs/python.md)
  python3-pytest python3-numpy python3-xarray  # its tests (tests/python)
  python3-h5py  # bench/python_build.py reads the HDF5 series it compares against
)
for a in "$@"; do
  # Open MPI's compiler wrappers and launcher, and parallel HDF5 (tspplay-mpi's own build of
  # the library links it; the rest keeps the serial HDF5 above).
  [ "$a" = "--mpi" ] && PKGS+=(libopenmpi-dev openmpi-bin libhdf5-openmpi-dev)
done
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
