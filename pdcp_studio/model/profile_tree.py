"""Named profile trees: human names for profile paths (thesis figure 4.6).

Trees are JSON resources (``pdcp-profile-tree/1``) that users edit and extend with
vendor trees. Two are shipped, each named and standing alone: the prosthetic tree (hand,
wrist, elbow, EMG, control unit…, figure 4.6's example extended) and the thesis test
tree (chapter 6's LEDs and joystick). Their values overlap (both use the root ``0x2``), so
they are never merged into one tree: :class:`ProfileNames` names each profile from the
tree that knows it, whole paths from one tree (never ``Terminal Device › Axis``), so a
system that mixes thesis test devices and prosthetic devices has every channel named.

A tree may say who assigns its odd components (``vendor``): odd components are reserved
for vendors (reference §1), so a tree's odd nodes are "vendor-reserved" only when it does
not (the thesis's own test hierarchy uses ``0x1``, assigned by its author). Pure: file
I/O is in :mod:`pdcp_studio.app.dialogs.profile_tree_editor` and
:mod:`pdcp_studio.app.documents.document`.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from pdcp_studio.errors import ProfileError
from pdcp_studio.model import profile as prof

TREE_FORMAT = "pdcp-profile-tree/1"


@dataclass
class ProfileNode:
    """One named component; its profile is the path of components from the root."""

    name: str
    component: int
    children: list[ProfileNode] = field(default_factory=list)
    description: str = ""

    def child(self, component: int) -> ProfileNode | None:
        for c in self.children:
            if c.component == component:
                return c
        return None

    @property
    def vendor_reserved(self) -> bool:
        return prof.is_vendor_component(self.component)


@dataclass
class ProfileTree:
    """A forest of named profile nodes, looked up by profile value."""

    name: str = "profiles"
    roots: list[ProfileNode] = field(default_factory=list)
    #: Who assigns this tree's odd (vendor) components; '' when nobody does.
    vendor: str = ""
    description: str = ""

    def is_vendor_reserved(self, node: ProfileNode) -> bool:
        """An odd component no vendor of this tree has assigned: reserved, not to be used."""
        return node.vendor_reserved and not self.vendor

    def names_exactly(self, profile: int) -> bool:
        """True when the tree has a node for exactly ``profile``."""
        return self.node(profile) is not None

    # -- lookup -----------------------------------------------------------------
    def node_path(self, profile: int) -> list[ProfileNode]:
        """The named nodes along ``profile``'s path, as far as the tree knows it."""
        nodes: list[ProfileNode] = []
        level = self.roots
        for comp in prof.components(profile):
            match = next((n for n in level if n.component == comp), None)
            if match is None:
                break
            nodes.append(match)
            level = match.children
        return nodes

    def node(self, profile: int) -> ProfileNode | None:
        """The node for exactly this profile, or None."""
        path = self.node_path(profile)
        return path[-1] if path and len(path) == prof.depth(profile) else None

    def name_of(self, profile: int, sep: str = " › ") -> str:
        """``Sensor › Accelerometer › Wrist``; unknown tails are shown as hex components."""
        if profile == prof.NULL_PROFILE:
            return "(null profile)"
        comps = prof.components(profile)
        path = self.node_path(profile)
        names = [n.name for n in path] + [f"0x{c:X}" for c in comps[len(path) :]]
        return sep.join(names)

    def short_name(self, profile: int) -> str:
        """The deepest known name, e.g. ``Power Grip``; hex when unknown."""
        path = self.node_path(profile)
        if path and len(path) == prof.depth(profile):
            return path[-1].name
        return prof.fmt(profile)

    def walk(self) -> list[tuple[int, ProfileNode]]:
        """Every (profile value, node), depth first in component order."""
        out: list[tuple[int, ProfileNode]] = []

        def visit(nodes: list[ProfileNode], prefix: tuple[int, ...]) -> None:
            for n in sorted(nodes, key=lambda n: n.component):
                path = (*prefix, n.component)
                out.append((prof.from_components(path), n))
                visit(n.children, path)

        visit(self.roots, ())
        return out

    # -- editing ----------------------------------------------------------------
    def children_of(self, profile: int) -> list[ProfileNode]:
        if profile == prof.NULL_PROFILE:
            return self.roots
        node = self.node(profile)
        if node is None:
            raise ProfileError(f"no node at profile {prof.fmt(profile)}")
        return node.children

    def add(self, parent_profile: int, name: str, component: int) -> int:
        """Add a named node under ``parent_profile`` (null = a root); returns its profile."""
        if prof.depth(parent_profile) >= prof.MAX_DEPTH:
            raise ProfileError(f"{prof.fmt(parent_profile)} is 4 levels deep: no room below it")
        if not 1 <= component <= 0xF:
            raise ProfileError(f"component {component} is not 1…15")
        if not name.strip():
            raise ProfileError("a profile node needs a name")
        siblings = self.children_of(parent_profile)
        if any(s.component == component for s in siblings):
            raise ProfileError(
                f"component 0x{component:X} is already used under {self.name_of(parent_profile)}"
            )
        siblings.append(ProfileNode(name.strip(), component))
        siblings.sort(key=lambda n: n.component)
        return prof.from_components((*prof.components(parent_profile), component))

    def remove(self, profile: int) -> ProfileNode:
        siblings = self.children_of(prof.parent(profile))
        node = self.node(profile)
        if node is None:
            raise ProfileError(f"no node at profile {prof.fmt(profile)}")
        siblings.remove(node)
        return node

    def rename(self, profile: int, name: str) -> None:
        node = self.node(profile)
        if node is None:
            raise ProfileError(f"no node at profile {prof.fmt(profile)}")
        if not name.strip():
            raise ProfileError("a profile node needs a name")
        node.name = name.strip()

    def renumber(self, profile: int, component: int) -> int:
        """Give a node a new component; its subtree moves with it. Returns the new profile."""
        node = self.node(profile)
        if node is None:
            raise ProfileError(f"no node at profile {prof.fmt(profile)}")
        if not 1 <= component <= 0xF:
            raise ProfileError(f"component {component} is not 1…15")
        siblings = self.children_of(prof.parent(profile))
        if any(s is not node and s.component == component for s in siblings):
            raise ProfileError(f"component 0x{component:X} is already used by a sibling")
        node.component = component
        siblings.sort(key=lambda n: n.component)
        return prof.from_components((*prof.components(prof.parent(profile)), component))

    def merged(self, other: ProfileTree) -> ProfileTree:
        """A new tree with ``other``'s nodes added where this one has none."""

        def copy(n: ProfileNode) -> ProfileNode:
            return ProfileNode(n.name, n.component, [copy(c) for c in n.children], n.description)

        def merge_into(dst: list[ProfileNode], src: list[ProfileNode]) -> None:
            for s in src:
                d = next((n for n in dst if n.component == s.component), None)
                if d is None:
                    dst.append(copy(s))
                else:
                    merge_into(d.children, s.children)
            dst.sort(key=lambda n: n.component)

        result = ProfileTree(self.name, [copy(r) for r in self.roots], self.vendor,
                             self.description)
        merge_into(result.roots, other.roots)
        return result

    # -- JSON -------------------------------------------------------------------
    def to_json(self) -> dict[str, Any]:
        def node_json(n: ProfileNode) -> dict[str, Any]:
            d: dict[str, Any] = {"name": n.name, "component": f"0x{n.component:X}"}
            if n.description:
                d["description"] = n.description
            if n.children:
                d["children"] = [node_json(c) for c in n.children]
            return d

        nodes = [node_json(r) for r in self.roots]
        doc: dict[str, Any] = {"format": TREE_FORMAT, "name": self.name}
        if self.description:
            doc["description"] = self.description
        if self.vendor:
            doc["vendor"] = self.vendor
        doc["nodes"] = nodes
        return doc

    @classmethod
    def from_json(cls, doc: object, where: str = "") -> ProfileTree:
        """Build a tree, raising ProfileError that names the JSON path of a bad node."""
        if not isinstance(doc, dict) or doc.get("format") != TREE_FORMAT:
            raise ProfileError(f"{where}: not a {TREE_FORMAT} document")

        def parse(items: object, path: str, depth: int) -> list[ProfileNode]:
            if not isinstance(items, list):
                raise ProfileError(f"{where}{path}: expected a list")
            if items and depth > prof.MAX_DEPTH:
                raise ProfileError(f"{where}{path}: deeper than {prof.MAX_DEPTH} levels")
            nodes: list[ProfileNode] = []
            for i, item in enumerate(items):
                p = f"{path}[{i}]"
                if not isinstance(item, dict) or not isinstance(item.get("name"), str):
                    raise ProfileError(f"{where}{p}: a node needs a name")
                comp = item.get("component")
                try:
                    comp = int(comp, 0) if isinstance(comp, str) else comp
                except ValueError:
                    comp = None
                if not isinstance(comp, int) or not 1 <= comp <= 0xF:
                    raise ProfileError(f"{where}{p}.component: must be 1…15")
                if any(n.component == comp for n in nodes):
                    raise ProfileError(f"{where}{p}.component: 0x{comp:X} used twice")
                children = parse(item.get("children", []), f"{p}.children", depth + 1)
                nodes.append(ProfileNode(item["name"], comp, children, item.get("description", "")))
            return nodes

        for key in ("vendor", "description"):
            if not isinstance(doc.get(key, ""), str):
                raise ProfileError(f"{where}: {key}: must be text")
        return cls(str(doc.get("name", "profiles")), parse(doc.get("nodes", []), "nodes", 1),
                   doc.get("vendor", ""), doc.get("description", ""))


