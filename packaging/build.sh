#!/usr/bin/env bash
# Build the one-folder desktop app (Python and Qt inside) and smoke-test it, in one command:
#   python3 -m venv .venv && packaging/build.sh     → build/dist/pdcp-studio/pdcp-studio
# It installs the project with its `build` extra (PyInstaller) into the venv first, so a
# fresh venv is enough. PYTHON picks the venv's interpreter (default .venv/bin/python).
# The build is CPU-heavy; it runs under nice.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-.venv/bin/python}
if [ ! -x "$PY" ]; then
    echo "build.sh: no Python at $PY: python3 -m venv .venv (or set PYTHON)" >&2
    exit 1
fi
"$PY" -m pip install -q -e ".[build]"

# Translations: the committed .ts files compiled to the .qm files Qt loads.
"$PY" - <<'PY'
from pathlib import Path
from pdcp_studio.app.i18n import compile_ts
for ts in sorted(Path("resources/i18n").glob("*.ts")):
    if not compile_ts(ts, ts.with_suffix(".qm")):
        raise SystemExit(f"build.sh: cannot compile {ts}")
    print(f"compiled {ts.with_suffix('.qm')}")
PY

nice -n 10 "$PY" -m PyInstaller --noconfirm --clean --log-level WARN \
    --distpath build/dist --workpath build/work packaging/pdcp-studio.spec

APP=build/dist/pdcp-studio
cp packaging/pdcp-studio.desktop packaging/pdcp-studio-mime.xml packaging/install-desktop.sh \
    resources/icons/pdcp-studio.svg LICENSE "$APP/"
echo "built $APP ($(du -sh "$APP" | cut -f1))"
packaging/smoke_test.sh "$APP/pdcp-studio"
