"""How alike two channels are (thesis listing 4.9, reference §2 ``determine_similarity``).

The profile dominates: each equal, non-zero leading component is worth 8, more than the
type can ever add (control mode 4 + data type 2 + byte size 1 = 7), so the type only
breaks ties between equally deep profile matches. Keeping the breakdown lets a plan say
*why* a candidate won, which is what makes a prosthetist trust it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

from pdcp_studio.model.channel_type import (
    BYTE_SIZE_MASK,
    CONTROL_MODE_MASK,
    DATA_TYPE_MASK,
)
from pdcp_studio.model.profile import common_prefix_depth

PROFILE_STEP = 8
CONTROL_MODE_SCORE = 4
DATA_TYPE_SCORE = 2
BYTE_SIZE_SCORE = 1
#: The most the type part can add; a deeper profile match always beats it.
MAX_TYPE_SCORE = CONTROL_MODE_SCORE + DATA_TYPE_SCORE + BYTE_SIZE_SCORE
#: "Shares at least the root profile component" (reference §2 Decision).
MIN_CANDIDATE_SCORE = PROFILE_STEP


@dataclass(frozen=True)
class Similarity:
    """A similarity score and the parts it is made of."""

    total: int
    profile_depth: int
    control_mode: bool
    data_type: bool
    byte_size: bool

    @property
    def shares_root(self) -> bool:
        return self.profile_depth >= 1

    def describe(self) -> str:
        """``23 = profile 2 levels (16) + control mode (4) + data type (2) + byte size (1)``."""
        parts = []
        if self.profile_depth:
            levels = "level" if self.profile_depth == 1 else "levels"
            parts.append(
                f"profile {self.profile_depth} {levels} ({self.profile_depth * PROFILE_STEP})"
            )
        else:
            parts.append("no profile component in common (0)")
        for flag, name, score in (
            (self.control_mode, "control mode", CONTROL_MODE_SCORE),
            (self.data_type, "data type", DATA_TYPE_SCORE),
            (self.byte_size, "byte size", BYTE_SIZE_SCORE),
        ):
            if flag:
                parts.append(f"{name} ({score})")
        return f"{self.total} = " + " + ".join(parts)

    def as_json(self) -> dict[str, Any]:
        return {
            "total": self.total,
            "profile_depth": self.profile_depth,
            "control_mode": self.control_mode,
            "data_type": self.data_type,
            "byte_size": self.byte_size,
        }


def type_score(a_type: int, b_type: int) -> int:
    """The type part of the score (0…7): control mode 4, data type 2, byte size 1."""
    diff = a_type ^ b_type
    return (
        (0 if diff & CONTROL_MODE_MASK else CONTROL_MODE_SCORE)
        + (0 if diff & DATA_TYPE_MASK else DATA_TYPE_SCORE)
        + (0 if diff & BYTE_SIZE_MASK else BYTE_SIZE_SCORE)
    )


class Typed(Protocol):
    """Anything with a channel type and profile: a Channel, a StoredChannel, a Candidate."""

    type: int
    profile: int


def _type_profile(x: int | Typed | tuple[int, int], name: str) -> tuple[int, int]:
    if isinstance(x, tuple) and len(x) == 2:
        return int(x[0]), int(x[1])
    if hasattr(x, "type") and hasattr(x, "profile"):
        return int(x.type), int(x.profile)
    raise TypeError(f"determine_similarity: {name} must be a channel or a (type, profile) pair")


def determine_similarity(a: int | Typed | tuple[int, int], b: int | Typed | tuple[int, int],
                         b_type: int | None = None, b_profile: int | None = None) -> Similarity:
    """Listing 4.9: 8 per equal leading non-zero component, then 4/2/1 for the type fields.

    Takes two channels as the listing does (anything with ``type`` and ``profile``, or
    ``(type, profile)`` pairs), or four numbers ``(a_type, a_profile, b_type, b_profile)``.

    >>> determine_similarity(0x5000, 0x1110, 0x5000, 0x1100).total
    23
    >>> determine_similarity((0x5000, 0x1110), (0x5000, 0x1100)).total
    23
    """
    if b_type is None and b_profile is None:
        (a_type, a_profile), (b_type, b_profile) = (_type_profile(a, "a"),
                                                    _type_profile(b, "b"))
    elif isinstance(a, int) and isinstance(b, int) and b_type is not None \
            and b_profile is not None:
        a_type, a_profile = a, b
    else:
        raise TypeError("determine_similarity takes two channels or four numbers")
    return similarity_at(common_prefix_depth(a_profile, b_profile), a_type, b_type)


def similarity_at(depth: int, a_type: int, b_type: int) -> Similarity:
    """The similarity of two channels whose profiles share ``depth`` leading components."""
    diff = a_type ^ b_type
    cm = not diff & CONTROL_MODE_MASK
    dt = not diff & DATA_TYPE_MASK
    bs = not diff & BYTE_SIZE_MASK
    total = (
        depth * PROFILE_STEP
        + (CONTROL_MODE_SCORE if cm else 0)
        + (DATA_TYPE_SCORE if dt else 0)
        + (BYTE_SIZE_SCORE if bs else 0)
    )
    return Similarity(total, depth, cm, dt, bs)
