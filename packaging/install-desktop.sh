#!/usr/bin/env bash
# Put PDCP Studio in the desktop's menu for this user: the .desktop entry, the file types
# (.pdcfg, PDCP system files) and the icon. Run from the build folder or packaging/;
# PDCP_STUDIO=/path/to/pdcp-studio names the program when it is not on PATH.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
data=${XDG_DATA_HOME:-$HOME/.local/share}
icon=$here/pdcp-studio.svg
[ -f "$icon" ] || icon=$here/../resources/icons/pdcp-studio.svg
exe=${PDCP_STUDIO:-}
[ -z "$exe" ] && [ -x "$here/pdcp-studio" ] && exe=$here/pdcp-studio
mkdir -p "$data/applications" "$data/mime/packages" "$data/icons/hicolor/scalable/apps"
if [ -n "$exe" ]; then
    sed "s|^Exec=pdcp-studio|Exec=$exe|; s|^TryExec=pdcp-studio|TryExec=$exe|" \
        "$here/pdcp-studio.desktop" > "$data/applications/pdcp-studio.desktop"
else
    cp "$here/pdcp-studio.desktop" "$data/applications/"
fi
cp "$here/pdcp-studio-mime.xml" "$data/mime/packages/pdcp-studio.xml"
cp "$icon" "$data/icons/hicolor/scalable/apps/pdcp-studio.svg"
command -v update-mime-database >/dev/null && update-mime-database "$data/mime" || true
command -v update-desktop-database >/dev/null && update-desktop-database "$data/applications" || true
echo "installed the PDCP Studio menu entry, file types and icon under $data"
