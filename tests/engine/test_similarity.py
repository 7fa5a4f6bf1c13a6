"""determine_similarity (listing 4.9) and the prefix-indexed candidate search (listing 4.8)."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pdcp_studio.engine import determine_similarity
from pdcp_studio.engine.candidates import Candidate, CandidateIndex
from pdcp_studio.model import Channel, ChannelRef, DeviceKey, Direction, StoredChannel

U8_POS = 0x5000


def naive(a_type: int, a_profile: int, b_type: int, b_profile: int) -> int:
    """Listing 4.9 word for word."""
    s = 0
    for shift in (12, 8, 4, 0):
        ca, cb = (a_profile >> shift) & 0xF, (b_profile >> shift) & 0xF
        if ca == cb and ca != 0:
            s += 8
        else:
            break
    s += 4 if (a_type & 0x0C00) == (b_type & 0x0C00) else 0
    s += 2 if (a_type & 0x3000) == (b_type & 0x3000) else 0
    s += 1 if (a_type & 0xC000) == (b_type & 0xC000) else 0
    return s


def test_reference_example_is_23():
    sim = determine_similarity(U8_POS, 0x1110, U8_POS, 0x1100)
    assert sim.total == 23
    assert (sim.profile_depth, sim.control_mode, sim.data_type, sim.byte_size) == (
        2, True, True, True)
    assert sim.describe() == ("23 = profile 2 levels (16) + control mode (4) + data type (2)"
                              " + byte size (1)")


def test_takes_two_channels_as_the_listing_does():
    a = Channel(1, Direction.OUTPUT, U8_POS, 0x1110)
    b = StoredChannel(1, 2, 2, 5, U8_POS, 0x1100)
    assert determine_similarity(a, b).total == 23
    assert determine_similarity((U8_POS, 0x1110), (U8_POS, 0x1100)).total == 23
    with pytest.raises(TypeError):
        determine_similarity(U8_POS, 0x1110)


def test_components_count_from_the_front_and_stop_at_the_first_difference():
    assert determine_similarity(U8_POS, 0x1234, U8_POS, 0x1234).total == 32 + 7
    assert determine_similarity(U8_POS, 0x1234, U8_POS, 0x1334).total == 8 + 7  # 3rd,4th equal
    assert determine_similarity(U8_POS, 0x2110, U8_POS, 0x1110).total == 7  # root differs


def test_zero_components_never_count():
    assert determine_similarity(U8_POS, 0x1100, U8_POS, 0x1100).profile_depth == 2
    assert determine_similarity(U8_POS, 0x0000, U8_POS, 0x0000).total == 7
    assert determine_similarity(U8_POS, 0x1010, U8_POS, 0x1010).profile_depth == 1


def test_type_fields_score_4_2_1_and_ignore_flags():
    base = 0x5000  # 8-bit, unsigned, position
    assert determine_similarity(base, 0x1000, 0x5400, 0x1000).total == 8 + 2 + 1  # velocity
    assert determine_similarity(base, 0x1000, 0x4000, 0x1000).total == 8 + 4 + 1  # signed
    assert determine_similarity(base, 0x1000, 0xD000, 0x1000).total == 8 + 4 + 2  # 16-bit
    # Sole access, terminal, prescaler and unused bits are not part of the score.
    assert determine_similarity(base, 0x1000, 0x53FF, 0x1000).total == 15


@settings(max_examples=300, deadline=None)
@given(st.integers(0, 0xFFFF), st.integers(0, 0xFFFF), st.integers(0, 0xFFFF),
       st.integers(0, 0xFFFF))
def test_matches_the_listing_and_is_symmetric(at, ap, bt, bp):
    sim = determine_similarity(at, ap, bt, bp)
    assert sim.total == naive(at, ap, bt, bp)
    assert sim == determine_similarity(bt, bp, at, ap)
    assert 0 <= sim.total <= 39


@settings(max_examples=200, deadline=None)
@given(st.integers(0, 0xFFFF), st.integers(0, 0xFFFF), st.integers(0, 0xFFFF),
       st.integers(0, 0xFFFF), st.integers(0, 0xFFFF))
def test_one_more_profile_component_outweighs_any_type(qt, qp, t1, t2, p2):
    """Why the profile dominates: depth d+1 with the worst type beats depth d with the best."""
    deep = determine_similarity(qt, qp, t1, qp)
    shallow = determine_similarity(qt, qp, t2, p2)
    if deep.profile_depth > shallow.profile_depth:
        assert deep.total > shallow.total


# -- the candidate index against a brute-force scan -------------------------------------------
profiles = st.sampled_from([0x1000, 0x1100, 0x1110, 0x1120, 0x1200, 0x1210, 0x2000, 0x2100,
                            0x2110, 0x2120, 0x2200, 0x3000, 0x1111, 0x0000, 0x1010])
types = st.sampled_from([0x5000, 0x7000, 0x4000, 0x5400, 0xD000, 0x1000])


@settings(max_examples=200, deadline=None)
@given(
    st.lists(st.tuples(st.integers(1, 4), st.integers(1, 6), types, profiles), max_size=25,
             unique_by=lambda c: (c[0], c[1])),
    types, profiles, st.one_of(st.none(), st.integers(1, 4)),
    st.frozensets(st.tuples(st.integers(1, 4), st.integers(1, 6))),
)
def test_index_finds_what_scanning_every_candidate_finds(chans, qt, qp, exclude, taken):
    cands = [Candidate(ChannelRef(2, 2, s, i), t, p) for s, i, t, p in chans]
    index = CandidateIndex(reversed(cands))  # listing order must not matter
    excl = DeviceKey(2, 2, exclude) if exclude else None

    def free(r: ChannelRef) -> bool:
        return (r.serial, r.index) not in taken

    got = index.best(qt, qp, exclude=excl, free=free)
    pool = [c for c in cands
            if c.ref.device != excl and free(c.ref) and naive(qt, qp, c.type, c.profile) >= 8]
    if not pool:
        assert got is None
        return
    want = min(pool, key=lambda c: (-naive(qt, qp, c.type, c.profile), c.profile, c.ref))
    assert got is not None
    assert got[0] == want
    assert got[1] == determine_similarity(qt, qp, want.type, want.profile)


@settings(max_examples=150, deadline=None)
@given(
    st.lists(st.tuples(st.integers(1, 4), st.integers(1, 6), types, profiles), max_size=25,
             unique_by=lambda c: (c[0], c[1])),
    types, profiles,
    st.lists(st.tuples(st.booleans(), st.integers(0, 24)), max_size=30),
)
def test_taking_and_releasing_outputs_for_sole_access(chans, qt, qp, moves):
    """The sole-access view equals a scan over the outputs not taken, after any history."""
    cands = [Candidate(ChannelRef(2, 2, s, i), t, p) for s, i, t, p in chans]
    index = CandidateIndex(cands)
    taken: set[ChannelRef] = set()
    for take, n in moves:
        if not cands:
            break
        c = cands[n % len(cands)]
        if take and c.ref not in taken:
            index.take(c)
            taken.add(c.ref)
        elif not take and c.ref in taken:
            index.release(c)
            taken.discard(c.ref)
    got = index.best(qt, qp, sole_free=True)
    pool = [c for c in cands if c.ref not in taken and naive(qt, qp, c.type, c.profile) >= 8]
    want = min(pool, key=lambda c: (-naive(qt, qp, c.type, c.profile), c.profile, c.ref),
               default=None)
    assert (got[0] if got else None) == want
    # Every output is still there for a query without the flag.
    assert sorted(index.sharing_root(qp)) == sorted(
        c for c in cands if qp >> 12 and c.profile >> 12 == qp >> 12)
