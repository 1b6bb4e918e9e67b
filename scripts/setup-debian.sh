#!/usr/bin/env bash
# Installs every Debian package vibrissa needs to build, test, benchmark and plot.
# Usage: sudo-less root or sudo: bash scripts/setup-debian.sh
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev            # linear algebra (fixed-size 3x3, small dense solves)
  nlohmann-json3-dev       # JSON case/result files
  libcli11-dev             # command-line parsing
  libgtest-dev libgmock-dev  # unit tests
  libbenchmark-dev         # micro-benchmarks
  libhdf5-dev              # HDF5 trial / array output
  libmatio-dev             # MATLAB .mat trial input
  libcgal-dev              # objects: CGAL's AABB tree for mesh closest points (header-only)
  libassimp-dev            # objects: reading OBJ, STL and PLY mesh files
  pybind11-dev python3-dev python3-pybind11   # Python extension
  python3-numpy python3-matplotlib python3-pytest python3-h5py
  python3-pandas           # TrialResult.to_dataframe() in the Python package
  python3-xarray python3-h5netcdf python3-netcdf4   # to_xarray(), sweeps; every HDF5 output opens in xarray (both engines)
  python3-distributed python3-dask python3-psutil python3-cloudpickle  # vibrissa.sweep / `vibrissa sweep` on Dask; psutil, cloudpickle: the sweep tests
  ffmpeg                   # MP4 animations
  python3-venv python3-pip dpkg-dev   # install checks: pip into a venv, cpack -G DEB (dpkg-shlibdeps)
  clang-14 libclang-rt-14-dev libomp-14-dev   # libFuzzer harnesses (scripts/fuzz.sh)
  libtomlplusplus-dev libyaml-cpp-dev   # calibrations: anipose calibration.toml, OpenCV FileStorage YAML
  python3-opencv python3-scipy          # tests: OpenCV's projectPoints as the reference camera model; SciPy checks
  chromium chromium-driver python3-selenium libjs-three   # viewer: three.js inlined into pages; headless tests
  ccache                                # compiler cache (used by the build when present)
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
echo "vibrissa: all Debian packages present"
