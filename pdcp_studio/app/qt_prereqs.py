"""Can Qt open a window here? Checked before any Qt import, so a missing system library or
display gives one clear message instead of Qt's abort (exit 134, "could not load the Qt
platform plugin xcb").

Qt's GUI libraries need a few system libraries (EGL, OpenGL, fontconfig…) even to render
off screen; its X11 platform plugin (xcb) needs a dozen more that minimal Debian and
Ubuntu installs lack. Each is tried with ``ctypes`` (the dynamic loader's own answer, as Qt
would get it) and named with the Debian/Ubuntu package that has it. A display is there when
``$DISPLAY`` names an X server that accepts a connection (``xcb_connect``) or
``$WAYLAND_DISPLAY`` is set.

No Qt import here: the command line calls :func:`problem` before it imports PySide6.
"""

from __future__ import annotations

import ctypes
import os
import sys
from collections.abc import Callable, Iterable, Mapping
from typing import TypedDict, Unpack

#: What Qt's GUI libraries load on Linux, whatever the platform plugin (Debian package).
GUI_LIBRARIES: dict[str, str] = {
    "libEGL.so.1": "libegl1",
    "libGL.so.1": "libgl1",
    "libfontconfig.so.1": "libfontconfig1",
    "libfreetype.so.6": "libfreetype6",
    "libX11.so.6": "libx11-6",
    "libxcb.so.1": "libxcb1",
    "libxkbcommon.so.0": "libxkbcommon0",
    "libglib-2.0.so.0": "libglib2.0-0",
    "libdbus-1.so.3": "libdbus-1-3",
}

#: What Qt's xcb platform plugin (a window on X11) loads on top (Debian package).
XCB_LIBRARIES: dict[str, str] = {
    "libxcb-cursor.so.0": "libxcb-cursor0",
    "libxcb-icccm.so.4": "libxcb-icccm4",
    "libxcb-keysyms.so.1": "libxcb-keysyms1",
    "libxcb-image.so.0": "libxcb-image0",
    "libxcb-render-util.so.0": "libxcb-render-util0",
    "libxcb-shape.so.0": "libxcb-shape0",
    "libxcb-xkb.so.1": "libxcb-xkb1",
    "libxcb-randr.so.0": "libxcb-randr0",
    "libxcb-render.so.0": "libxcb-render0",
    "libxcb-shm.so.0": "libxcb-shm0",
    "libxcb-sync.so.1": "libxcb-sync1",
    "libxcb-xfixes.so.0": "libxcb-xfixes0",
    "libxcb-util.so.1": "libxcb-util1",
    "libxkbcommon-x11.so.0": "libxkbcommon-x11-0",
    "libX11-xcb.so.1": "libx11-xcb1",
}

#: The one apt-get line the README gives (every package above).
APT_PACKAGES = tuple(dict.fromkeys([*GUI_LIBRARIES.values(), *XCB_LIBRARIES.values()]))

CLI_HINT = ("the command-line tools work without it (pdcp-studio --help), and "
            "`pdcp-studio gui --screenshot window.png` renders the window to a picture")


def _loads(soname: str) -> bool:
    """Whether the dynamic loader finds ``soname`` — in a frozen build first beside the
    program, where the build bundles what it could."""
    bundled = getattr(sys, "_MEIPASS", None)
    names = [os.path.join(bundled, soname)] if bundled else []
    for name in [*names, soname]:
        if bundled and name != soname and not os.path.exists(name):
            continue
        try:
            ctypes.CDLL(name)
        except OSError:
            continue
        return True
    return False


def missing(libraries: Mapping[str, str], loads: Callable[[str], bool] = _loads
            ) -> list[tuple[str, str]]:
    """The (library, package) pairs of ``libraries`` that the dynamic loader cannot load."""
    return [(so, pkg) for so, pkg in libraries.items() if not loads(so)]


def x_server_answers(display: str) -> bool:
    """True when the X server ``display`` accepts a connection (libxcb's ``xcb_connect``)."""
    try:
        xcb = ctypes.CDLL("libxcb.so.1")
    except OSError:
        return False
    xcb.xcb_connect.restype = ctypes.c_void_p
    xcb.xcb_connect.argtypes = [ctypes.c_char_p, ctypes.c_void_p]
    xcb.xcb_connection_has_error.argtypes = [ctypes.c_void_p]
    xcb.xcb_disconnect.argtypes = [ctypes.c_void_p]
    conn = xcb.xcb_connect(display.encode(), None)
    try:
        return bool(conn) and xcb.xcb_connection_has_error(conn) == 0
    finally:
        if conn:
            xcb.xcb_disconnect(conn)


def _install_line(pairs: Iterable[tuple[str, str]]) -> str:
    return "sudo apt-get install " + " ".join(dict.fromkeys(pkg for _so, pkg in pairs))


def problem(*, screenshot: bool = False, environ: Mapping[str, str] | None = None,
            platform: str = sys.platform, loads: Callable[[str], bool] = _loads,
            answers: Callable[[str], bool] = x_server_answers) -> str | None:
    """Why the desktop app cannot start here (one message), or None when it can.

    ``screenshot``: the window can be rendered off screen (see :func:`needs_offscreen`),
    so only the libraries Qt's GUI itself needs count.
    """
    env = os.environ if environ is None else environ
    if not platform.startswith("linux"):
        return None  # Windows and macOS wheels carry what Qt needs
    gui = missing(GUI_LIBRARIES, loads)
    if gui:
        names = ", ".join(so for so, _pkg in gui)
        return (f"PDCP Studio's window needs system libraries that are missing here: {names}. "
                f"Install them with: {_install_line(gui)} — "
                "the command-line tools work without them (pdcp-studio --help).")
    if screenshot:
        return None
    wanted = env.get("QT_QPA_PLATFORM", "")
    if wanted and not wanted.startswith("xcb"):
        return None  # offscreen, wayland, vnc…: Qt's choice, not an X11 window
    display, wayland = env.get("DISPLAY", ""), env.get("WAYLAND_DISPLAY", "")
    if not display and not wayland:
        return (f"There is no display to open PDCP Studio's window on (neither $DISPLAY nor "
                f"$WAYLAND_DISPLAY is set: no desktop session). {CLI_HINT[0].upper()}"
                f"{CLI_HINT[1:]}.")
    if wayland and not wanted:
        return None  # Qt uses its Wayland plugin
    xcb = missing(XCB_LIBRARIES, loads)
    if xcb:
        names = ", ".join(so for so, _pkg in xcb)
        return (f"Qt cannot open a window on X11: system libraries are missing: {names}. "
                f"Install them with: {_install_line(xcb)} — meanwhile {CLI_HINT}.")
    if not answers(display):
        return (f"The X display {display!r} does not answer (is the desktop session still "
                f"running, or ssh without -X?). Meanwhile {CLI_HINT}.")
    return None


class Probes(TypedDict, total=False):
    """What :func:`problem` looks at, for a caller (or a test) to give instead."""

    screenshot: bool
    environ: Mapping[str, str] | None
    platform: str
    loads: Callable[[str], bool]
    answers: Callable[[str], bool]


def needs_offscreen(**probes: Unpack[Probes]) -> bool:
    """True when a screenshot must be rendered off screen: no window can open here."""
    return problem(**probes) is not None
