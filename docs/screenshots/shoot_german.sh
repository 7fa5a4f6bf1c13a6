#!/bin/bash
# Retakes main-window-de.png, the app in German on the simulated transradial prosthesis
# (--lang de), by the app's own --screenshot (the window laid out and the graph fitted):
#   xvfb-run -a -s "-screen 0 1600x1000x24" docs/screenshots/shoot_german.sh
# PDCP_STUDIO names the program (default: pdcp-studio). The German user manual is in
# manual-images-de.png (shoot_manual.py --lang de).
set -e
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
OUT="$ROOT/docs/screenshots"
EXE=${PDCP_STUDIO:-pdcp-studio}
export HOME=$(mktemp -d) XDG_CONFIG_HOME= XDG_DATA_HOME= XDG_CACHE_HOME=
unset QT_QPA_PLATFORM
"$EXE" --lang de gui --bus sim:transradial --screenshot "$OUT/main-window-de.png" --size 1600x1000
