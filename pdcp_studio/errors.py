"""One exception root for PDCP Studio, with a subclass per layer.

Messages say *where* (a byte offset, a JSON path, a node ID) and *why*, so the
CLI and the app can show them to a user unchanged.
"""

from __future__ import annotations


class PdcpError(Exception):
    """Root of every error PDCP Studio raises on purpose."""


class FrameError(PdcpError):
    """A CAN frame or PDCP message is malformed (bad DLC, code or range)."""


class ParameterError(PdcpError):
    """A parameter value does not fit its catalog layout or is not writable."""


class ProfileError(PdcpError):
    """A profile value or profile-tree file is invalid."""


class ModelError(PdcpError):
    """A system violates a rule of the domain model (duplicate device, bad link...)."""


class ConfigFormatError(PdcpError):
    """A stored-configuration byte string is malformed.

    ``offset`` is the byte offset of the offending record (or -1 if none applies).
    """

    def __init__(self, message: str, offset: int = -1) -> None:
        self.offset = offset
        self.reason = message
        super().__init__(f"offset {offset}: {message}" if offset >= 0 else message)


class SystemFileError(PdcpError):
    """A ``pdcp-system/1`` document is invalid; ``path`` is the JSON path."""

    def __init__(self, message: str, path: str = "") -> None:
        self.path = path
        self.reason = message
        super().__init__(f"{path}: {message}" if path else message)


class EngineError(PdcpError):
    """The profile layer was asked something impossible."""


class TransportError(PdcpError):
    """A bus or serial link failed (cable pulled, adapter missing...)."""


class BusTimeoutError(TransportError):
    """A request got no answer within its timeout and retries."""


class NodeIdExhaustedError(PdcpError):
    """All 254 node IDs are in use by devices and output channels."""
