"""The ``pdcp-studio`` command line: one small module per subcommand.

Each module in ``COMMAND_MODULES`` has ``add_subparser(subparsers)``, which registers
its command and sets ``func`` to a ``run(args) -> int``. Modules import heavy
libraries (python-can, networkx, Qt) inside ``run`` only, so a headless command
starts fast and never loads Qt.

Exit status: 0 success, 2 bad input (``BadInput``: a file that does not parse or
validate, named with where and why; ``BusUrlError``: a ``--bus`` URL that is malformed or names
what python-can or the simulator does not have, the same line from every command), 1 any
other failure.
"""

from __future__ import annotations

import argparse
import importlib
import logging
import os
import sys
from collections.abc import Sequence

from pdcp_studio import __version__
from pdcp_studio.bus.session.urls import BusUrlError
from pdcp_studio.errors import ConfigFormatError, PdcpError, SystemFileError
from pdcp_studio.model.safe_text import shown

# Order = order in --help. Under ``pdcp_studio.cli``: files and systems offline here, the
# commands on a live prosthesis or bus in ``live/``.
COMMAND_MODULES = (
    "gui",
    "config_cmd",
    "listing",
    "plan",
    "live.apply",
    "live.policy",
    "history",
    "archive",
    "live.param",
    "check",
    "live.scan",
    "sim",
    "live.arbitrator",
    "monitor",
    "live.hostlink_test",
    "live.can_bridge",
    "doctor",
)

EXIT_OK = 0
EXIT_FAILURE = 1
EXIT_BAD_INPUT = 2


class BadInput(PdcpError):
    """Raised by a command for input the user must fix (exit status 2)."""


def build_parser(commands: Sequence[str] = COMMAND_MODULES) -> argparse.ArgumentParser:
    """The parser of ``commands`` (all of them unless the desktop app alone is asked for)."""
    parser = argparse.ArgumentParser(
        prog="pdcp-studio",
        description="See, configure and repair the PDCP bus inside a powered prosthesis.",
    )
    parser.add_argument("--version", action="version", version=f"pdcp-studio {__version__}")
    parser.add_argument("--lang", metavar="LANG", default=None,
                        help="the desktop app's language, e.g. de or en (default: the system's)")
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in commands:
        importlib.import_module(f"pdcp_studio.cli.{name}").add_subparser(subparsers)
    return parser


class _StderrWarnings(logging.Handler):
    """A warning the user must see (a bitrate other than PDCP's) on stderr as one line with
    the program's prefix, like its errors; the stream is looked up at each line."""

    def __init__(self) -> None:
        super().__init__(logging.WARNING)
        self.setFormatter(logging.Formatter("pdcp-studio: warning: %(message)s"))

    def emit(self, record: logging.LogRecord) -> None:
        try:
            print(self.format(record), file=sys.stderr)
        except Exception:
            self.handleError(record)


def _warnings_to_stderr() -> None:
    logger = logging.getLogger("pdcp_studio.bus.session.urls")
    if not any(isinstance(h, _StderrWarnings) for h in logger.handlers):
        logger.addHandler(_StderrWarnings())


def _commands_for(argv: Sequence[str]) -> Sequence[str]:
    """Only ``gui`` for the desktop app (``gui …`` or bare): starting it does not load the
    other commands' modules. Its usage, help and errors read the same either way (the
    command list shows as ``COMMAND``); anything else gets every command."""
    if not argv or argv[0] == "gui":
        return ("gui",)
    return COMMAND_MODULES


def main(argv: Sequence[str] | None = None) -> int:
    _warnings_to_stderr()
    parser = build_parser(_commands_for(sys.argv[1:] if argv is None else argv))
    args = parser.parse_args(argv)
    if args.command is None:
        # Bare `pdcp-studio` opens the desktop app on the built-in simulated prosthesis
        # (contracts §2); `pdcp-studio gui` alone keeps the start page.
        from pdcp_studio.app.window.support import DEFAULT_BUS  # Qt-free

        args = parser.parse_args(["gui", "--bus", DEFAULT_BUS,
                                  *(["--lang", args.lang] if args.lang else [])])
        if getattr(args, "func", None) is None:
            parser.print_help()
            return EXIT_OK
    try:
        code = int(args.func(args) or 0)
        sys.stdout.flush()  # a reader that has gone shows here, not at the interpreter's exit
        return code
    except BrokenPipeError:
        return _reader_gone()
    except (BadInput, BusUrlError, ConfigFormatError, SystemFileError) as err:
        print(f"pdcp-studio: {shown(str(err), newlines=True)}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except PdcpError as err:
        print(f"pdcp-studio: error: {shown(str(err), newlines=True)}", file=sys.stderr)
        return EXIT_FAILURE
    except KeyboardInterrupt:
        print("pdcp-studio: interrupted", file=sys.stderr)
        return 130
    except OSError as err:
        print(f"pdcp-studio: error: {shown(os_error_text(err), newlines=True)}",
              file=sys.stderr)
        return EXIT_FAILURE


def _reader_gone() -> int:
    """Output piped to a reader that stopped reading (``| head``): exit quietly, as command
    line tools do, with the failure status (not everything was delivered). What is still
    buffered goes to the null device, so the interpreter's own flush at exit does not
    complain either."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError):  # stdout is not a file descriptor (a test's capture)
        pass
    return EXIT_FAILURE


def os_error_text(err: OSError) -> str:
    """An operating-system failure in words that name the file and, for a path that
    cannot exist, the folder that is missing (not "[Errno 2] …"); the app uses the same
    words (``storage/write_failure.py``)."""
    from pdcp_studio.storage.write_failure import os_error_text as plain_words

    return plain_words(err)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
