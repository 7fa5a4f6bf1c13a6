"""The pure parts of the configuration document: checks of what a configuration holds,
edits, device names, and fitting a configuration to a prosthesis (thesis test 1)."""

from __future__ import annotations

from dataclasses import replace

import pytest

from pdcp_studio.engine import configuration_from_system, plan_autoconfigure
from pdcp_studio.engine.config_checks import check_configuration
from pdcp_studio.engine.config_fit import PRESENT, fit_configuration
from pdcp_studio.model import config_edit as edit
from pdcp_studio.model.config_diff import diff_configurations
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
    UnknownRecord,
)
from pdcp_studio.model.device_names import DeviceCatalogue, unknown_device_name
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.paths import systems_dir
from pdcp_studio.storage import config_codec, system_file

# Appendix D's rig (reference §4): SN4.O1 → SN5.I2, SN5.O3 → SN6.I1, SN5.O5 → SN6.I2.
O4_1 = StoredChannel(1, 2, 2, 4, 0x5000, 0x2120)
I5_2 = StoredChannel(2, 2, 2, 5, 0x5200, 0x2110)
O5_3 = StoredChannel(3, 2, 2, 5, 0x5000, 0x1100)
I6_1 = StoredChannel(1, 2, 2, 6, 0x5300, 0x1110)
O5_5 = StoredChannel(5, 2, 2, 5, 0x7000, 0x1220)
I6_2 = StoredChannel(2, 2, 2, 6, 0x7300, 0x1220)
APPENDIX_D = StoredConfiguration(1, [StoredLink(I5_2, O4_1, 1), StoredLink(I6_1, O5_3, 2),
                                     StoredLink(I6_2, O5_5, 3)])


def _codes(cfg: StoredConfiguration) -> list[str]:
    return [f.code for f in check_configuration(cfg)]


def test_the_appendix_d_configuration_has_no_findings():
    assert check_configuration(APPENDIX_D) == []


def test_a_configuration_saved_from_the_live_system_has_no_findings():
    """The issue's reopened file: no terminal-profile, source or device-data findings."""
    system = system_file.load_path(systems_dir() / "transradial.json")
    if not system.links:
        plan_autoconfigure(system).apply(system)
    data = config_codec.dumps(ConfigCollection([configuration_from_system(system)]))
    (cfg,) = config_codec.loads(data).configurations
    assert cfg.links and check_configuration(cfg) == []


def test_two_sources_for_one_input_is_an_error_naming_the_links():
    cfg = StoredConfiguration(1, [StoredLink(I6_1, O5_3, 1), StoredLink(I6_1, O4_1, 2)])
    (finding,) = [f for f in check_configuration(cfg) if f.code == "two-sources"]
    assert finding.severity.value == "error" and finding.links == (0, 1)
    assert "input 2/2/6#1 is given 2 sources" in finding.message


def test_duplicate_link_same_device_and_both_directions():
    assert _codes(StoredConfiguration(1, [StoredLink(I6_1, O5_3, 1),
                                          StoredLink(I6_1, O5_3, 2)])) == ["duplicate-link"]
    same = StoredConfiguration(1, [StoredLink(I5_2, O5_3, 1)])
    assert _codes(same)[0] == "same-device"  # an error, listed before the profile misfit
    # 2/2/5#2 is an input in link 1 and an output in link 2.
    both = StoredConfiguration(1, [StoredLink(I5_2, O4_1, 1),
                                   StoredLink(I6_1, replace(I5_2, type=0x5000), 2)])
    assert "both-directions" in _codes(both)


def test_sole_access_between_stored_links():
    sole_a = replace(I6_1, type=I6_1.type | 0x0200)
    sole_b = replace(I6_2, type=0x5300 | 0x0200, profile=0x1110)
    cfg = StoredConfiguration(1, [StoredLink(sole_a, O5_3, 1), StoredLink(sole_b, O5_3, 2)])
    (finding,) = [f for f in check_configuration(cfg) if f.code == "sole-access"]
    assert finding.severity.value == "error" and finding.links == (0, 1)
    # One sole-access input per output is fine.
    assert "sole-access" not in _codes(StoredConfiguration(1, [StoredLink(sole_a, O5_3, 1)]))


def test_profile_fitness_and_unknown_profiles():
    misfit = StoredConfiguration(1, [StoredLink(I6_1, O4_1, 1)])  # 0x2120 → 0x1110
    assert _codes(misfit) == ["profile-misfit"]
    unknown = StoredConfiguration(1, [StoredLink(replace(I6_1, profile=0), O4_1, 1)])
    assert _codes(unknown) == []  # a profile of 0 is "not stored", not a misfit
    inconsistent = StoredConfiguration(1, [StoredLink(I5_2, O4_1, 1),
                                           StoredLink(I6_1, replace(O4_1, profile=0x1100), 2)])
    assert "inconsistent-records" in _codes(inconsistent)


