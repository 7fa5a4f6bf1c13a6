"""The profile layer's procedures (thesis listings 4.1–4.3, 4.6, 4.7 and the CLI's extras).

Each works on a ``ProfileLayer`` (an overlay, so the system is never changed) and is
written to read like the listing it implements; the reference's Decisions are named where
they apply.
"""

from __future__ import annotations

from pdcp_studio.engine.layer import ProfileLayer
from pdcp_studio.engine.plan import Attempt, Refusal, Rule
from pdcp_studio.engine.similarity import Similarity
from pdcp_studio.errors import EngineError
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.model.profile import fmt
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import Channel, Device, Link, System


# -- configurations ------------------------------------------------------------------------
def retrieve_configuration(system: System) -> StoredConfiguration:
    """Rebuild a configuration from the devices' own Source fields (behaviour 1, §4.3.2).

    Present inputs only (a missing device cannot be read), in ascending input order. The
    output end carries the source type and profile the input stored, which is what
    ``find_replacements`` compares with when that output is gone.
    """
    links: list[StoredLink] = []
    for device in sorted(system.devices.values(), key=lambda d: d.key):
        if not device.present:
            continue
        for ch in sorted(device.inputs(), key=lambda c: c.index):
            s = ch.source
            if not s.connected:
                continue
            links.append(StoredLink(
                input=StoredChannel(ch.index, device.vid, device.pid, device.serial,
                                    ch.type, ch.profile),
                output=StoredChannel(s.index, s.vid, s.pid, s.serial, s.type, s.profile),
                index=len(links) + 1,
            ))
    return StoredConfiguration(index=1, links=links)


def configuration_from_system(system: System) -> StoredConfiguration:
    """The current links as a stored configuration, with the type and profile of both ends."""
    links: list[StoredLink] = []
    for n, link in enumerate(system.links, 1):
        out, inp = system.channel(link.output), system.channel(link.input)
        assert out is not None and inp is not None  # a System only holds links it can check
        o, i = link.output, link.input
        links.append(StoredLink(
            input=StoredChannel(i.index, i.vid, i.pid, i.serial, inp.type, inp.profile),
            output=StoredChannel(o.index, o.vid, o.pid, o.serial, out.type, out.profile),
            index=n,
        ))
    return StoredConfiguration(index=1, links=links)


def _present(system: System, ref: ChannelRef, direction: Direction) -> bool:
    ch = system.channel(ref)
    return ch is not None and ch.direction is direction and system.is_present(ref)


def _fit(system: System, cfg: StoredConfiguration) -> tuple[int, int]:
    """(links with both ends present, distinct channels missing)."""
    whole = 0
    missing: set[ChannelRef] = set()
    for sl in cfg.links:
        out_ok = _present(system, sl.output.ref, Direction.OUTPUT)
        in_ok = _present(system, sl.input.ref, Direction.INPUT)
        whole += out_ok and in_ok
        if not out_ok:
            missing.add(sl.output.ref)
        if not in_ok:
            missing.add(sl.input.ref)
    return whole, len(missing)


def choose_configuration(system: System,
                         collection: ConfigCollection) -> tuple[StoredConfiguration, str]:
    """Pick the stored configuration that best fits the present hardware (B.2.1 case 4).

    Most links whose both ends are present, then fewest missing channels, then the first
    in the collection. Returns it and a sentence saying which and why.
    """
    configs = collection.configurations
    if not configs:
        raise EngineError("the stored collection holds no configuration")
    fits = [_fit(system, c) for c in configs]
    best = min(range(len(configs)), key=lambda i: (-fits[i][0], fits[i][1], i))
    cfg = configs[best]

    def says(i: int) -> str:
        c = configs[i]
        return (f"configuration {c.index}: {fits[i][0]} of {len(c.links)} links with both "
                f"ends present, {fits[i][1]} missing channel(s)")

    if len(configs) == 1:
        return cfg, f"the only stored {says(best)}"
    others = "; ".join(says(i) for i in range(len(configs)) if i != best)
    return cfg, (f"chose {says(best)} — the best fit of {len(configs)} "
                 f"(most links with both ends present, then fewest missing channels); {others}")


def resolve_configuration(
    system: System, config: ConfigCollection | StoredConfiguration | None,
) -> tuple[StoredConfiguration | None, str]:
    """A single configuration (chosen from a collection when needed) and why."""
    if config is None:
        return None, ""
    if isinstance(config, ConfigCollection):
        if not config.configurations:
            return None, "the stored collection holds no configuration"
        return choose_configuration(system, config)
    return config, f"configuration {config.index} as given ({len(config.links)} links)"


def _involves_missing(layer: ProfileLayer, cfg: StoredConfiguration) -> bool:
    return any(
        not (layer.is_present(sl.output.ref, Direction.OUTPUT)
             and layer.is_present(sl.input.ref, Direction.INPUT))
        for sl in cfg.links
    )


