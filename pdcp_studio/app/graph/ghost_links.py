"""Links drawn that the system does not hold: a previewed plan's additions and removals,
and the pending removals (links still on the prosthesis that the project removes).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from pdcp_studio.app.graph.links import LinkItem
from pdcp_studio.app.i18n import translate
from pdcp_studio.model.system import Link

if TYPE_CHECKING:
    from pdcp_studio.app.graph.scene import BusScene


class GhostLinks:
    """The ghost links of one scene (``preview``, ``unwritten``), made anew on each change."""

    def __init__(self, scene: BusScene) -> None:
        self._scene = scene
        self.preview: list[LinkItem] = []
        #: Ghosts of links on the prosthesis that the project removes (pending removals).
        self.unwritten: list[LinkItem] = []

    def forget(self) -> None:
        """The scene was cleared (its items are gone with it)."""
        self.preview.clear()
        self.unwritten.clear()

    def show_unwritten(self) -> None:
        """Ghost links: on the prosthesis, removed in the project (not yet written)."""
        from pdcp_studio.app.words.part_names import one_naming
        from pdcp_studio.app.words.plan_words import link_words

        self._drop(self.unwritten)
        doc = self._scene.doc
        bus = doc.bus_system
        if bus is None:
            return
        with one_naming(doc.system):  # a tooltip per link: one lookup for all
            for link in sorted(set(bus.links) - set(doc.system.links)):
                item = self._ghost(link, "unwritten")
                if item is not None:
                    item.setToolTip(translate(
                        "BusScene", "Pending removal (still on the prosthesis): {link}"
                    ).format(link=link_words(doc.system, link.output, link.input)))
                    self.unwritten.append(item)

    def show_preview(self, plan: Any) -> None:
        """A plan's steps as dashed links (None: no preview)."""
        from pdcp_studio.app.words import plan_words
        from pdcp_studio.app.words.part_names import one_naming

        self._drop(self.preview)
        if plan is None:
            return
        doc = self._scene.doc
        with one_naming(doc.system):  # a tooltip per step: one lookup for all
            for action in getattr(plan, "actions", ()):
                item = self._ghost(action.link, "add" if action.op == "add" else "remove")
                if item is not None:
                    item.setToolTip(plan_words.step_words(doc.system, plan, action,
                                                          doc.profile_name))
                    self.preview.append(item)

    def _ghost(self, link: Link, kind: str) -> LinkItem | None:
        """A ghost between two shown ports, added to the scene (None: an end not shown)."""
        scene = self._scene
        if scene.port(link.output) is None or scene.port(link.input) is None:
            return None
        item = LinkItem(scene, link, kind)
        scene.addItem(item)
        return item

    def _drop(self, items: list[LinkItem]) -> None:
        for item in items:
            item.detach()
            self._scene.removeItem(item)
        items.clear()