def test_edits_keep_unknown_records_and_number_configurations():
    rec = UnknownRecord(0x20, 7)
    coll = ConfigCollection([replace_cfg(APPENDIX_D, unknown=(rec,))], (rec,))
    dup = edit.duplicate_configuration(coll, 0)
    assert [c.index for c in dup.configurations] == [1, 2]
    assert dup.configurations[1].unknown == (rec,) and dup.unknown == (rec,)
    assert coll.configurations[0].index == 1 and len(coll.configurations) == 1  # untouched
    moved = edit.move_configuration(edit.add_configuration(dup), 2, 0)
    assert [len(c.links) for c in moved.configurations] == [0, 3, 3]
    assert [c.index for c in moved.configurations] == [1, 2, 3]
    removed = edit.remove_links(dup, 1, [0])
    assert [lk.index for lk in removed.configurations[1].links] == [1, 2]
    assert len(dup.configurations[1].links) == 3
    added = edit.add_link(removed, 1, O4_1, I5_2)
    assert added.configurations[1].links[-1].index == 3
    edited = edit.set_channel(added, 1, O5_3.ref, profile=0x1110)
    assert [lk.output.profile for lk in edited.configurations[1].links
            if lk.output.ref == O5_3.ref] == [0x1110]
    assert edit.remove_configuration(edited, 0).configurations[0].index == 1
    with pytest.raises(ValueError):
        edit.set_channel(coll, 0, O5_3.ref, type=0x10000)


def replace_cfg(cfg: StoredConfiguration, **changes) -> StoredConfiguration:
    return StoredConfiguration(changes.get("index", cfg.index), list(cfg.links),
                               changes.get("unknown", cfg.unknown))


def test_device_names_from_a_catalogue_or_plainly_unknown():
    key = DeviceKey(2641, 257, 101)
    assert unknown_device_name(key) == "unknown device (2641/257/101)"
    cat = DeviceCatalogue.from_names({DeviceKey(2, 2, 4): "Myo sensor"})
    assert cat.label(DeviceKey(2, 2, 4)) == "Myo sensor"
    assert cat.label(DeviceKey(2, 2, 9)) == "Myo sensor"  # same product
    assert cat.label(key) == "unknown device (2641/257/101)"
    system = system_file.load_path(systems_dir() / "transradial.json")
    named = DeviceCatalogue.from_system(system)
    for k, device in system.devices.items():
        if device.name:
            assert named.label(k) == device.name


def test_fit_against_thesis_test1_shows_the_replacement_and_the_choice():
    system = system_file.load_path(systems_dir() / "thesis-test1.json")
    plan_autoconfigure(system).apply(system)
    stored = configuration_from_system(system)
    other = StoredConfiguration(2, [StoredLink(I6_2, O5_5, 1)])
    system.devices[DeviceKey(2, 2, 5)].present = False  # device 2 replaced by device 3
    system.devices[DeviceKey(2, 2, 6)].present = True
    fit = fit_configuration(system, ConfigCollection([stored, other]), 0)
    (lf,) = fit.links
    assert lf.output == PRESENT and lf.input == "missing" and not lf.whole
    (action,) = [a for a in lf.actions if a.op.value == "add"]
    assert action.link.input == ChannelRef(2, 2, 6, 1)
    assert "replaced by 2/2/4#1 → 2/2/6#1" in lf.summary()
    assert fit.chosen_index == 1 and "best fit of 2" in fit.chosen_reason


def test_the_one_diff_sees_unknown_records_at_every_level():
    rec = UnknownRecord(0x20, 1)
    a = ConfigCollection([replace_cfg(APPENDIX_D)])
    assert diff_configurations(a, a).equal
    for b in (ConfigCollection([replace_cfg(APPENDIX_D)], (rec,)),
              ConfigCollection([replace_cfg(APPENDIX_D, unknown=(rec,))])):
        assert not diff_configurations(a, b).equal
    link_b = ConfigCollection([StoredConfiguration(1, [replace(APPENDIX_D.links[0],
                                                               unknown=(rec,)),
                                                       *APPENDIX_D.links[1:]])])
    diff = diff_configurations(a, link_b)
    (changed,) = diff.configurations[0].changed
    assert "link unknown records [] → [32=0x0001]" in diff.describe()
    assert changed.b.unknown == (rec,)


def test_fit_of_the_second_terminal_device_configuration_replaces_the_hook_by_the_hand():
    """Thesis B.2.1 case 4: the hook's configuration on a prosthesis wearing the hand."""
    from pathlib import Path

    system = system_file.load_path(systems_dir() / "transradial.json")
    if not system.links:
        plan_autoconfigure(system).apply(system)
    root = Path(__file__).resolve().parents[2]
    coll = config_codec.load_path(root / "resources" / "configs"
                                  / "transradial-hand-and-hook.pdcfg")
    fit = fit_configuration(system, coll, 1)
    assert fit.chosen_index == 1  # the hand's configuration fits best
    assert [lf.whole for lf in fit.links] == [True, True, False, False]
    hook = fit.links[2]
    (add,) = [a for a in hook.actions if a.op.value == "add"]
    assert add.link.input == ChannelRef(2641, 769, 301, 1)
    assert "replaced by 2641/513/201#3 → 2641/769/301#1" in hook.summary()
