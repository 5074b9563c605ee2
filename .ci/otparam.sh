#!/usr/bin/env bash
# Set-up, build, main job and tests of OTParam on Debian 12, as root (or with sudo).
#
#   bash .ci/otparam.sh main [output dir] [--mesh FILE]
#                                           install packages, build, run the full pipeline on
#                                           the built-in surface (or FILE) and write its
#                                           outputs and pictures
#   bash .ci/otparam.sh test                install packages, build, run every test (ctest),
#                                           then the core's unit tests with ASan + UBSan
#   bash .ci/otparam.sh setup               install packages and build only
#
# Environment: OTPARAM_BUILD_DIR (default <repo>/build), OTPARAM_ASAN_BUILD_DIR (default
# <repo>/build-asan), OTPARAM_JOBS (default: number of cores). apt-get install is idempotent,
# so every run installs (or confirms) the packages; builds are incremental (and use ccache).
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${OTPARAM_BUILD_DIR:-$repo/build}
asan_build=${OTPARAM_ASAN_BUILD_DIR:-$repo/build-asan}
jobs=${OTPARAM_JOBS:-$(nproc)}
python=/usr/bin/python3

# ParaView 5.11 with its own VTK 9.2 (module, Python wrapping and plugin are all built against
# it), the third-party headers its CMake package looks for with the components OTParam uses,
# Qt's help tools for the plugin documentation, the algorithms' libraries, Open MPI's mpiexec
# and mpi4py for cohorts on pvbatch ranks, test tools.
packages=(
  cmake ninja-build g++ ccache
  paraview paraview-dev python3-paraview python3-dev python3-numpy
  qtbase5-dev qttools5-dev qttools5-dev-tools libqt5svg5-dev qtxmlpatterns5-dev-tools
  libqt5x11extras5-dev
  openmpi-bin python3-mpi4py
  libopenmpi-dev libdouble-conversion-dev liblz4-dev liblzma-dev libexpat1-dev zlib1g-dev
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev libeigen3-dev libsuitesparse-dev
  libopenblas0-pthread
  libgtest-dev xvfb xauth
)

log() { printf '\n==== %s\n' "$*"; }

# OpenBLAS's kernels as the otparam command chooses them (CommandLine/otparam.in), unless set:
# Debian 12's OpenBLAS 0.3.21 runs its generic SSE3 kernels on processors newer than itself.
cpu_flags=" $(grep -m1 '^flags' /proc/cpuinfo 2> /dev/null || true) "
has_cpu_flags() {
  local flag
  for flag in "$@"; do [[ $cpu_flags == *" $flag "* ]] || return 1; done
}
if [ -z "${OPENBLAS_CORETYPE:-}" ]; then
  if has_cpu_flags avx512f avx512cd avx512bw avx512dq avx512vl; then
    export OPENBLAS_CORETYPE=SkylakeX
  elif has_cpu_flags avx2 fma; then
    export OPENBLAS_CORETYPE=Haswell
  fi
fi

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

install_packages() {
  log "installing packages"
  export DEBIAN_FRONTEND=noninteractive
  as_root apt-get update
  as_root apt-get install -y --no-install-recommends "${packages[@]}"
}

configure_and_build() {
  local generator=()
  command -v ninja > /dev/null && generator=(-G Ninja)
  log "configuring $build"
  cmake -S "$repo" -B "$build" "${generator[@]}" \
    -DCMAKE_BUILD_TYPE=Release \
    -DPython3_EXECUTABLE="$python"
  log "building $build"
  cmake --build "$build" --parallel "$jobs"
}

setup() {
  install_packages
  configure_and_build
}

run_main() {
  local output=$repo/otparam-output
  if [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; then
    output=$1
    shift
  fi
  setup
  log "main job: area-preserving parameterization ${*:-of the built-in hand-like surface} -> $output"
  PYTHONPATH="$build/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}" \
    "$python" "$repo/Examples/area_preserving_demo.py" "$output" "$@"
  if [ $# -eq 0 ]; then
    log "main job: the built-in closed surface onto the unit sphere -> $output/sphere"
    PYTHONPATH="$build/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}" \
      "$python" "$repo/Examples/sphere_demo.py" "$output/sphere"
  fi
}

run_tests() {
  setup
  # Tests run side by side (--parallel): idle OpenMP threads sleep, so that one test's spinning
  # threads do not starve the other's (as the otparam command sets it).
  export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
  log "ctest in $build"
  (cd "$build" && ctest --output-on-failure --parallel "$jobs")

  # The core alone, with AddressSanitizer and UndefinedBehaviorSanitizer: no VTK, so every
  # report is the core's. -O1 keeps the n = 1e5 tests fast enough. The sampler tests on real
  # conformal images and the 3e5-Dirac reproducibility test run no code path the other tests
  # miss, and take minutes under ASan.
  log "core-only sanitizer build in $asan_build"
  local generator=()
  command -v ninja > /dev/null && generator=(-G Ninja)
  cmake -S "$repo" -B "$asan_build" "${generator[@]}" \
    -DOTPARAM_CORE_ONLY=ON \
    -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_CXX_FLAGS_DEBUG="-g -O1" \
    -DCMAKE_CXX_FLAGS="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
  cmake --build "$asan_build" --parallel "$jobs"
  log "ctest in $asan_build"
  (cd "$asan_build" &&
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      ctest --output-on-failure --parallel "$jobs" --exclude-regex 'ConformalImages|At3e5')
}

case "${1:-}" in
  main) shift; run_main "$@" ;;
  test) run_tests ;;
  setup) setup ;;
  *) echo "usage: $0 main [output dir] [--mesh FILE] | test | setup" >&2; exit 2 ;;
esac
