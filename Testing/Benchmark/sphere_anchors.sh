#!/bin/bash
# Run two published MATLAB spherical-map anchors under GNU Octave and score them with
# param_metrics.py --sphere (the scorer used for every table in shared/docs).
#   FLASH  (Choi, Lam, Lui 2015)         github.com/garyptchoi/spherical-conformal-map
#   SDEM   (Lyu, Lui, Choi 2024)         github.com/garyptchoi/spherical-density-equalizing-map
# Usage: sphere_anchors.sh SCM_DIR SDEM_DIR OUT_DIR [MESH ...]
#   SCM_DIR / SDEM_DIR: work trees of the two repositories (not vendored here; fetch them
#   yourself).  Defaults for MESH: the two closed meshes of shared/data/meshes.
# Env: SHARED (default ../shared beside the checkout), NREP (timing repetitions, default 3; median reported),
#      PYTHON (default /usr/bin/python3, needs numpy).  Needs octave-cli (Debian: apt install octave).
set -euo pipefail
SCM=$(realpath "$1"); SDEM=$(realpath "$2"); OUT=$(realpath -m "$3"); shift 3
SHARED=${SHARED:-$(realpath -m "$(dirname "$0")/../../../shared")}; NREP=${NREP:-3}; PY=${PYTHON:-/usr/bin/python3}
MESHES=("$@"); [ ${#MESHES[@]} -gt 0 ] || MESHES=("$SHARED/data/meshes/brain_choi_closed_48k.off" "$SHARED/data/meshes/spot_closed_3k.obj")
DRV=$(dirname "$(realpath "$0")")/sphere_anchors       # our Octave drivers (+ fmincon shim)
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1          # one core, as in reference-figures.md
mkdir -p "$OUT"
for mesh in "${MESHES[@]}"; do
  name=$(basename "${mesh%.*}")
  # flash: conformal map alone; flash_mobius: + the repo's Mobius area correction;
  # sdem: flash_mobius as initial map, population = surface face areas (area-preserving use).
  for method in flash flash_mobius sdem; do
    src=$SCM; [ $method = sdem ] && src=$SDEM
    off="$OUT/${name}_${method}.off"
    octave-cli -q --eval "addpath('$DRV'); run_sphere_anchor('$method','$mesh','$off','$src',$NREP)" \
      > "$OUT/${name}_${method}.log" 2>&1 || { echo "$name $method: octave failed (see log)"; continue; }
    grep '^RESULT' "$OUT/${name}_${method}.log"
    "$PY" "$SHARED/tools/param_metrics.py" "$mesh" "$off" --sphere --json | tee "$OUT/${name}_${method}.json"
  done
done