def ranked_trees(trees: list[ProfileTree], profiles: Iterable[int]) -> list[ProfileTree]:
    """``trees``, the one naming the most of ``profiles`` exactly first (ties: the order
    given, the shipped trees before the user's and vendors')."""
    wanted = [p for p in profiles if p]
    scores = [sum(1 for p in wanted if t.names_exactly(p)) for t in trees]
    order = sorted(range(len(trees)), key=lambda i: (-scores[i], i))
    return [trees[i] for i in order]


def best_tree(trees: list[ProfileTree], profiles: Iterable[int]) -> ProfileTree:
    """The tree that names the most of ``profiles`` exactly (ties: the earlier tree); the
    first tree when none names any."""
    return ranked_trees(trees, profiles)[0] if trees else ProfileTree("profiles")


class ProfileNames(ProfileTree):
    """The names of one system's profiles, each from the tree that knows it.

    Every lookup (``name_of``, ``short_name``, ``node``, ``names_exactly``, ``walk``) takes
    a profile's whole path from one tree. Which tree, when several could:

    1. a code only one tree names exactly is named by that tree;
    2. a code several trees name (the thesis test tree's ``0x2200`` Push Button is the
       prosthetic tree's Grip) is named by the tree that names the most profiles of the
       devices carrying it — a device's other channels tell which family it belongs to;
       a tie there goes to the tree that names the most of the whole system, then to the
       order the trees were given (shipped before the user's and vendors');
    3. a code no tree names exactly is named by the tree that knows the longest start of
       its path (same ties), the rest in hex.

    So a thesis joystick on a prosthesis reads "Joystick › Push Button" while the hand
    next to it reads "Terminal Device › Grip › Power Grip". The attributes of a single
    tree (``name``, ``roots``, ``vendor``) are those of :attr:`primary`, the tree that names
    the most of the system. A view for reading: edit the trees themselves.
    """

    def __init__(self, trees: list[ProfileTree],
                 devices: Iterable[Iterable[int]] = ()) -> None:
        groups = [[p for p in g if p] for g in devices]
        self.trees = ranked_trees(trees, [p for g in groups for p in g]) or [
            ProfileTree("profiles")]
        self.primary = self.trees[0]
        super().__init__(self.primary.name, self.primary.roots, self.primary.vendor,
                         self.primary.description)
        #: Codes several trees name, settled by the devices that carry them (rule 2).
        self._settled: dict[int, ProfileTree] = {}
        for code in {p for g in groups for p in g}:
            knowing = [t for t in self.trees if t.names_exactly(code)]
            if len(knowing) < 2:
                continue
            around = [p for g in groups if code in g for p in g]
            self._settled[code] = max(
                knowing, key=lambda t: (sum(1 for p in around if t.names_exactly(p)),
                                        -self.trees.index(t)))

    def tree_of(self, profile: int) -> ProfileTree:
        """The tree that names ``profile`` (see the class's rules)."""
        settled = self._settled.get(profile)
        if settled is not None:
            return settled
        for tree in self.trees:
            if tree.names_exactly(profile):
                return tree
        return max(self.trees, key=lambda t: (len(t.node_path(profile)), -self.trees.index(t)))

    def node_path(self, profile: int) -> list[ProfileNode]:
        return self.tree_of(profile).node_path(profile)

    def walk(self) -> list[tuple[int, ProfileNode]]:
        """Every named profile once, by the tree that names it, in profile order."""
        seen: dict[int, ProfileNode] = {}
        for tree in self.trees:
            for value, node in tree.walk():
                if value not in seen and self.tree_of(value) is tree:
                    seen[value] = node
        return sorted(seen.items(), key=lambda item: item[0])

    def children_of(self, profile: int) -> list[ProfileNode]:
        raise ProfileError("these names come from several profile trees: edit one of them")

    def rename(self, profile: int, name: str) -> None:
        raise ProfileError("these names come from several profile trees: edit one of them")
