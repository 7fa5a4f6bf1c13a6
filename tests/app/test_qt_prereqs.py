"""Before Qt starts: a missing system library or display is one clear message (never Qt's
abort), naming the package to install or the alternative."""

from __future__ import annotations

import os
import subprocess
import sys

from pdcp_studio.app import qt_prereqs as q


def _loads_all_but(*gone: str):
    return lambda so: so not in gone


def test_all_there_with_an_answering_display_is_fine():
    assert q.problem(environ={"DISPLAY": ":0"}, platform="linux",
                     loads=_loads_all_but(), answers=lambda d: True) is None


def test_missing_xcb_libraries_name_their_packages():
    why = q.problem(environ={"DISPLAY": ":0"}, platform="linux",
                    loads=_loads_all_but("libxcb-cursor.so.0", "libxcb-icccm.so.4",
                                         "libxcb-keysyms.so.1"), answers=lambda d: True)
    assert why is not None
    assert "sudo apt-get install libxcb-cursor0 libxcb-icccm4 libxcb-keysyms1" in why
    assert "--screenshot" in why and "pdcp-studio --help" in why


def test_missing_gui_library_is_named_even_for_a_screenshot():
    why = q.problem(screenshot=True, environ={}, platform="linux",
                    loads=_loads_all_but("libEGL.so.1"), answers=lambda d: True)
    assert why is not None and "libEGL.so.1" in why and "libegl1" in why


def test_no_display_points_at_screenshot_and_the_cli():
    why = q.problem(environ={}, platform="linux", loads=_loads_all_but(),
                    answers=lambda d: True)
    assert why is not None and "--screenshot" in why and "no desktop session" in why
    assert q.problem(screenshot=True, environ={}, platform="linux", loads=_loads_all_but(),
                     answers=lambda d: True) is None


def test_a_display_that_does_not_answer_is_said():
    why = q.problem(environ={"DISPLAY": ":42"}, platform="linux", loads=_loads_all_but(),
                    answers=lambda d: False)
    assert why is not None and "':42' does not answer" in why


def test_offscreen_wayland_and_other_systems_are_left_to_qt():
    ok = _loads_all_but("libxcb-cursor.so.0")
    assert q.problem(environ={"QT_QPA_PLATFORM": "offscreen"}, platform="linux",
                     loads=ok) is None
    assert q.problem(environ={"WAYLAND_DISPLAY": "wayland-0"}, platform="linux",
                     loads=ok) is None
    assert q.problem(environ={}, platform="win32", loads=lambda so: False) is None


def test_apt_packages_cover_every_library():
    assert set(q.APT_PACKAGES) == set(q.GUI_LIBRARIES.values()) | set(q.XCB_LIBRARIES.values())


def test_the_real_x_probe_says_no_for_a_display_that_is_not_there():
    assert q.x_server_answers(":9731") is False


def test_the_app_without_a_display_exits_1_with_the_message_not_an_abort(tmp_path):
    env = {k: v for k, v in os.environ.items()
           if k not in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
    for argv in ([], ["gui"]):
        done = subprocess.run([sys.executable, "-m", "pdcp_studio", *argv], env=env,
                              capture_output=True, text=True, timeout=60, cwd=tmp_path)
        assert done.returncode == 1, done.stderr
        assert "no desktop session" in done.stderr and "--screenshot" in done.stderr
        assert done.stderr.count("\n") == 1  # one message, no traceback, no Qt abort