# -- listing 4.3 ------------------------------------------------------------------------------
def implement_configuration(layer: ProfileLayer, cfg: StoredConfiguration,
                            rule: Rule = Rule.STORED) -> None:
    """Every stored link: ``connect`` it, or ``intelligently_connect`` it when its input is
    a terminal channel. Links with a missing end are refused here (find_replacements)."""
    for n, sl in enumerate(cfg.links, 1):
        link = Link(sl.output.ref, sl.input.ref)
        if rule is Rule.RETRIEVED:
            reason = f"retrieved: input {link.input} stores source {link.output}"
        else:
            reason = f"stored configuration {cfg.index}, link {sl.index or n}"
        inp = layer.channel(link.input)
        if inp is not None and inp.terminal:
            layer.intelligently_connect(link, rule, reason)
        else:
            layer.connect(link, rule, reason)


# -- listing 4.6 ------------------------------------------------------------------------------
def find_replacements(layer: ProfileLayer, cfg: StoredConfiguration) -> None:
    """Repair each stored link with exactly one missing channel with the present channel
    most similar to the stored one; connect the repaired links, most similar first."""
    repaired: list[tuple[Link, Similarity, Link, ChannelRef, str]] = []
    for sl in cfg.links:
        original = Link(sl.output.ref, sl.input.ref)
        out_ok = layer.is_present(sl.output.ref, Direction.OUTPUT)
        in_ok = layer.is_present(sl.input.ref, Direction.INPUT)
        if out_ok and in_ok:
            continue
        attempt = Attempt(Rule.REPLACEMENT, original, None)
        if not out_ok and not in_ok:
            layer.reject(Refusal.MISSING, attempt,
                         f"both ends of stored link {original} are missing: nothing to repair")
            continue
        missing: StoredChannel = sl.output if not out_ok else sl.input
        if not out_ok:
            sole = layer.channels[sl.input.ref].sole_access
            found = layer.find_similar_channel(Direction.OUTPUT, missing.type, missing.profile,
                                               exclude=sl.input.ref.device, sole_access=sole)
        else:
            found = layer.find_similar_channel(Direction.INPUT, missing.type, missing.profile,
                                               exclude=sl.output.ref.device)
        kind = "output" if not out_ok else "input"
        if found is None:
            layer.reject(Refusal.NO_CANDIDATE, Attempt(Rule.REPLACEMENT, original, missing.ref),
                         f"no free present {kind} shares a profile component with missing "
                         f"{kind} {missing.ref} ({fmt(missing.profile)})")
            continue
        new_ref, sim = found
        link = Link(new_ref, sl.input.ref) if not out_ok else Link(sl.output.ref, new_ref)
        reason = (f"replaces missing {kind} {missing.ref} ({fmt(missing.profile)}): the most "
                  f"similar free present {kind} (similarity {sim.total} to the missing one)")
        repaired.append((link, layer.similarity(link), original, missing.ref, reason))
    # Decision: highest input–output similarity first; ties by output, then input.
    repaired.sort(key=lambda r: (-r[1].total, r[0].output, r[0].input))
    for link, link_sim, original, missing_ref, reason in repaired:
        if not layer.intelligently_connect(link, Rule.REPLACEMENT, reason, cause=missing_ref,
                                           similarity=link_sim):
            continue
        if original in layer.links:
            layer.remove(original, Rule.REPLACED,
                         f"{missing_ref} is missing; replaced by {link}", cause=link)


# -- listing 4.7 ------------------------------------------------------------------------------
def autoconfigure(layer: ProfileLayer) -> None:
    """Connect each unconnected terminal channel, lowest terminal profile first, to its most
    similar free output, with everything that output and input require."""
    for ref in layer.unconnected_terminals():
        if layer.has_source(ref):
            layer.note(f"terminal channel {ref} was connected by an earlier step")
            continue
        ch = layer.channels[ref]
        found = layer.find_output_for(ref)
        if found is None:
            layer.reject(Refusal.NO_CANDIDATE, Attempt(Rule.TERMINAL, None, ref),
                         f"terminal channel {ref} ({fmt(ch.terminal_profile)}) left "
                         f"unconnected: {layer.why_no_output(ref)}")
            continue
        out_ref, sim = found
        layer.intelligently_connect(
            Link(out_ref, ref), Rule.TERMINAL,
            f"terminal channel {fmt(ch.terminal_profile)}: most similar free output",
            similarity=sim)


# -- listings 4.1 / 5.1 and 4.2 -----------------------------------------------------------------
AUTOCONFIGURE_OFF = "autoconfigure is off on this prosthesis"


def report_unconnected_terminals(layer: ProfileLayer) -> None:
    """With the policy's autoconfigure off: note each unconnected terminal channel instead
    of linking it (issue 17)."""
    for ref in layer.unconnected_terminals():
        layer.note(f"terminal channel {ref} not connected — {AUTOCONFIGURE_OFF}")


