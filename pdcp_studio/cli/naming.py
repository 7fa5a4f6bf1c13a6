"""The command line's names for parts and channels: the one naming the app uses
(``model/names.py``), with the named profile trees the app reads, so a part reads the same
in a terminal as on the screen. Human text puts the name first and the engineer's numbers
beside it in brackets; ``--json`` outputs never change."""

from __future__ import annotations

from typing import TYPE_CHECKING

from pdcp_studio.model.names import Names

if TYPE_CHECKING:
    from pdcp_studio.model.profile_tree import ProfileTree
    from pdcp_studio.model.system import System


def names_for(system: System, tree: ProfileTree | None = None) -> Names:
    """``system``'s names; channels without a descriptor by ``tree``'s profile names, else
    by the profile tree the app would choose for ``system``."""
    from pdcp_studio.storage.profile_trees import system_names

    return system_names(system, tree)
