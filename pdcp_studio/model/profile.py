"""Channel profiles: 16-bit paths of 4-bit components (reference §1 "Channel profile").

``0x4620`` is Sensor (4) → Accelerometer (6) → Wrist (2). ``0x0000`` is the null
profile (invalid). Even components are standard, odd ones vendor-reserved; a lower
value means a higher priority.
"""

from __future__ import annotations

NULL_PROFILE = 0x0000
MAX_DEPTH = 4


def check_profile(value: int) -> int:
    """Return ``value`` if it is a 16-bit profile, else raise ValueError."""
    if not isinstance(value, int) or not 0 <= value <= 0xFFFF:
        raise ValueError(f"profile {value!r} is not a 16-bit value")
    return value


def components(profile: int) -> tuple[int, ...]:
    """The path from the root: the nibbles up to the first zero nibble."""
    check_profile(profile)
    out = []
    for shift in (12, 8, 4, 0):
        nibble = (profile >> shift) & 0xF
        if nibble == 0:
            break
        out.append(nibble)
    return tuple(out)


def depth(profile: int) -> int:
    return len(components(profile))


def from_components(path: tuple[int, ...] | list[int]) -> int:
    """Concatenate 4-bit components from the root, padded with zero nibbles."""
    if len(path) > MAX_DEPTH:
        raise ValueError(f"a profile path has at most {MAX_DEPTH} components, not {len(path)}")
    value = 0
    for i, comp in enumerate(path):
        if not 1 <= comp <= 0xF:
            raise ValueError(f"profile component {comp} is not 1…15")
        value |= comp << (12 - 4 * i)
    return value


def common_prefix_depth(a: int, b: int) -> int:
    """How many leading components ``a`` and ``b`` share (zero components never match)."""
    n = 0
    for x, y in zip(components(a), components(b), strict=False):
        if x != y:
            break
        n += 1
    return n


def parent(profile: int) -> int:
    """The profile one level up (the null profile for a root)."""
    path = components(profile)
    return from_components(path[:-1]) if path else NULL_PROFILE


def is_null(profile: int) -> bool:
    return profile == NULL_PROFILE


def is_vendor_component(component: int) -> bool:
    """Odd component values are reserved for vendors."""
    return component % 2 == 1


def is_well_formed(profile: int) -> bool:
    """True unless a non-zero nibble follows a zero one (e.g. 0x2020) or it is null."""
    if profile == NULL_PROFILE:
        return False
    return from_components(components(profile)) == profile


def fmt(value: int) -> str:
    """Profiles and types are written ``0x%04X`` everywhere."""
    return f"0x{value:04X}"
