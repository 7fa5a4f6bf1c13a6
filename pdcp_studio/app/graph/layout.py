"""Layered placement of device cards: sensors → control → terminal devices, left to right.

A Sugiyama-style layout, no force-directed step (``spring_layout`` takes seconds beyond a
few hundred nodes). networkx assigns the layers: the device graph's condensation (a
feedback loop collapses into one node) in topological order, each device at the longest
path from the sources but at least its role's layer, terminal devices last. Then a few
barycentre sweeps order each layer to reduce crossings, and the cards are stacked in
columns — rather than networkx's ``multipartite_layout``, which knows neither card
heights nor that a very tall layer should wrap into sub-columns. Pure: no Qt.
networkx is imported on first use; the app preloads it while a bus connects.

Stability: :func:`place` keeps every remembered position and puts only newcomers, at
the bottom of their layer's column, so one device coming or going never reshuffles
the rest.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from pdcp_studio.app.graph import style
from pdcp_studio.app.graph.analysis import ROLE_LAYER, TERMINAL, device_role
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Device, System

Position = tuple[float, float]
PITCH = style.CARD_WIDTH + style.LAYER_GAP
SWEEPS = 4


def card_height(device: Device) -> float:
    rows = max(1, len(device.channels))
    return style.HEADER_HEIGHT + rows * style.ROW_HEIGHT + style.FOOTER


def planned_bounds(system: System, positions: Mapping[DeviceKey, tuple[float, float]]
                   ) -> tuple[float, float, float, float]:
    """Where the cards will be (x, y, width, height; all 0 without cards), from their
    places alone: a large bus's graph has its size before its cards are made."""
    r = style.PORT_RADIUS + 2
    boxes = []
    for key, device in system.devices.items():
        x, y = positions.get(key, (0.0, 0.0))
        boxes.append((x - r, y - 2, x + style.CARD_WIDTH + r, y + card_height(device) + 4))
    if not boxes:
        return 0.0, 0.0, 0.0, 0.0
    left, top = min(b[0] for b in boxes), min(b[1] for b in boxes)
    right, bottom = max(b[2] for b in boxes), max(b[3] for b in boxes)
    return left, top, right - left, bottom - top


def device_edges(system: System) -> dict[DeviceKey, set[DeviceKey]]:
    """Device → devices it feeds (self-links ignored)."""
    succ: dict[DeviceKey, set[DeviceKey]] = {k: set() for k in system.devices}
    for link in system.links:
        a, b = link.output.device, link.input.device
        if a != b and a in succ and b in succ:
            succ[a].add(b)
    return succ


def _device_graph(system: System) -> Any:
    """The devices as a networkx DiGraph, an edge where one feeds another."""
    import networkx as nx

    graph = nx.DiGraph()
    graph.add_nodes_from(system.devices)
    graph.add_edges_from((a, b) for a, bs in device_edges(system).items() for b in bs)
    return graph


def assign_layers(system: System) -> dict[DeviceKey, int]:
    """Layers by networkx: longest path over the condensation (a feedback loop shares a
    layer), at least the role's layer; terminal devices last."""
    import networkx as nx

    roles = {k: device_role(d) for k, d in system.devices.items()}
    graph = _device_graph(system)
    dag = nx.condensation(graph)
    members = {c: dag.nodes[c]["members"] for c in dag.nodes}
    level: dict[int, int] = {}
    for comp in nx.topological_sort(dag):
        base = min(ROLE_LAYER[roles[k]] if roles[k] != TERMINAL else 1 for k in members[comp])
        preds = [level[p] + 1 for p in dag.predecessors(comp)]
        level[comp] = max([base, *preds])
    mapping = dag.graph["mapping"]
    layer = {k: level[mapping[k]] for k in system.devices}
    # Compact: remove empty layers, then put every terminal device in the last one.
    used = sorted({layer[k] for k in layer if roles[k] != TERMINAL})
    remap = {v: i for i, v in enumerate(used)}
    last = len(used)
    return {k: (last if roles[k] == TERMINAL else remap[layer[k]]) for k in layer}


def _row_fraction(device: Device, index: int) -> float:
    """Where a channel's port sits on its card, 0 (top) … <1 (bottom): inputs, then outputs."""
    rows = sorted(device.channels.values(), key=lambda c: (c.is_output, c.index))
    for i, ch in enumerate(rows):
        if ch.index == index:
            return i / max(1, len(rows))
    return 0.0


