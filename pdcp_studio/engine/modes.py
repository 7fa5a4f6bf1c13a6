"""One function per operation, each returning a ``Plan`` and never changing the system."""

from __future__ import annotations

from pdcp_studio.engine import procedures as proc
from pdcp_studio.engine.layer import ProfileLayer
from pdcp_studio.engine.plan import Plan, Rule
from pdcp_studio.errors import EngineError
from pdcp_studio.model.configuration import ConfigCollection, StoredConfiguration
from pdcp_studio.model.refs import ChannelRef, Direction
from pdcp_studio.model.system import System

AnyConfig = ConfigCollection | StoredConfiguration | None

#: The modes of ``pdcp-studio plan`` (contracts §2), plus ``duty-cycle``.
MODES = ("autoconfigure", "replacements", "implement", "startup", "enforce", "clear")
EXTRA_MODES = ("duty-cycle",)


def without_unrouted_outputs(system: System) -> tuple[System, list[ChannelRef]]:
    """The system without the output channels that got no node ID on a live bus.

    When devices and outputs need more than the 254 node IDs (reference §1), some outputs of
    a bound device get none: nothing can hear them, so a plan must never link from them. They
    are recognised by their device having a node ID and they none (offline systems have no
    node IDs at all and are returned as they are). Returns the system to plan on and the
    outputs left out.
    """
    unrouted = [dev.ref(ch.index) for dev in system.devices.values()
                if dev.present and dev.node_id is not None
                for ch in dev.outputs() if ch.node_id is None]
    if not unrouted:
        return system, []
    usable = system.copy()
    for ref in unrouted:
        for link in [lk for lk in usable.links if lk.output == ref]:
            usable.remove_link(link)
        del usable.devices[ref.device].channels[ref.index]
    return usable, unrouted


def _note_unrouted(plan: Plan, unrouted: list[ChannelRef]) -> Plan:
    if unrouted:
        plan.notes.append(
            f"{len(unrouted)} output(s) got no node ID (all 254 are in use by devices and "
            "outputs) and are never linked: " + ", ".join(str(r) for r in unrouted))
    return plan


def plan_autoconfigure(system: System) -> Plan:
    """Listing 4.7 on the current links."""
    layer = ProfileLayer(system, "autoconfigure")
    proc.autoconfigure(layer)
    return layer.finish()


def _configured(layer: ProfileLayer, config: AnyConfig, *, source: str) -> StoredConfiguration:
    """The configuration to work from, recorded on the plan.

    Without one (contracts §2: ``--config`` is optional) it is the system's own links; a
    collection with no configuration in it (what an arbitrator with empty memory stores)
    is an empty configuration: nothing to implement or repair, not an error.
    """
    plan = layer.plan
    if config is None:
        cfg = proc.configuration_from_system(layer.system)
        plan.configuration, plan.configuration_source = cfg, "system"
        plan.configuration_reason = "no configuration given: the system's current links"
        return cfg
    resolved, why = proc.resolve_configuration(layer.system, config)
    if resolved is None:
        plan.configuration_source, plan.configuration_reason = source, why
        return StoredConfiguration(index=1, links=[])
    plan.configuration, plan.configuration_source, plan.configuration_reason = \
        resolved, source, why
    return resolved


def plan_implement(system: System, configuration: AnyConfig) -> Plan:
    """Listing 4.3: make the stored links (links with a missing end are refused).
    Without a configuration, the system's own links are implemented."""
    layer = ProfileLayer(system, "implement")
    cfg = _configured(layer, configuration, source="given")
    proc.implement_configuration(layer, cfg, Rule.STORED)
    return layer.finish()


def plan_replacements(system: System, configuration: AnyConfig) -> Plan:
    """Implement the stored links whose ends are all present, then repair the others
    (listing 4.6). Without a configuration, the system's own links are repaired."""
    layer = ProfileLayer(system, "replacements")
    cfg = _configured(layer, configuration, source="given")
    whole = [sl for sl in cfg.links
             if layer.is_present(sl.output.ref, Direction.OUTPUT)
             and layer.is_present(sl.input.ref, Direction.INPUT)]
    proc.implement_configuration(layer, StoredConfiguration(cfg.index, whole), Rule.STORED)
    proc.find_replacements(layer, cfg)
    return layer.finish()


def plan_startup(system: System, stored: AnyConfig, *, autoconfigure: bool = True) -> Plan:
    """Listings 4.1 / 5.1 (see ``procedures.startup``); ``autoconfigure`` False is the
    policy of issue 17 (unconnected terminal channels are noted, not linked)."""
    layer = ProfileLayer(system, "startup")
    proc.startup(layer, stored, autoconfigure_on=autoconfigure)
    return layer.finish()


def plan_duty_cycle(system: System, previously_present: set[ChannelRef] | None = None, *,
                    autoconfigure: bool = True) -> Plan:
    """Listing 4.2, the hot-swap duty cycle (``autoconfigure`` as for start-up); outputs
    without a node ID are left out (:func:`without_unrouted_outputs`)."""
    system, unrouted = without_unrouted_outputs(system)
    if previously_present is not None and unrouted:
        previously_present = previously_present - set(unrouted)
    layer = ProfileLayer(system, "duty-cycle")
    proc.duty_cycle(layer, previously_present, autoconfigure_on=autoconfigure)
    return _note_unrouted(layer.finish(), unrouted)


def plan_enforce(system: System) -> Plan:
    layer = ProfileLayer(system, "enforce")
    proc.enforce(layer)
    return layer.finish()


def plan_clear(system: System) -> Plan:
    layer = ProfileLayer(system, "clear")
    proc.clear(layer)
    return layer.finish()


def plan_for(mode: str, system: System, config: AnyConfig = None, *,
             autoconfigure: bool = True) -> Plan:
    """Dispatch by mode name; ``config`` is ignored by autoconfigure, enforce and clear;
    ``autoconfigure`` (the arbitrator's policy) only by startup and duty-cycle. Outputs that
    got no node ID on a live bus are never used (:func:`without_unrouted_outputs`)."""
    if mode != "duty-cycle":
        system, unrouted = without_unrouted_outputs(system)
        if unrouted:
            return _note_unrouted(plan_for(mode, system, config, autoconfigure=autoconfigure),
                                  unrouted)
    if mode == "autoconfigure":
        return plan_autoconfigure(system)
    if mode == "replacements":
        return plan_replacements(system, config)
    if mode == "implement":
        return plan_implement(system, config)
    if mode == "startup":
        return plan_startup(system, config, autoconfigure=autoconfigure)
    if mode == "enforce":
        return plan_enforce(system)
    if mode == "clear":
        return plan_clear(system)
    if mode == "duty-cycle":
        return plan_duty_cycle(system, None, autoconfigure=autoconfigure)
    raise EngineError(f"unknown mode {mode!r} (one of {', '.join(MODES + EXTRA_MODES)})")


def plan_on_bus(mode: str, system: System, memory: ConfigCollection, *,
                autoconfigure: bool = True) -> Plan:
    """``plan_for`` on a live bus, with the arbitrator's stored configuration and policy; an
    empty memory means none is stored, so the plan works from the system's own links
    (start-up retrieves them from the inputs' source fields)."""
    return plan_for(mode, system, memory if memory.configurations else None,
                    autoconfigure=autoconfigure)
