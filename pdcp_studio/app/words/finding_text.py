"""The engine's check findings in plain words for a prosthetist, with what to do.

The engine's messages (``engine/checks.py``) are the engineer's and the JSON contract's:
channel references, profile codes, rule keys. The app shows this text instead and keeps
the engineer's message and the rule's key one hover away (:func:`finding_detail`).
"""

from __future__ import annotations

from collections.abc import Mapping
from html import escape

from pdcp_studio.app.i18n import translate
from pdcp_studio.engine.checks import Finding
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import System

_CTX = "Findings"

#: Finding key → plain text with ``{a}``/``{b}`` for the first two channels named.
_TEXTS = {
    "null-profile": "{a} has no profile, so it can never be connected automatically. "
                    "Set its profile in the inspector.",
    "malformed-profile": "{a} has a profile with a gap in it, so matching ignores part "
                         "of it. Check its profile in the inspector.",
    "required-not-input": "{a} says it needs a channel of its device that is not an "
                          "input. The device's description is wrong: ask its maker.",
    "desired-not-input": "{a} says it would like a channel of its device that is not an "
                         "input. The device's description is wrong: ask its maker.",
    "terminal-profile-null": "{a} has no terminal profile, so it is connected before all "
                             "others. Set its terminal profile if that is not intended.",
    "missing-end": "The link {a} → {b} carries no data: a device at one end is not on the "
                   "bus. Plug the device in, or remove the link.",
    "self-link": "The link {a} → {b} joins a device to itself. Remove it.",
    "sole-access": "{a} feeds several inputs that each need it for themselves. Keep one "
                   "of these links and remove the others.",
    "two-sources": "{a} is given more than one source. Keep one link into it and remove "
                   "the others.",
    "source-field-stale": "{a} remembers a different source than it is linked to. "
                          "Writing the configuration again fixes this.",
    "required-unmet": "{a} is in use but the input it needs, {b}, is not connected. "
                      "Connect a source to it, or let Autoconfigure do it.",
    "desired-unmet": "{a} is in use and would work better with {b} connected. Connect a "
                     "source to it if one is available.",
    "terminal-unconnected": "{a} drives a part of the prosthesis but nothing feeds it, so "
                            "that part will not move. Connect a matching output, or let "
                            "Autoconfigure do it.",
}

#: ``terminal-unconnected`` on a prosthesis whose policy is autoconfigure off (issue 17).
_TERMINAL_OFF = ("{a} drives a part of the prosthesis but nothing feeds it, so that part "
                 "will not move. Autoconfigure is off on this prosthesis, so it will not "
                 "link it on its own: connect a matching output.")


def channel_words(system: System, ref: ChannelRef,
                  names: Mapping[DeviceKey, str] | None = None) -> str:
    """``Multi-grip hand (serial 301), Pinch grip``: the channel's one name (``model/
    names.py``: its descriptor, "channel N" only where it has none); ``names`` (device →
    name) when the caller names the parts itself."""
    from pdcp_studio.app.words import part_names
    from pdcp_studio.model import names as model_names

    name = names.get(ref.device) if names else None
    if name is None:
        return part_names.channel_name(system, ref)
    channel = part_names.names(system).channel_only(ref)
    return part_names.tr(model_names.CHANNEL).format(part=name, channel=channel)


def plain_finding(finding: Finding, system: System, autoconfigure: bool = True,
                  names: Mapping[DeviceKey, str] | None = None) -> str:
    """The finding in plain words with what to do; the engine's message if the rule is new.

    ``autoconfigure`` is the prosthesis's policy (the checks were made with it); ``names``
    as for :func:`channel_words`."""
    text = _TEXTS.get(finding.code)
    if finding.code == "terminal-unconnected" and not autoconfigure:
        text = _TERMINAL_OFF
    if text is None:
        return finding.message
    refs = [channel_words(system, r, names) for r in finding.refs[:2]]
    refs += [""] * (2 - len(refs))
    return translate(_CTX, text).format(a=refs[0], b=refs[1])


def finding_detail(finding: Finding) -> str:
    """The engineer's detail: the engine's message and the rule's key (for a tooltip)."""
    return f"{escape(finding.message)}<br><i>{escape(finding.code)}</i>"