def _order(system: System, layers: dict[DeviceKey, int]) -> list[list[DeviceKey]]:
    """Devices per layer, ordered by barycentre sweeps to reduce link crossings."""
    n = max(layers.values(), default=-1) + 1
    columns: list[list[DeviceKey]] = [[] for _ in range(n)]
    for key in system.devices:  # file order is the user's order: a good start
        columns[layers[key]].append(key)
    # Port-level neighbours: a device's barycentre is taken at the rows of the ports its
    # links use, so two sensors feeding inputs 1 and 2 of one control unit come out in
    # that order instead of crossing.
    pred: dict[DeviceKey, list[tuple[DeviceKey, float]]] = {k: [] for k in system.devices}
    succ: dict[DeviceKey, list[tuple[DeviceKey, float]]] = {k: [] for k in system.devices}
    for link in system.links:
        a, b = link.output.device, link.input.device
        if a == b or a not in pred or b not in pred:
            continue
        pred[b].append((a, _row_fraction(system.devices[a], link.output.index)))
        succ[a].append((b, _row_fraction(system.devices[b], link.input.index)))
    for sweep in range(SWEEPS):
        forward = sweep % 2 == 0
        rng = range(1, n) if forward else range(n - 2, -1, -1)
        for i in rng:
            ref_col = columns[i - 1] if forward else columns[i + 1]
            pos = {k: j for j, k in enumerate(ref_col)}
            neigh = pred if forward else succ
            current = {k: j for j, k in enumerate(columns[i])}

            def bary(k: DeviceKey, pos: dict[DeviceKey, int] = pos,
                     neigh: dict[DeviceKey, list[tuple[DeviceKey, float]]] = neigh,
                     current: dict[DeviceKey, int] = current) -> tuple[float, int]:
                """The device's barycentre, then its place so far (a stable order)."""
                ps = [pos[m] + frac for m, frac in neigh[k] if m in pos]
                mean = (sum(ps) / len(ps) if ps
                        else current[k] * (len(pos) / max(1, len(current))))
                return mean, current[k]

            columns[i].sort(key=bary)
    return columns


def layered_layout(system: System, aspect: float = 1.0) -> dict[DeviceKey, Position]:
    """Top-left corners of every card, laid out from scratch; a tall layer wraps into
    sub-columns so the whole comes out about ``aspect`` (width / height) — the shape of
    the window it is shown in, so that fitting it loses the least room."""
    if not system.devices:
        return {}
    layers = assign_layers(system)
    columns = _order(system, layers)
    heights = {k: card_height(d) for k, d in system.devices.items()}
    total_area = sum((h + style.CARD_GAP) * PITCH for h in heights.values())
    aspect = max(0.5, min(3.0, aspect))
    max_col = max(900.0, math.sqrt(total_area / aspect) * 1.1)
    # Split a tall layer into sub-columns so big systems stay roughly square.
    placed: dict[DeviceKey, Position] = {}
    col_tops: list[tuple[list[tuple[DeviceKey, float]], float]] = []
    for col in columns:
        sub: list[tuple[DeviceKey, float]] = []
        y = 0.0
        groups: list[tuple[list[tuple[DeviceKey, float]], float]] = []
        for key in col:
            h = heights[key]
            if sub and y + h > max_col:
                groups.append((sub, y - style.CARD_GAP))
                sub, y = [], 0.0
            sub.append((key, y))
            y += h + style.CARD_GAP
        if sub or not groups:
            groups.append((sub, max(0.0, y - style.CARD_GAP)))
        col_tops.extend(groups)
    tallest = max((h for _, h in col_tops), default=0.0)
    for ci, (sub, height) in enumerate(col_tops):
        x = ci * PITCH
        offset = (tallest - height) / 2
        for key, y in sub:
            placed[key] = (x, y + offset)
    return placed


def place(system: System, remembered: Mapping[DeviceKey, Position],
          aspect: float = 1.0) -> dict[DeviceKey, Position]:
    """Positions for every device: remembered ones kept, newcomers at their layer's bottom
    (none remembered: a fresh layout about ``aspect`` wide)."""
    known = {k: remembered[k] for k in system.devices if k in remembered}
    if not known:
        return layered_layout(system, aspect)
    new = [k for k in system.devices if k not in known]
    if not new:
        return known
    layers = assign_layers(system)
    xs_by_layer: dict[int, list[float]] = {}
    for k, (x, _y) in known.items():
        xs_by_layer.setdefault(layers[k], []).append(x)
    result = dict(known)
    for key in new:
        lay = layers[key]
        if lay in xs_by_layer:
            xs = sorted(xs_by_layer[lay])
            x = xs[len(xs) // 2]
        else:
            x = min(x for x, _ in known.values()) + lay * PITCH
        column = [(k, p) for k, p in result.items() if abs(p[0] - x) < style.CARD_WIDTH]
        y = max((p[1] + card_height(system.devices[k]) for k, p in column
                 if k in system.devices), default=-style.CARD_GAP) + style.CARD_GAP
        result[key] = (x, y)
        xs_by_layer.setdefault(lay, []).append(x)
    return result
