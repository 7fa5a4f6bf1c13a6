#!/bin/bash
# Retakes every picture the README, docs/ and the user manual show, under one X server:
#   docs/screenshots/shoot_all.sh
# (it starts xvfb-run itself; needs xvfb, xdotool, ImageMagick and poppler-utils' pdftoppm).
# PDCP_STUDIO names the program (default: pdcp-studio); its Python runs the Python scripts.
# Each script is run in turn; a failing one is named at the end and the others still run.
# About 3 minutes on a quiet 2-core machine.
set -u
HERE=$(cd "$(dirname "$0")" && pwd)
if [ -z "${DISPLAY:-}" ] || [ "${1:-}" != "--inside" ]; then
    exec xvfb-run -a -s "-screen 0 1600x1000x24" "$0" --inside
fi
ROOT=$(cd "$HERE/../.." && pwd)
cd "$ROOT"
EXE=${PDCP_STUDIO:-pdcp-studio}
export PDCP_STUDIO=$EXE
PY=$(dirname "$(command -v "$EXE")")/python
unset QT_QPA_PLATFORM
failed=()
run() {
    echo "== $*"
    local start=$SECONDS
    timeout 300 "$@" || failed+=("$*")
    echo "   $((SECONDS - start)) s"
}
DE=$(mktemp -d)
# main-window.png: the simulated prosthesis fitted to the window, by the app's own --screenshot
run env HOME="$DE/home" "$EXE" gui --bus sim:transradial --screenshot "$HERE/main-window.png" --size 1500x920
run "$PY" "$HERE/shoot_plan.py"            # plan-preview.png
run "$PY" "$HERE/shoot_wizards.py"         # wizard-*.png
run "$PY" "$HERE/shoot_wizards.py" --lang de --out "$DE/wizards"
QT_QPA_PLATFORM=offscreen run "$PY" "$HERE/manual_pictures.py"                 # resources/manual/images
QT_QPA_PLATFORM=offscreen run "$PY" "$HERE/manual_pictures.py" --lang de "$DE/wizards"
run "$PY" "$HERE/shoot_manual.py"          # manual-images.png
run "$PY" "$HERE/shoot_manual.py" --lang de  # manual-images-de.png
run "$PY" "$HERE/shoot_change_road.py"     # pending-changes.png, confirm-change.png, history.png,
                                           # restore-preview.png, report-1.png … (pdftoppm)
run "$PY" "$HERE/shoot_trace.py"           # trace.png, plot.png, trace-capture.png
run bash "$HERE/shoot_start.sh"            # start.png
run bash "$HERE/shoot_german.sh"           # main-window-de.png
run bash "$HERE/configuration-document.sh" # configuration-document.png
run bash "$HERE/shoot_rigs.sh"             # large-fitted.png, full-rig.png, bus-events-hot-swap.png
rm -rf "$DE"
echo "took $SECONDS s"
if [ ${#failed[@]} -gt 0 ]; then
    printf 'FAILED: %s\n' "${failed[@]}"
    exit 1
fi
