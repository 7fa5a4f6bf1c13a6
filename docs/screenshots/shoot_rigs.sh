#!/bin/bash
# Retakes the pictures of the simulated rigs: the large rig (32 devices) and the full rig
# (93 devices) fitted to the window, and the Bus events list after a hot-swap on the thesis's
# test 4 rig. Under a real X server, from the repository root:
#   xvfb-run -a -s "-screen 0 1600x1000x24" docs/screenshots/shoot_rigs.sh
# PDCP_STUDIO names the program (default: pdcp-studio).
set -e
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
OUT="$ROOT/docs/screenshots"
EXE=${PDCP_STUDIO:-pdcp-studio}
PY=$(dirname "$(command -v "$EXE")")/python
export HOME=$(mktemp -d) XDG_CONFIG_HOME= XDG_DATA_HOME= XDG_CACHE_HOME=
unset QT_QPA_PLATFORM
"$EXE" gui --bus sim:large --screenshot "$OUT/large-fitted.png" --size 1600x1000
"$PY" "$OUT/shoot_full_rig.py"  # full-rig.png
"$PY" "$OUT/shoot_hot_swap.py"  # bus-events-hot-swap.png
