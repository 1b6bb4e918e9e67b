#!/usr/bin/env bash
# Regenerates the Janelia Whisker Tracker fixtures of this directory (README.md) with the tracker itself.
#   WHISK=/path/to/whisk/build tests/data/janelia/make_fixtures.sh
# WHISK: a build of github.com/nclack/whisk (its `trace`, `measure`, `classify`, `whisker_convert`), made
# outside this repository. Needs /usr/bin/python3 with numpy, scipy and Pillow for the video.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
/usr/bin/python3 "$here/render_video.py"                     # video.tif: 6 frames, one dark curved whisker
"$WHISK/trace" video.tif synth                               # synth.whiskers (binary whiskbin1)
"$WHISK/measure" --face left synth.whiskers synth.measurements   # measv3, every segment identity 0
"$WHISK/classify" synth.measurements synth.measurements left --px2mm 0.04 -n 1   # one whisker: 0, the rest -1
"$WHISK/whisker_convert" synth.whiskers synth_text.whiskers whisk1             # the text variant (whisker1)
cp synth.whiskers synth_text.whiskers synth.measurements "$here/"
