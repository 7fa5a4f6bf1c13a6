"""The node-ID pool shared by devices and output channels."""

from __future__ import annotations

import pytest

from pdcp_studio.bus.arbitrator.node_ids import NodeIdPool
from pdcp_studio.errors import NodeIdExhaustedError
from pdcp_studio.model.refs import DeviceKey

A, B = DeviceKey(2, 2, 4), DeviceKey(2, 2, 5)


def test_full_range_is_1_to_254():
    pool = NodeIdPool()
    assert (pool.low, pool.high, pool.capacity, pool.free_count) == (1, 254, 254, 254)
    assert not pool.is_free(0) and not pool.is_free(255)


def test_take_prefers_the_asked_id_then_the_lowest_free():
    pool = NodeIdPool()
    assert pool.take(A, 7) == 7
    assert pool.take(B, 7) == 1  # taken: the lowest free instead
    assert pool.take((A, 1)) == 2  # an output channel shares the pool
    assert pool.owner(7) == A and pool.id_of((A, 1)) == 2
    assert pool.take(A) == 7  # an owner keeps what it holds
    assert pool.take(A, 9) == 9 and pool.is_free(7)  # or moves to a free ID it asks for
    assert len(pool) == 3


def test_release_and_release_where_give_ids_back():
    pool = NodeIdPool()
    pool.take(A)
    pool.take((A, 1))
    pool.take((A, 3))
    pool.take(B)
    assert pool.release(A) == 1
    assert pool.release(A) is None
    freed = pool.release_where(lambda o: isinstance(o, tuple) and o[0] == A)
    assert sorted(freed) == [2, 3]
    assert pool.free_count == 253 and pool.id_of(B) == 4
    pool.clear()
    assert pool.free_count == 254


def test_an_empty_pool_raises_a_clear_error():
    pool = NodeIdPool(1, 3)
    for owner in (A, (A, 1), B):
        pool.take(owner)
    with pytest.raises(NodeIdExhaustedError, match="all 3 node IDs are in use"):
        pool.take((B, 1))
    with pytest.raises(NodeIdExhaustedError):
        pool.lowest_free()
    pool.release(B)
    assert pool.take((B, 1)) == 3
