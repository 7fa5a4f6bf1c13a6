#!/usr/bin/env bash
# Smoke test of a PDCP Studio program (the frozen build, or any `pdcp-studio`):
#   packaging/smoke_test.sh build/dist/pdcp-studio/pdcp-studio
# --version; doctor --json (every module imports, every python-can interface listed);
# sim list; scan of a simulated prosthesis; a screenshot; then every dialog and dock opened
# (PDCP_STUDIO_SMOKE_TEST). Under a real X server when xvfb-run is there (the xcb
# platform plugin and its libraries are what a desktop uses), else off screen.
set -euo pipefail
EXE=$(realpath "${1:?usage: smoke_test.sh PROGRAM}")
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
export PDCP_STUDIO_HISTORY="$OUT/history.sqlite" XDG_DATA_HOME="$OUT/data" XDG_CONFIG_HOME="$OUT/config"
cd "$OUT"

step() { printf '%-44s' "$1"; }
step "--version";  "$EXE" --version
step "doctor --json"
"$EXE" doctor --json > doctor.json 2>doctor.err
python3 - doctor.json <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
bad = [m for m, ok in doc["modules"].items() if not ok]
assert not bad, f"modules that do not import: {bad} {doc['module_errors']}"
names = set(doc["can_interfaces"])
assert len(names) >= 23 and {"pcan", "kvaser", "socketcan", "vector", "slcan"} <= names, names
have = sorted(n for n, e in doc["can_interfaces"].items() if e["driver"])
assert doc["resources"], "no resources folder"
print(f"{len(doc['modules'])} modules import; {len(names)} interfaces listed, drivers here: "
      f"{', '.join(have)}; frozen={doc['frozen']}")
PY
step "sim list";   "$EXE" sim list | tr '\n' ' '; echo
step "scan --bus sim:transradial --json"
"$EXE" scan --bus sim:transradial --json | python3 -c "import json,sys; print(len(json.load(sys.stdin)['devices']), 'devices')"
step "can:kvaser:0 (no driver: one line, exit 1)"
set +e; "$EXE" scan --bus can:kvaser:0 2>kvaser.err; code=$?; set -e
[ "$code" = 1 ] && [ "$(wc -l < kvaser.err)" = 1 ] || { echo "exit $code:"; cat kvaser.err; exit 1; }
echo "exit 1: $(cat kvaser.err)"

run_gui() {
    if command -v xvfb-run >/dev/null 2>&1; then
        env -u QT_QPA_PLATFORM xvfb-run -a -s "-screen 0 1600x1000x24" "$@"
    else
        QT_QPA_PLATFORM=offscreen "$@"
    fi
}
step "gui --bus sim:transradial --screenshot"
run_gui "$EXE" gui --bus sim:transradial --screenshot shot.png --size 1400x860 2>gui.err
python3 -c "import os; s=os.path.getsize('shot.png'); assert s > 20000, s; print(s, 'bytes')"
step "every dialog and dock"
PDCP_STUDIO_SMOKE_TEST="$OUT/smoke.json" run_gui "$EXE" gui --bus sim:transradial 2>smoke.err || true
python3 - smoke.json <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
failed = {k: v for k, v in doc["steps"].items() if v != "ok"}
assert not failed, failed
print(f"{len(doc['steps'])} steps ok")
PY
step "German (--lang de)"
run_gui "$EXE" --lang de gui --bus sim:transradial --screenshot shot-de.png 2>>gui.err || true
python3 -c "import os; print(os.path.getsize('shot-de.png'), 'bytes')"
echo "smoke test passed"
