#!/bin/bash
# Retakes configuration-document.png under a real X server:
#   xvfb-run -a -s "-screen 0 1600x1000x24" docs/screenshots/configuration-document.sh
# PDCP_STUDIO names the program (default: pdcp-studio).
# The app runs on the simulated transradial prosthesis; File ▸ Open picks the
# two-configuration file (hand, and a hook as the second terminal device) through the real
# file dialog; configuration 2 is selected; the screen is grabbed and cropped to the window.
set -e
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
FILE="$ROOT/resources/configs/transradial-hand-and-hook.pdcfg"
OUT="$ROOT/docs/screenshots/configuration-document.png"
export HOME=$(mktemp -d) XDG_CONFIG_HOME= XDG_DATA_HOME=
cp "$FILE" "$HOME/"
unset QT_QPA_PLATFORM
"${PDCP_STUDIO:-pdcp-studio}" gui --bus sim:transradial >/dev/null 2>&1 &
APP=$!
sleep 10
WID=$(xdotool search --name "PDCP Studio" | head -1)
xdotool windowfocus "$WID"
xdotool key --window "$WID" ctrl+o
sleep 3
# The file is the only one in the dialog's folder: double-click it (typing under Xvfb
# without a window manager repeats keys).
xdotool mousemove 590 233 click --repeat 2 --delay 80 1
sleep 5
xdotool mousemove 80 66 click 1   # configuration 2
sleep 3
import -window root -crop 1500x920+0+0 "$OUT"
kill "$APP"
