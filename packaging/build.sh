#!/usr/bin/env bash
# Build the one-folder desktop app (Python and Qt inside) and smoke-test it:
#   packaging/build.sh            → build/dist/pdcp-studio/pdcp-studio
# PYTHON picks the interpreter (default .venv/bin/python, with PyInstaller installed:
# .venv/bin/pip install pyinstaller). The build is CPU-heavy; it runs under nice.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-.venv/bin/python}
if ! "$PY" -m PyInstaller --version >/dev/null 2>&1; then
    echo "build.sh: PyInstaller is missing: $PY -m pip install pyinstaller" >&2
    exit 1
fi

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
