# Shared by the make_*.sh case scripts (sourced, not run): their arguments, the
# Python that imports the result, OpenFOAM's environment and the logged run stages.
# Needs case_name set by the caller; sets out_dir, keep and run_dir.

usage() { echo "usage: $0 OUTDIR [--keep]" >&2; exit 2; }

# foam_case_args "$@": OUTDIR [--keep] → out_dir (absolute, created), keep (0/1), run_dir.
foam_case_args() {
  [ $# -ge 1 ] || usage
  out_dir="$1"
  keep=0
  [ $# -ge 2 ] && { [ "$2" = "--keep" ] && keep=1 || usage; }
  mkdir -p "$out_dir"
  out_dir="$(cd "$out_dir" && pwd)"
  run_dir="$out_dir/$case_name.run"
}

# foam_python: PYTHON, or the first of python3, /usr/bin/python3 with numpy and h5py.
foam_python() {
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
}

# foam_load SOLVER: sources FOAM_BASHRC (default Debian's) and checks SOLVER is on PATH. Debian's
# bashrc complains about helper scripts it does not ship; the variables it sets (WM_PROJECT_DIR,
# ...) are all the solvers need.
foam_load() {
  local bashrc="${FOAM_BASHRC:-/usr/share/openfoam/etc/bashrc}"
  [ -f "$bashrc" ] || { echo "$0: $bashrc not found (apt-get install openfoam)" >&2; exit 1; }
  set +u
  # shellcheck disable=SC1090
  source "$bashrc" >/dev/null 2>&1 || true
  set -u
  if ! command -v "$1" >/dev/null; then
    echo "$0: OpenFOAM solvers not on PATH after sourcing $bashrc" >&2
    exit 1
  fi
}

# stage NAME COMMAND...: runs COMMAND at nice 19 in the current directory, logs to log.NAME,
# prints its time; on failure shows the log's tail and exits.
stage() {
  local name="$1"; shift
  local t0=$SECONDS
  if ! nice -n 19 "$@" >"log.$name" 2>&1; then
    echo "$0: $name failed; see $run_dir/log.$name" >&2
    tail -20 "log.$name" >&2
    exit 1
  fi
  echo "$name: $((SECONDS - t0)) s" >&2
}

# foam_finish: removes the run directory unless --keep, and says what was written.
foam_finish() {
  if [ "$keep" -eq 0 ]; then
    cd "$out_dir"
    rm -rf "$run_dir"
  fi
  echo "wrote $out_dir/$case_name.h5" >&2
}

# foam_to_vtk FIELDS: writes the run's foamToVTK series (what our unstructured users have: a
# .vtm.series of multiblock files whose "internal" block is a .vtu) and moves it to
# OUTDIR/CASE/ (replacing an earlier one); removes the run directory unless --keep.
foam_to_vtk() {
  stage vtk foamToVTK -fields "$1" -no-boundary
  rm -rf "${out_dir:?}/$case_name"
  mv "$run_dir/VTK" "$out_dir/$case_name"
  if [ "$keep" -eq 0 ]; then
    cd "$out_dir"
    rm -rf "$run_dir"
  fi
  echo "wrote $(ls "$out_dir/$case_name"/*.vtm.series)" >&2
}
