#!/usr/bin/env bash
# Builds the Debian package (CLI, library, headers, CMake package, figure scripts, Python module for Debian's
# python3) from a configured build directory: bash scripts/build-deb.sh [BUILD_DIR]  ->  BUILD_DIR/vibrissa_*.deb
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${1:-build}"
# Debian's python3 reads /usr/lib/python3/dist-packages: package the module there, then put the build
# directory's own setting back (only install rules change; nothing is recompiled).
previous="$(sed -n 's/^VIBRISSA_PYTHON_INSTALL_DIR:STRING=//p' "$BUILD/CMakeCache.txt")"
cmake -S . -B "$BUILD" -DVIBRISSA_PYTHON_INSTALL_DIR=lib/python3/dist-packages > /dev/null
restore() { if [ -n "$previous" ]; then cmake -S . -B "$BUILD" -DVIBRISSA_PYTHON_INSTALL_DIR="$previous" > /dev/null; fi; }
trap restore EXIT
cmake --build "$BUILD" -j"$(nproc)"
(cd "$BUILD" && cpack -G DEB)
ls "$BUILD"/vibrissa_*.deb
