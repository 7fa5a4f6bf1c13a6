"""The named profile trees PDCP Studio reads: the shipped ones, then the user's and vendors'.

Pure file reading (no Qt), so the command line names profiles exactly as the app does.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterable
from pathlib import Path

from pdcp_studio.errors import ProfileError
from pdcp_studio.model.names import Names
from pdcp_studio.model.profile_tree import ProfileNames, ProfileTree
from pdcp_studio.model.system import System

log = logging.getLogger(__name__)

#: Profile trees shipped in resources/profiles: the prosthetic tree, then the thesis test
#: tree. Each stands alone (their values overlap): a system is named by the one that fits it.
BUILTIN_TREES = ("prosthesis.json", "thesis-tests.json")
#: A profile-tree file holds at most this many bytes and this many levels of nesting (as
#: ``plan --profiles`` reads it).
MAX_TREE_BYTES = 1024 * 1024
MAX_TREE_DEPTH = 64


def read_tree_json(path: str | Path) -> object:
    """A profile-tree file's JSON, bounded; a FIFO or a device is refused, never waited on
    (``NotARegularFile``, an OSError). InputError (a ValueError) for bad JSON."""
    from pdcp_studio.storage.bounded_input import loads_json, read_capped

    return loads_json(read_capped(path, MAX_TREE_BYTES, "a profile tree"),
                      max_depth=MAX_TREE_DEPTH)


def user_profiles_dir() -> Path | None:
    """Where user and vendor profile trees live (the user's data folder, ``profiles``)."""
    from pdcp_studio.paths import user_profiles_dir as folder

    return folder()


def load_profile_trees(extra: Iterable[Path] = (), *,
                       user_dir: bool = True) -> list[ProfileTree]:
    """The named trees: the shipped ones, then the user's and vendors' (a user tree with a
    shipped tree's name is the user's edit of it and takes its place). A broken user file
    is logged, not fatal."""
    from pdcp_studio.paths import profiles_dir

    files = [profiles_dir() / name for name in BUILTIN_TREES]
    udir = user_profiles_dir() if user_dir else None
    if udir is not None and udir.is_dir():
        files += sorted(udir.glob("*.json"))
    files += list(extra)
    trees: list[ProfileTree] = []
    for path in files:
        try:
            tree = ProfileTree.from_json(read_tree_json(path), str(path))
        except (OSError, ValueError, ProfileError) as err:
            log.warning("profile tree %s skipped: %s", path, err)
            continue
        same = next((i for i, t in enumerate(trees) if t.name == tree.name), None)
        if same is None:
            trees.append(tree)
        else:
            trees[same] = tree
    return trees


def load_profile_tree(extra: Iterable[Path] = (), *, user_dir: bool = True,
                      system: System | None = None) -> ProfileTree:
    """The names of ``system``'s profiles from every named tree (:func:`tree_for`); without a
    system the prosthetic tree comes first."""
    return tree_for(load_profile_trees(extra, user_dir=user_dir), system)


def tree_for(trees: list[ProfileTree], system: System | None) -> ProfileNames:
    """The names of ``system``'s profiles from all the named trees, each profile from the
    tree that knows it (:class:`ProfileNames`: a system mixing thesis test devices and
    prosthetic devices is named by both shipped trees)."""
    devices = [] if system is None else [
        [p for ch in device.channels.values() for p in (ch.profile, ch.terminal_profile)]
        for device in system.devices.values()]
    return ProfileNames(trees, devices)


def system_names(system: System, tree: ProfileTree | None = None,
                 tr: Callable[[str], str] | None = None) -> Names:
    """The one naming of ``system``'s parts and channels (``model/names.py``), its profiles
    named by ``tree`` or else by the named trees that fit ``system`` — what the change
    road, the CLI and the app all name a prosthesis with."""
    profiles = tree if tree is not None else tree_for(load_profile_trees(), system)
    return Names(system, profiles=profiles, tr=tr or (lambda text: text))
