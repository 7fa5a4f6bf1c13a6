#!/bin/bash
# Retakes start.png: the start page of a window opened with no file and no bus, with three
# recent files of a clinic's folder. Under a real X server:
#   xvfb-run -a -s "-screen 0 1600x1000x24" docs/screenshots/shoot_start.sh
# PDCP_STUDIO names the program (default: pdcp-studio).
set -e
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
OUT="$ROOT/docs/screenshots"
EXE=${PDCP_STUDIO:-pdcp-studio}
PY=$(dirname "$(command -v "$EXE")")/python
export HOME=$(mktemp -d) XDG_CONFIG_HOME= XDG_DATA_HOME= XDG_CACHE_HOME=
unset QT_QPA_PLATFORM
FITTINGS="$HOME/Fittings"
mkdir -p "$FITTINGS"
cp "$ROOT/resources/systems/transradial.json" "$FITTINGS/P-0042 transradial.json"
cp "$ROOT/resources/systems/appendix-d.json" "$FITTINGS/P-0017 test rig.json"
cp "$ROOT/resources/configs/fig410.pdcfg" "$FITTINGS/P-0042 stored.pdcfg"
"$PY" - "$FITTINGS" <<'PYEOF'
import sys
from pathlib import Path
from PySide6.QtCore import QCoreApplication, QSettings
app = QCoreApplication([])
app.setOrganizationName("PDCP Studio")
app.setApplicationName("PDCP Studio")
from pdcp_studio.app.window.recent_files import RecentFiles
recent = RecentFiles(QSettings())
for name in ("P-0017 test rig.json", "P-0042 stored.pdcfg", "P-0042 transradial.json"):
    recent.add(Path(sys.argv[1]) / name)
QSettings().sync()
PYEOF
"$EXE" gui --screenshot "$OUT/start.png" --size 1360x820
