"""Function codes (data byte 0) and response codes of the PDCP lower layer.

From 001 figure 3.1 as restated in reference §1. A response's code is its request's code
with bit 7 set (0x03 → 0x83); the Device Beacon (0x0A) has no response.
"""

from __future__ import annotations

from enum import IntEnum


class FunctionCode(IntEnum):
    """Every function code in use. ``code.title`` is the name a bus monitor shows."""

    BIND_REQUEST = 0x01
    BIND_RESPONSE = 0x81
    GET_PARAMETER = 0x03
    GET_PARAMETER_RESPONSE = 0x83
    SET_PARAMETER = 0x04
    SET_PARAMETER_RESPONSE = 0x84
    SUSPEND = 0x08
    SUSPEND_RESPONSE = 0x88
    RELEASE = 0x09
    RELEASE_RESPONSE = 0x89
    BEACON = 0x0A
    RESET = 0x0B
    RESET_RESPONSE = 0x8B
    CONFIGURE_GET_BULK = 0x0C
    CONFIGURE_GET_BULK_RESPONSE = 0x8C
    CONFIGURE_SET_BULK = 0x0D
    CONFIGURE_SET_BULK_RESPONSE = 0x8D
    BULK_DATA = 0x0E
    BULK_DATA_RESPONSE = 0x8E
    UPDATE_DATA_CHANNEL = 0x0F
    UPDATE_DATA_CHANNEL_RESPONSE = 0x8F

    @property
    def title(self) -> str:
        """The 001 name, e.g. "Get Device Parameter Response"."""
        return _TITLES[self]

    @property
    def label(self) -> str:
        """Code and name, e.g. "0x83 Get Device Parameter Response" (prefix of error messages)."""
        return _LABELS[self]

    @property
    def is_response(self) -> bool:
        return bool(self.value & 0x80)

    @property
    def response(self) -> FunctionCode | None:
        """The code that answers this request (None for responses and the beacon)."""
        if self.is_response or self is FunctionCode.BEACON:
            return None
        return FunctionCode(self.value | 0x80)

    @property
    def request(self) -> FunctionCode | None:
        """The request this response answers (None for requests)."""
        return FunctionCode(self.value & 0x7F) if self.is_response else None


_TITLES: dict[FunctionCode, str] = {
    FunctionCode.BIND_REQUEST: "Bind Device Request",
    FunctionCode.BIND_RESPONSE: "Bind Device Request Response",
    FunctionCode.GET_PARAMETER: "Get Device Parameter",
    FunctionCode.GET_PARAMETER_RESPONSE: "Get Device Parameter Response",
    FunctionCode.SET_PARAMETER: "Set Device Parameter",
    FunctionCode.SET_PARAMETER_RESPONSE: "Set Device Parameter Response",
    FunctionCode.SUSPEND: "Suspend Device",
    FunctionCode.SUSPEND_RESPONSE: "Suspend Device Response",
    FunctionCode.RELEASE: "Release Device",
    FunctionCode.RELEASE_RESPONSE: "Release Device Response",
    FunctionCode.BEACON: "Device Beacon",
    FunctionCode.RESET: "Reset Device",
    FunctionCode.RESET_RESPONSE: "Reset Device Response",
    FunctionCode.CONFIGURE_GET_BULK: "Configure Get Bulk Data Transfer",
    FunctionCode.CONFIGURE_GET_BULK_RESPONSE: "Configure Get Bulk Data Transfer Response",
    FunctionCode.CONFIGURE_SET_BULK: "Configure Set Bulk Data Transfer",
    FunctionCode.CONFIGURE_SET_BULK_RESPONSE: "Configure Set Bulk Data Transfer Response",
    FunctionCode.BULK_DATA: "Bulk Data Transfer",
    FunctionCode.BULK_DATA_RESPONSE: "Bulk Data Transfer Response",
    FunctionCode.UPDATE_DATA_CHANNEL: "Update Data Channel",
    FunctionCode.UPDATE_DATA_CHANNEL_RESPONSE: "Update Data Channel Response",
}

#: Each code's label, made once (every message is built with it at hand for its errors).
_LABELS: dict[FunctionCode, str] = {code: f"0x{code.value:02X} {title}"
                                    for code, title in _TITLES.items()}
#: Byte 0 → its FunctionCode: what ``FunctionCode(byte)`` gives, as one dict look-up (every
#: frame decoded asks it; Enum's call machinery costs microseconds each time).
FUNCTION_CODES: dict[int, FunctionCode] = {code.value: code for code in FunctionCode}

#: Allowed DLC (min, max), including byte 0 — reference §1, the authoritative table.
#: (001 figure 3.1 itself prints 5 for 0x0C and 1 for 0x88/0x89/0x8B; its own §3.2 frame
#: layouts and the worked examples of §3.3 give the values below.)
DLC_RANGE: dict[FunctionCode, tuple[int, int]] = {
    FunctionCode.BIND_REQUEST: (7, 7),
    FunctionCode.BIND_RESPONSE: (8, 8),
    FunctionCode.GET_PARAMETER: (3, 3),
    FunctionCode.GET_PARAMETER_RESPONSE: (4, 8),
    FunctionCode.SET_PARAMETER: (4, 7),
    FunctionCode.SET_PARAMETER_RESPONSE: (5, 8),
    FunctionCode.SUSPEND: (3, 3),
    FunctionCode.SUSPEND_RESPONSE: (4, 4),
    FunctionCode.RELEASE: (1, 1),
    FunctionCode.RELEASE_RESPONSE: (2, 2),
    FunctionCode.BEACON: (1, 1),
    FunctionCode.RESET: (1, 1),
    FunctionCode.RESET_RESPONSE: (2, 2),
    FunctionCode.CONFIGURE_GET_BULK: (3, 3),
    FunctionCode.CONFIGURE_GET_BULK_RESPONSE: (6, 6),
    FunctionCode.CONFIGURE_SET_BULK: (5, 5),
    FunctionCode.CONFIGURE_SET_BULK_RESPONSE: (6, 6),
    FunctionCode.BULK_DATA: (3, 8),
    FunctionCode.BULK_DATA_RESPONSE: (2, 2),
    FunctionCode.UPDATE_DATA_CHANNEL: (2, 2),
    FunctionCode.UPDATE_DATA_CHANNEL_RESPONSE: (3, 3),
}


class ResponseCode(IntEnum):
    """Byte 1 of a response. USE_BULK is valid only in 0x83 / 0x84."""

    FAILURE = 0
    SUCCESS = 1
    USE_BULK = 2

    @property
    def title(self) -> str:
        return ("failure", "success", "use bulk data transfer")[self]


def describe_code(code: int) -> str:
    """Name any byte-0 value, including reserved and deprecated ranges (for a bus monitor)."""
    if not isinstance(code, int) or not 0 <= code <= 0xFF:
        return f"{code!r}: not a byte"
    try:
        return FunctionCode(code).label
    except ValueError:
        pass
    text = f"0x{code:02X}"
    if code in (0x02, 0x05, 0x06, 0x07):
        return f"{text} deprecated command"
    if code in (0x82, 0x85, 0x86, 0x87):
        return f"{text} deprecated response"
    if 0x10 <= code <= 0x4F:
        return f"{text} reserved for future system commands"
    if 0x50 <= code <= 0x7F:
        return f"{text} reserved for module-specific commands"
    if 0x90 <= code <= 0xCF:
        return f"{text} reserved for future system responses"
    if 0xD0 <= code <= 0xFE:
        return f"{text} reserved for device-specific responses"
    # 0x00, 0x80, 0x8A (a beacon has no response) and 0xFF.
    return f"{text} undefined"
