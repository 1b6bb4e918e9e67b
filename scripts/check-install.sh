#!/usr/bin/env bash
# The three ways to install vibrissa, each used without the source tree (CI runs this after the build):
#   1. CMake: install to a prefix, build and run an outside C++ project with find_package(vibrissa).
#   2. pip: `pip install .` into a fresh venv (Debian's NumPy through --system-site-packages), then, with only
#      the pip-installed package (no build tree on PATH or PYTHONPATH): the `vibrissa` command (demo, array with
#      its figures, viewer page and animation, sweep), `python -m vibrissa`, the examples and the pipeline from Python.
#   3. Debian package: cpack -G DEB, dpkg -i, then `vibrissa demo` and `import vibrissa` with /usr/bin/python3.
# Usage: bash scripts/check-install.sh [BUILD_DIR]   (a configured and built Release build directory)
set -euo pipefail
cd "$(dirname "$0")/.."
SRC="$PWD"
BUILD="$(cd "${1:-build}" && pwd)"
WORK="$(mktemp -d)"
# pip's build of the package goes beside BUILD, at the same depth below the source tree and with BUILD's -Werror
# setting, so its compiler commands equal BUILD's and a compiler cache (ccache with base_dir, as .ci/run sets it)
# serves them instead of compiling the library a second time.
WHEEL_BUILD="$(dirname "$BUILD")/.$(basename "$BUILD")-pip"
WERROR="$(sed -n 's/^VIBRISSA_WERROR:BOOL=//p' "$BUILD/CMakeCache.txt")"
rm -rf "$WHEEL_BUILD"
trap 'rm -rf "$WORK" "$WHEEL_BUILD"' EXIT
cd "$WORK"

echo "=== 1. CMake package: install to a prefix, build an outside project ==="
cmake --install "$BUILD" --prefix "$WORK/prefix" > /dev/null
cmake -S "$SRC/tests/package/consumer" -B "$WORK/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$WORK/prefix" > /dev/null
cmake --build "$WORK/consumer" > /dev/null
"$WORK/consumer/consumer"
env -u VIBRISSA_FIGURES_DIR "$WORK/prefix/bin/vibrissa" synth "$WORK/t.csv" --duration 0.5 > /dev/null
env -u VIBRISSA_FIGURES_DIR "$WORK/prefix/bin/vibrissa" trial "$WORK/t.csv" --out "$WORK/t_results" > /dev/null
ls "$WORK"/t_results/figures/*.png > /dev/null 2>&1 || { ls -R "$WORK/t_results"; echo "installed CLI drew no figures"; exit 1; }
echo "installed CLI: figures from $WORK/prefix/share/vibrissa/figures"

echo "=== 2. pip install . into a fresh venv: the package and the vibrissa command ==="
/usr/bin/python3 -m venv --system-site-packages "$WORK/venv"
VIBRISSA_BUILD_DIR="$WHEEL_BUILD" VIBRISSA_CMAKE_ARGS="-DVIBRISSA_WERROR=${WERROR:-OFF}" "$WORK/venv/bin/python" -m pip install --no-index --quiet "$SRC"  # all CPUs
mkdir "$WORK/elsewhere" && cd "$WORK/elsewhere"
# Only what pip installed: the venv's bin first, no build tree, no figure scripts or CLI from outside.
VENV=(env -u PYTHONPATH -u VIBRISSA_CLI -u VIBRISSA_FIGURES_DIR -u VIBRISSA_PYTHON
      PATH="$WORK/venv/bin:/usr/bin:/bin" MPLBACKEND=Agg)
[ "$("${VENV[@]}" sh -c 'command -v vibrissa')" = "$WORK/venv/bin/vibrissa" ] || { echo "no vibrissa command in the venv"; exit 1; }
"${VENV[@]}" vibrissa demo > /dev/null
"${VENV[@]}" python -m vibrissa --version | grep -q "vibrissa 0.1" || { echo "python -m vibrissa failed"; exit 1; }
"${VENV[@]}" vibrissa array --out array_results --frames 12 --animation > /dev/null
for f in array.h5 summary.json array_traces.png view.html array_animation.mp4; do
  [ -s "array_results/$f" ] || { ls -l array_results; echo "pip-installed vibrissa array wrote no $f"; exit 1; }
done
echo '{"kind": "solve", "base": {"whisker": {"length": 0.03, "curvature": 20.0},
       "load": {"mode": "point", "point": [0.02, 0.005, 0.0]}}, "grid": {"load.point.1": [0.004, 0.006]}}' > sweep.json
"${VENV[@]}" vibrissa sweep sweep.json --out sweep_results --workers 1 > /dev/null
"${VENV[@]}" python "$SRC/examples/peg_contact.py" --output peg.png > /dev/null
"${VENV[@]}" python - <<'PY'
import pathlib, vibrissa, xarray
assert "site-packages" in vibrissa.__file__, vibrissa.__file__
trial = vibrissa.synthesize_trial(duration=0.5)
result = vibrissa.analyze_trial(trial, mu=0.48)
result.write("out")
result.figures("out/figures")
assert pathlib.Path("out/summary.json").is_file() and any(pathlib.Path("out/figures").glob("*.png"))
array = vibrissa.simulate_array("array_results/config.json")
assert array.to_xarray().FT.dims == ("pitch", "whisker", "time")
assert xarray.open_dataset("sweep_results/sweep.nc").FT.dims == ("load.point.1",)
print("pip-installed vibrissa", vibrissa.__version__, "from", pathlib.Path(vibrissa.__file__).parent)
PY
cd "$WORK"

echo "=== 3. Debian package ==="
bash "$SRC/scripts/build-deb.sh" "$BUILD" > "$WORK/cpack.log"
DEB="$(ls "$BUILD"/vibrissa_*.deb | head -n1)"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
$SUDO dpkg -i "$DEB" > /dev/null
/usr/bin/vibrissa demo > /dev/null
(cd / && /usr/bin/python3 -c "import vibrissa, sys; assert vibrissa.__file__.startswith('/usr/lib/python3/dist-packages'), vibrissa.__file__; print('deb python module', vibrissa.__file__)")
$SUDO dpkg -r vibrissa > /dev/null
echo "install checks: all three passed"
