"""Candidate channels indexed by profile prefix (listing 4.8 without scanning every channel).

Because one more equal profile component (8) outweighs any type match (at most 7), the most
similar candidate is always among those sharing the *longest* prefix with the query. So the
search looks at the bucket of the query's full prefix first and walks up one level only when
that bucket holds no free candidate. Buckets are pre-sorted by the tie-break order (lower
profile, then lower VID, PID, serial, index), so the first best score found wins ties.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import NamedTuple

from pdcp_studio.engine.similarity import MAX_TYPE_SCORE, Similarity, type_score
from pdcp_studio.model.refs import ChannelRef, DeviceKey

_SHIFTS = (12, 8, 4, 0)


class Candidate(NamedTuple):
    """A present channel that may be chosen: its reference, type and profile."""

    ref: ChannelRef
    type: int
    profile: int


def _prefix_depth(profile: int) -> int:
    """Leading non-zero components (a zero component ends the path)."""
    depth = 0
    for shift in _SHIFTS:
        if (profile >> shift) & 0xF == 0:
            break
        depth += 1
    return depth


def _key(depth: int, profile: int) -> tuple[int, int]:
    return depth, profile >> (16 - 4 * depth)


class CandidateIndex:
    """Present channels of one direction, bucketed by every prefix of their profile."""

    def __init__(self, candidates: Iterable[Candidate]) -> None:
        self._buckets: dict[tuple[int, int], list[Candidate]] = {}
        for c in candidates:
            for depth in range(1, _prefix_depth(c.profile) + 1):
                self._buckets.setdefault(_key(depth, c.profile), []).append(c)
        for bucket in self._buckets.values():
            bucket.sort(key=lambda c: (c.profile, c.ref))

    def best(
        self,
        q_type: int,
        q_profile: int,
        *,
        exclude: DeviceKey | None = None,
        free: Callable[[ChannelRef], bool] | None = None,
    ) -> tuple[Candidate, Similarity] | None:
        """The most similar free candidate sharing at least the root component, or None.

        ``exclude`` is a device whose channels are not candidates (no same-device links);
        ``free`` says whether a candidate may still be connected.
        """
        q_depth = _prefix_depth(q_profile)
        for depth in range(q_depth, 0, -1):
            bucket = self._buckets.get(_key(depth, q_profile))
            if not bucket:
                continue
            # Candidates that also match the next component were seen one level deeper
            # and found unusable; a query that ends here has no next component to match.
            shift = 12 - 4 * depth
            next_q = (q_profile >> shift) & 0xF if depth < q_depth else -1
            best: Candidate | None = None
            best_score = -1
            for c in bucket:
                if next_q >= 0 and (c.profile >> shift) & 0xF == next_q:
                    continue
                if exclude is not None and c.ref[:3] == exclude:
                    continue
                if free is not None and not free(c.ref):
                    continue
                score = type_score(q_type, c.type)
                if score > best_score:
                    best, best_score = c, score
                    if score == MAX_TYPE_SCORE:
                        break
            if best is not None:
                diff = q_type ^ best.type
                sim = Similarity(
                    depth * 8 + best_score,
                    depth,
                    not diff & 0x0C00,
                    not diff & 0x3000,
                    not diff & 0xC000,
                )
                return best, sim
        return None

    def sharing_root(self, q_profile: int) -> list[Candidate]:
        """Every candidate with the query's root component (for explanations)."""
        if _prefix_depth(q_profile) == 0:
            return []
        return list(self._buckets.get(_key(1, q_profile), ()))
