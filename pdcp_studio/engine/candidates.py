"""Candidate channels indexed by profile prefix (listing 4.8 without scanning every channel).

Because one more equal profile component (8) outweighs any type match (at most 7), the most
similar candidate is always among those sharing the *longest* prefix with the query. So the
search looks at the bucket of the query's full prefix first and walks up one level only when
that bucket holds no usable candidate.

Inside a bucket, candidates are grouped by the type fields that score (control mode, data
type, byte size), each group sorted by the tie-break order (lower profile, then lower VID,
PID, serial, index). The best candidate of a bucket is then the best of the groups' first
usable members, which costs a handful of comparisons instead of a walk over the bucket.

Outputs that already feed a sole-access input are not free for another one. The index keeps
a second set of groups holding only the outputs still free for sole access; the profile
layer moves an output out of it (``take``) and back (``release``) as links come and go, so
a crowded prosthesis — most outputs taken — is searched as fast as an empty one.
"""

from __future__ import annotations

from bisect import bisect_left
from collections.abc import Callable, Iterable, Iterator
from typing import NamedTuple

from pdcp_studio.engine.similarity import Similarity, similarity_at, type_score
from pdcp_studio.model import profile as prof
from pdcp_studio.model.channel_type import BYTE_SIZE_MASK, CONTROL_MODE_MASK, DATA_TYPE_MASK
from pdcp_studio.model.refs import ChannelRef, DeviceKey

_SCORED = CONTROL_MODE_MASK | DATA_TYPE_MASK | BYTE_SIZE_MASK


class Candidate(NamedTuple):
    """A present channel that may be chosen: its reference, type and profile."""

    ref: ChannelRef
    type: int
    profile: int


# A group member: (profile, ref, candidate) sorts in the tie-break order (refs are unique
# in a group, so the candidate itself never decides).
_Entry = tuple[int, ChannelRef, Candidate]
_Groups = dict[int, list[_Entry]]  # scored type bits → members, sorted


def _key(depth: int, profile: int) -> tuple[int, int]:
    return depth, profile >> (16 - 4 * depth)


def _keys(profile: int) -> Iterator[tuple[int, int]]:
    for depth in range(1, prof.depth(profile) + 1):
        yield _key(depth, profile)


class CandidateIndex:
    """Present channels of one direction, bucketed by every prefix of their profile."""

    def __init__(self, candidates: Iterable[Candidate]) -> None:
        self._all: dict[tuple[int, int], _Groups] = {}
        self._sole_free: dict[tuple[int, int], _Groups] = {}
        for c in candidates:
            entry = (c.profile, c.ref, c)
            for key in _keys(c.profile):
                for table in (self._all, self._sole_free):
                    table.setdefault(key, {}).setdefault(c.type & _SCORED, []).append(entry)
        for table in (self._all, self._sole_free):
            for groups in table.values():
                for members in groups.values():
                    members.sort()

    # -- sole-access bookkeeping ------------------------------------------------------
    def take(self, c: Candidate) -> None:
        """``c`` now feeds a sole-access input: not free for another one."""
        entry = (c.profile, c.ref, c)
        for key in _keys(c.profile):
            members = self._sole_free[key][c.type & _SCORED]
            i = bisect_left(members, entry)
            if i < len(members) and members[i][1] == c.ref:
                del members[i]

    def release(self, c: Candidate) -> None:
        """``c`` feeds no sole-access input any more: free again."""
        entry = (c.profile, c.ref, c)
        for key in _keys(c.profile):
            members = self._sole_free[key][c.type & _SCORED]
            i = bisect_left(members, entry)
            if i == len(members) or members[i][1] != c.ref:
                members.insert(i, entry)

    # -- listing 4.8 ----------------------------------------------------------------------
    def best(
        self,
        q_type: int,
        q_profile: int,
        *,
        exclude: DeviceKey | None = None,
        free: Callable[[ChannelRef], bool] | None = None,
        sole_free: bool = False,
    ) -> tuple[Candidate, Similarity] | None:
        """The most similar usable candidate sharing at least the root component, or None.

        ``exclude`` is a device whose channels are not candidates (no same-device links);
        ``free`` says whether a candidate may still be connected; ``sole_free`` searches
        only the candidates not ``take``-n (outputs still free for a sole-access input).
        """
        table = self._sole_free if sole_free else self._all
        for depth in range(prof.depth(q_profile), 0, -1):
            groups = table.get(_key(depth, q_profile))
            if not groups:
                continue
            best: tuple[int, int, ChannelRef, Candidate] | None = None
            for bits, members in groups.items():
                score = type_score(q_type, bits)
                for profile, ref, c in members:
                    if exclude is not None and ref[:3] == exclude:
                        continue
                    if free is not None and not free(ref):
                        continue
                    if best is None or (-score, profile, ref) < (-best[0], best[1], best[2]):
                        best = (score, profile, ref, c)
                    break  # later members of this group only lose the tie-break
            if best is not None:
                c = best[3]
                return c, similarity_at(depth, q_type, c.type)
        return None

    def sharing_root(self, q_profile: int) -> Iterator[Candidate]:
        """Every candidate with the query's root component (for explanations), lazily and
        in a fixed order (by scored type bits, then profile, then reference)."""
        if prof.depth(q_profile) == 0:
            return
        groups = self._all.get(_key(1, q_profile), {})
        for bits in sorted(groups):
            for entry in groups[bits]:
                yield entry[2]
