"""The node map: what a monitor knew of the bus, saved beside a capture as JSON, so a
replay decodes the capture as the monitor did while recording it."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from pdcp_studio.bus.trace.files.capture import CaptureError
from pdcp_studio.bus.trace.frames import LinkMap, ref_json
from pdcp_studio.bus.trace.knowledge import BusKnowledge
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction

NODE_MAP_FORMAT = "pdcp-studio-node-map/1"
#: A capture's node map is saved beside it as ``<capture>`` + this suffix.
NODE_MAP_SUFFIX = ".nodemap.json"
#: A node map larger than this is not one.
MAX_NODE_MAP_BYTES = 1 << 20


def node_map_json(known: BusKnowledge, links: LinkMap) -> dict[str, Any]:
    """``known`` and the caller's ``links`` (node ID → output, inputs) as a node map."""
    return {
        "format": NODE_MAP_FORMAT,
        "devices": [{"node_id": n, "vid": k.vid, "pid": k.pid, "serial": k.serial}
                    for n, k in sorted(known.devices.items())],
        "outputs": [{"node_id": c, "device_node": d, "index": i}
                    for c, (d, i) in sorted(known.outputs.items())],
        "inputs": [{"node_id": c, "device_node": d, "index": i}
                   for c, ins in sorted(known.inputs.items()) for d, i in sorted(ins)],
        "directions": [{"device_node": d, "index": i, "direction": str(v)}
                       for (d, i), v in sorted(known.directions.items())],
        "links": [{"node_id": node, "output": ref_json(out),
                   "inputs": [ref_json(r) for r in ins]}
                  for node, (out, ins) in sorted(links.items())],
    }


def load_node_map(known: BusKnowledge, links: LinkMap, doc: Any,
                  where: str = "node map") -> None:
    """Add a saved node map to ``known`` and (when it is a dict) ``links``; ValueError
    names what is wrong."""
    try:
        if doc.get("format") != NODE_MAP_FORMAT:
            raise ValueError(f"format is {doc.get('format')!r}, not {NODE_MAP_FORMAT!r}")
        for d in doc.get("devices", []):
            known.devices[_node(d["node_id"])] = DeviceKey(int(d["vid"]), int(d["pid"]),
                                                          int(d["serial"]))
        for o in doc.get("outputs", []):
            owner = (0, 0) if int(o["device_node"]) == 0 else (
                _node(o["device_node"]), int(o["index"]))  # 0: inferred, owner unknown
            known.outputs[_node(o["node_id"])] = owner
        for i in doc.get("inputs", []):
            known.inputs.setdefault(_node(i["node_id"]), set()).add(
                (_node(i["device_node"]), int(i["index"])))
        for d in doc.get("directions", []):
            known.directions[_node(d["device_node"]), int(d["index"])] = Direction(
                d["direction"])
        saved = doc.get("links", [])
        if saved and isinstance(links, dict):
            for link in saved:
                links[_node(link["node_id"])] = (
                    _ref_from(link["output"]), tuple(_ref_from(r) for r in link["inputs"]))
    except (AttributeError, KeyError, TypeError, ValueError) as err:
        raise ValueError(f"{where}: {err}") from err


def _ref_from(doc: Any) -> Any:
    return doc if isinstance(doc, str) else ChannelRef(**doc)


def _node(value: Any) -> int:
    node = int(value)
    if not 1 <= node <= 254:
        raise ValueError(f"node ID {node} is out of range (1–254)")
    return node


def write_node_map(capture: str | Path, node_map: dict[str, Any]) -> Path:
    """Save ``node_map`` atomically beside ``capture``; returns the sidecar's path."""
    from pdcp_studio.storage.atomic import atomic_write_text

    path = Path(str(capture) + NODE_MAP_SUFFIX)
    atomic_write_text(path, json.dumps(node_map, indent=1) + "\n")
    return path


def read_node_map(capture: str | Path) -> dict[str, Any] | None:
    """The node map saved beside ``capture``, or None; CaptureError if it is unreadable."""
    path = Path(str(capture) + NODE_MAP_SUFFIX)
    if not path.is_file():
        return None
    try:
        with path.open("rb") as handle:
            raw = handle.read(MAX_NODE_MAP_BYTES + 1)
        if len(raw) > MAX_NODE_MAP_BYTES:
            raise ValueError("larger than 1 MiB")
        doc = json.loads(raw)
        if not isinstance(doc, dict):
            raise ValueError("not a JSON object")
        return doc
    except (OSError, ValueError) as err:
        raise CaptureError(path, f"not a readable node map ({err})") from err
