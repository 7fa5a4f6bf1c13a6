""""Nothing stored" reads alike in the preview and in the arbitrator's result (issue 26).

Found by tests/bus/test_effect_property.py: the preview gave the CRC of an empty collection's
bytes (0xFBAC) where the arbitrator said None, and the arbitrator itself said 0xFBAC once a
policy alone had been written (its memory then holds an empty collection beside the policy).
"""

from __future__ import annotations

from pdcp_studio.bus.session.change_road import preview_change
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.transaction import Change, Policy, config_crc, crc_of_bytes
from pdcp_studio.model.configuration import ConfigCollection, StoredConfiguration
from pdcp_studio.storage import config_codec


def test_an_empty_collection_is_nothing_stored():
    assert config_crc(ConfigCollection([])) is None
    assert crc_of_bytes(config_codec.dumps(ConfigCollection([]))) is None
    assert crc_of_bytes(None) is None


def test_a_configuration_with_no_links_is_stored():
    empty_cfg = ConfigCollection([StoredConfiguration(index=1, links=[])])
    assert (config_crc(empty_cfg) or "").startswith("0x")


def test_a_policy_alone_leaves_nothing_stored_in_preview_result_and_history():
    with open_session("sim:thesis-test1", frame_events=False) as session:
        assert session.wait_settled(20)
        change = Change("policy autoconfigure off", policy=Policy(autoconfigure=False))
        effect = preview_change(session, change).effect
        assert effect is not None
        result = session.transact(change)
        assert result.written
        assert (effect.crc_before, effect.crc_after) == (None, None)
        assert (result.config_crc_before, result.config_crc_after) == (None, None)
        # A change after it still starts from "nothing stored".
        back = session.transact(Change("policy autoconfigure on", policy=Policy()))
        assert back.written and back.config_crc_before is None
