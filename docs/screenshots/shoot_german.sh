#!/bin/bash
# Retakes main-window-de.png and manual-de.png under a real X server, the app in German:
#   xvfb-run -a -s "-screen 0 1600x1000x24" docs/screenshots/shoot_german.sh
# The app runs on the simulated transradial prosthesis with --lang de; the screen is
# grabbed (ImageMagick's import), then F1 opens the user manual at the part for the graph
# and the screen is grabbed again. PDCP_STUDIO names the program (default: pdcp-studio).
set -e
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
OUT="$ROOT/docs/screenshots"
EXE=${PDCP_STUDIO:-pdcp-studio}
export HOME=$(mktemp -d) XDG_CONFIG_HOME= XDG_DATA_HOME= XDG_CACHE_HOME=
unset QT_QPA_PLATFORM
"$EXE" --lang de gui --bus sim:transradial >/dev/null 2>&1 &
APP=$!
trap 'kill $APP 2>/dev/null || true' EXIT
for _ in $(seq 40); do
    WID=$(xdotool search --name "PDCP Studio" 2>/dev/null | head -1) && [ -n "$WID" ] && break
    sleep 0.5
done
sleep 6
xdotool windowsize "$WID" 1500 920 windowmove "$WID" 0 0
sleep 2
import -window root -crop 1500x920+0+0 "$OUT/main-window-de.png"
xdotool mousemove 700 400 click 1   # the graph has the focus: F1 opens its part
sleep 1
xdotool key --window "$WID" F1
sleep 3
MID=$(xdotool search --name "Benutzerhandbuch" | head -1)
xdotool windowmove "$MID" 0 0
sleep 2
import -window root -crop 900x880+0+0 "$OUT/manual-de.png"
