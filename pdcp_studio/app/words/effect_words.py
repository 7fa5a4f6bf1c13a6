"""The words of a change's effect in the user's language (context ``Effect``).

The effect (:mod:`pdcp_studio.engine.effect`) writes English templates and asks a ``tr`` for
each; the app passes :func:`effect_tr`, Qt's translate in context ``Effect``. Each template is
marked here so ``pyside6-lupdate`` finds it (a test keeps :data:`MARKED` equal to the engine's
``TEMPLATES`` + ``TYPE_WORDS``, so a new template cannot be forgotten). Part and channel names
come from :func:`app_names` (``model.names.Names`` with Qt's translate in context ``Names``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from pdcp_studio.app.i18n import QT_TRANSLATE_NOOP, translate

if TYPE_CHECKING:
    from pdcp_studio.model.names import Names
    from pdcp_studio.model.profile_tree import ProfileTree
    from pdcp_studio.model.system import System

CONTEXT = "Effect"

#: Every template and type word of ``engine.effect``, marked for translation.
MARKED: tuple[str, ...] = (
    QT_TRANSLATE_NOOP("Effect", "acknowledgement timeout"),
    QT_TRANSLATE_NOOP("Effect", "beacon interval"),
    QT_TRANSLATE_NOOP("Effect", "bind request timeout"),
    QT_TRANSLATE_NOOP("Effect", "{bits}-bit {kind}"),
    QT_TRANSLATE_NOOP("Effect", "{what} {old} → {new}"),
    QT_TRANSLATE_NOOP("Effect", "control mode"),
    QT_TRANSLATE_NOOP("Effect", "data transfer"),
    QT_TRANSLATE_NOOP("Effect", "data type"),
    QT_TRANSLATE_NOOP("Effect", "desired inputs"),
    QT_TRANSLATE_NOOP("Effect", "While the change is made, these parts are held still: "
                                "{parts}."),
    QT_TRANSLATE_NOOP("Effect", "No part needs to be held still for this change."),
    QT_TRANSLATE_NOOP("Effect", "Link made: {link}"),
    QT_TRANSLATE_NOOP("Effect", "Link removed: {link}"),
    QT_TRANSLATE_NOOP("Effect", "{n} ms"),
    QT_TRANSLATE_NOOP("Effect", "name"),
    QT_TRANSLATE_NOOP("Effect", "no"),
    QT_TRANSLATE_NOOP("Effect", "none"),
    QT_TRANSLATE_NOOP("Effect", "Nothing changes on the prosthesis."),
    QT_TRANSLATE_NOOP("Effect", "off"),
    QT_TRANSLATE_NOOP("Effect", "on"),
    QT_TRANSLATE_NOOP("Effect", "{where}: {what}"),
    QT_TRANSLATE_NOOP("Effect", "Automatic set-up (autoconfigure): {old} → {new}."),
    QT_TRANSLATE_NOOP("Effect", "Turning automatic set-up off removes nothing: {links} stay "
                                "as they are."),
    QT_TRANSLATE_NOOP("Effect", "  stays: {link}"),
    QT_TRANSLATE_NOOP("Effect", "This link stays but carries no data while data transfer is "
                                "off at one of its ends: {link}"),
    QT_TRANSLATE_NOOP("Effect", "{n} link"),
    QT_TRANSLATE_NOOP("Effect", "{n} links"),
    QT_TRANSLATE_NOOP("Effect", "  is made: {link}"),
    QT_TRANSLATE_NOOP("Effect", "Automatic set-up is on: start-up links unconnected terminal "
                                "channels."),
    QT_TRANSLATE_NOOP("Effect", "  comes back: {link}"),
    QT_TRANSLATE_NOOP("Effect", "  is removed: {link}"),
    QT_TRANSLATE_NOOP("Effect", "At the next power-on, start-up will change the links:"),
    QT_TRANSLATE_NOOP("Effect", "Start-up undoes part of this change."),
    QT_TRANSLATE_NOOP("Effect", "No configuration is stored: start-up rebuilds the links from "
                                "what the parts themselves remember."),
    QT_TRANSLATE_NOOP("Effect", "This change is not stored: the next power-on undoes it. "
                                "Store it as the prosthesis's configuration to keep it."),
    QT_TRANSLATE_NOOP("Effect", "Even stored, start-up's automatic set-up makes this again "
                                "(autoconfigure is on): turn automatic set-up off to keep the "
                                "change."),
    QT_TRANSLATE_NOOP("Effect", "At the next power-on: nothing changes; start-up keeps these "
                                "links."),
    QT_TRANSLATE_NOOP("Effect", "prescaler"),
    QT_TRANSLATE_NOOP("Effect", "profile"),
    QT_TRANSLATE_NOOP("Effect", "required inputs"),
    QT_TRANSLATE_NOOP("Effect", "sole access"),
    QT_TRANSLATE_NOOP("Effect", "  stored from now on: {link}"),
    QT_TRANSLATE_NOOP("Effect", "Stored configuration: cleared (nothing stored)."),
    QT_TRANSLATE_NOOP("Effect", "  no longer stored: {link}"),
    QT_TRANSLATE_NOOP("Effect", "Stored configuration: stored for the first time, {links}."),
    QT_TRANSLATE_NOOP("Effect", "Stored configuration: replaced; it will hold {links} "
                                "({added} added, {removed} removed)."),
    QT_TRANSLATE_NOOP("Effect", "Stored configuration: unchanged."),
    QT_TRANSLATE_NOOP("Effect", "terminal channel"),
    QT_TRANSLATE_NOOP("Effect", "terminal profile"),
    QT_TRANSLATE_NOOP("Effect", "yes"),
    # the words of a channel type's fields (engine.effect.TYPE_WORDS)
    QT_TRANSLATE_NOOP("Effect", "position"),
    QT_TRANSLATE_NOOP("Effect", "velocity"),
    QT_TRANSLATE_NOOP("Effect", "acceleration"),
    QT_TRANSLATE_NOOP("Effect", "other"),
    QT_TRANSLATE_NOOP("Effect", "signed int"),
    QT_TRANSLATE_NOOP("Effect", "unsigned int"),
    QT_TRANSLATE_NOOP("Effect", "float"),
    QT_TRANSLATE_NOOP("Effect", "boolean"),
)


def effect_tr(text: str) -> str:
    """An effect's template in the user's language."""
    return translate(CONTEXT, text)


def names_tr(text: str) -> str:
    """A name's template (``model.names``) in the user's language."""
    return translate("Names", text)


def app_names(system: System | None, profiles: ProfileTree | None = None) -> Names:
    """The names every text about a change uses, in the user's language (``profiles``: the
    document's named profile trees, else read from the shipped and the user's trees)."""
    from pdcp_studio.model.names import Names

    if profiles is None and system is not None:
        from pdcp_studio.bus.session.change_road import names_for

        return names_for(system, names_tr)
    return Names(system, profiles=profiles, tr=names_tr)