def startup(layer: ProfileLayer,
            stored: ConfigCollection | StoredConfiguration | None, *,
            autoconfigure_on: bool = True) -> None:
    """Start-up: the stored (central) configuration wins over the devices' own.
    ``autoconfigure_on`` False (the arbitrator's policy) reports unconnected terminal
    channels instead of autoconfiguring them."""
    cfg, why = resolve_configuration(layer.system, stored)
    plan = layer.plan
    if cfg is not None:
        plan.configuration, plan.configuration_source, plan.configuration_reason = (
            cfg, "stored", why)
        keep = {Link(sl.output.ref, sl.input.ref) for sl in cfg.links}
        # Decision: drop the current links the stored configuration does not have; links
        # in both are kept, not re-made.
        for link in sorted(layer.links):
            if link not in keep:
                layer.remove(link, Rule.NOT_STORED,
                             f"not in stored configuration {cfg.index}")
        implement_configuration(layer, cfg, Rule.STORED)
    else:
        cfg = retrieve_configuration(layer.system)
        lead = f"{why}; " if why else "no configuration stored: "
        plan.configuration, plan.configuration_source, plan.configuration_reason = (
            cfg, "retrieved",
            f"{lead}retrieved {len(cfg.links)} link(s) from the inputs' stored source fields")
        implement_configuration(layer, cfg, Rule.RETRIEVED)
    if _involves_missing(layer, cfg):
        find_replacements(layer, cfg)
    if layer.unconnected_terminals():
        if autoconfigure_on:
            autoconfigure(layer)
        else:
            report_unconnected_terminals(layer)


def duty_cycle(layer: ProfileLayer, previously_present: set[ChannelRef] | None, *,
               autoconfigure_on: bool = True) -> None:
    """Listing 4.2: replacements if channels disappeared, then autoconfigure if needed.

    The configuration to repair is the current links (those with a missing end are dead).
    Without ``previously_present``, the missing ends of current links count as disappeared.
    """
    cfg = configuration_from_system(layer.system)
    layer.plan.configuration, layer.plan.configuration_source = cfg, "system"
    layer.plan.configuration_reason = "the current links"
    if previously_present is None:
        gone = {r for lk in layer.links for r in (lk.output, lk.input) if r not in layer.present}
    else:
        gone = {r for r in previously_present if r not in layer.present}
    if gone:
        layer.note(f"{len(gone)} channel(s) disappeared: " +
                   ", ".join(str(r) for r in sorted(gone)[:8]) + (" …" if len(gone) > 8 else ""))
        find_replacements(layer, cfg)
    if layer.unconnected_terminals():
        if autoconfigure_on:
            autoconfigure(layer)
        else:
            report_unconnected_terminals(layer)


# -- the thesis CLI's extras ----------------------------------------------------------------------
def enforce(layer: ProfileLayer) -> None:
    """Remove links that break sole access.

    Decision: of the sole-access inputs one output feeds, the one kept is a terminal
    channel before others, then the lower profile (higher priority), then the lower
    reference; the links to the others are removed.
    """
    for out_ref in sorted(r for r, n in layer.sole_fed.items() if n > 1):
        fed = layer.sole_inputs_fed_by(out_ref)

        def priority(r: ChannelRef) -> tuple[bool, int, ChannelRef]:
            ch = layer.channels[r]
            return (not ch.terminal, ch.profile, r)

        keep = min(fed, key=priority)
        for r in sorted(fed):
            if r != keep:
                layer.remove(Link(out_ref, r), Rule.SOLE_ACCESS,
                             f"output {out_ref} also feeds sole-access input {keep}, which is "
                             "kept (terminal first, then lower profile, then lower reference)",
                             cause=Link(out_ref, keep))


def clear(layer: ProfileLayer) -> None:
    """Remove every link."""
    for link in sorted(layer.links):
        layer.remove(link, Rule.CLEAR, "clear: every link is removed")


def missing_devices(system: System, config: ConfigCollection | StoredConfiguration | None
                    ) -> list[Device]:
    """Devices a stored configuration names that ``system`` lacks, as ``present=False``
    devices with the channels the configuration remembers (type and profile), so a
    prosthetist sees what is missing — the replaced hand, the unplugged sensor."""
    cfg, _why = resolve_configuration(system, config)
    if cfg is None:
        return []
    found: dict[DeviceKey, Device] = {}
    for sl in cfg.links:
        for stored, direction in ((sl.output, Direction.OUTPUT), (sl.input, Direction.INPUT)):
            key = stored.ref.device
            if system.device(key) is not None:
                continue
            device = found.setdefault(key, Device(*key, present=False))
            if stored.index not in device.channels:
                device.add_channel(Channel(stored.index, direction, type=stored.type,
                                           profile=stored.profile))
    return [found[k] for k in sorted(found)]
