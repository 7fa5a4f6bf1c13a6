"""CRC-16/CCITT-FALSE: the stored configuration's checksum record and the host link's frame check.

One implementation for both, on ``binascii.crc_hqx`` (C speed): poly 0x1021, init 0xFFFF, no
reflection, no final XOR. Check value: ``crc16_ccitt_false(b"123456789") == 0x29B1``.
"""

from __future__ import annotations

import binascii

CRC_INIT = 0xFFFF


def crc16_ccitt_false(data: bytes | bytearray | memoryview, crc: int = CRC_INIT) -> int:
    """The CRC of ``data``; pass a previous result as ``crc`` to continue over several pieces."""
    return binascii.crc_hqx(data, crc)
