#!/usr/bin/env bash
# Multi-Axis Slicer set-up: installs the Debian packages it needs (only those missing), configures
# with FreeCAD's Python, builds, and then, by mode:
#   install  installs the workbench into ~/.local/share/FreeCAD/Mod/MultiAxisSlicer
#   demo     install, then run the main job headless on the bundled example part (results in out/)
#   test     build and run every test (ctest: engine, CLI, freecadcmd, GUI under Xvfb)
#   bench    also install libcgal-dev (for the comparison with CGAL's skeleton), fetch CGAL's
#            test meshes and run the benchmark programs (figures in out/bench_*.txt)
#   build    build only
# Idempotent: run it again after a pull.
set -euo pipefail
mode=${1:-install}
root=$(cd "$(dirname "$0")/.." && pwd)
build=${MAS_BUILD_DIR:-$root/build}
jobs=$(nproc 2>/dev/null || echo 2)

packages=(
  build-essential cmake pkg-config
  freecad
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-data-exchange-dev
  libboost-python-dev libeigen3-dev libpolyclipping-dev libtbb-dev
  libgtest-dev libbenchmark-dev
  linuxcnc-uspace xvfb xauth
  clang-format
)

install_packages() {
  local missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "setup: installing ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

configure_and_build() {
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3.11
  cmake --build "$build" -j "$jobs"
}

install_addon() {
  local mod="$HOME/.local/share/FreeCAD/Mod/MultiAxisSlicer"
  rm -rf "$mod"
  cmake --install "$build" --prefix "$mod" >/dev/null
  echo "setup: workbench installed in $mod"
}

[ "$mode" = bench ] && packages+=(libcgal-dev)
install_packages
configure_and_build
case "$mode" in
  build) ;;
  install) install_addon ;;
  demo)
    install_addon
    mkdir -p "$root/out"
    (cd "$root" && MAS_EXAMPLE="$root/examples/bracket.step" MAS_OUT="$root/out" \
      freecadcmd "$root/tools/main_job.py" 2>&1 | tee "$root/out/main_job.log")
    grep -q "main job: done" "$root/out/main_job.log"
    ;;
  test)
    cd "$build"
    ctest --output-on-failure -j 1
    ;;
  bench)
    mkdir -p "$root/out"
    [ -f "$build/bench-data/bunny00.off" ] || "$root/tools/fetch_bench_data.sh" "$build/bench-data"
    echo "setup: $(nproc) cores; benchmark figures go to out/bench_*.txt"
    "$build/bench/mas_bench" "$build/bench-data" | tee "$root/out/bench_sections.txt"
    "$build/bench/mas_bench_axis" "$build/bench-data" | tee "$root/out/bench_axis.txt"
    "$build/bench/mas_bench_decompose" | tee "$root/out/bench_decompose.txt"
    "$build/bench/mas_bench_slice" "$root/examples/bracket.step" | tee "$root/out/bench_slice.txt"
    MAS_APP="$build/Mod/MultiAxisSlicer/App" MAS_BENCH_DATA="$build/bench-data" \
      freecadcmd "$root/tools/bench_mesh_input.py" 2>&1 | tee "$root/out/bench_mesh_input.txt"
    bench_home=$(mktemp -d)  # the FreeCAD GUI writes its settings there, not the user's
    HOME="$bench_home" QTWEBENGINE_DISABLE_SANDBOX=1 MAS_MOD="$build/Mod/MultiAxisSlicer" \
      xvfb-run -a -s "-screen 0 1280x1024x24" freecad "$root/tools/bench_build_preview.py" 2>&1 |
      tee "$root/out/bench_build_preview.txt"
    rm -rf "$bench_home"
    ;;
  *) echo "usage: tools/setup.sh [install|demo|test|bench|build]" >&2; exit 2 ;;
esac
