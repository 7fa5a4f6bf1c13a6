"""Stored-configuration codec speed: decode and encode a 1,000-link configuration.

Target (issue 2): under 20 ms each on the 2-core CI machine. Prints the median and the
best of many runs so one slow scheduling hiccup does not decide the figure.

    python benchmarks/codec.py [--links N] [--runs R]
"""

from __future__ import annotations

import argparse

from _timing import median_and_best

from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.storage import config_codec

TARGET_MS = 20.0


def make_collection(n_links: int) -> ConfigCollection:
    """One configuration of ``n_links`` links between distinct, fully described channels."""
    links = []
    for i in range(n_links):
        out = StoredChannel(index=1 + i % 15, vid=0x0A51, pid=100 + i % 50, serial=i,
                            type=0x9000, profile=0x4222, owner_type=2, owner_profile=0x4000)
        inp = StoredChannel(index=1 + i % 15, vid=0x0A51, pid=300 + i % 50, serial=i,
                            type=0x9300, profile=0x4224, owner_type=3, owner_profile=0x4200)
        links.append(StoredLink(input=inp, output=out, index=i + 1))
    return ConfigCollection([StoredConfiguration(index=1, links=links)])


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--links", type=int, default=1000)
    ap.add_argument("--runs", type=int, default=50)
    args = ap.parse_args()

    collection = make_collection(args.links)
    data = config_codec.dumps(collection)
    assert config_codec.dumps(config_codec.loads(data)) == data, "round trip must be exact"

    enc_med, enc_min = median_and_best(lambda: config_codec.dumps(collection), args.runs)
    dec_med, dec_min = median_and_best(lambda: config_codec.loads(data), args.runs)
    print(f"configuration: {args.links} links, {len(data)} bytes, {args.runs} runs")
    print(f"{'':8} {'median ms':>10} {'best ms':>9} {'target':>8}")
    for name, med, best in (("encode", enc_med, enc_min), ("decode", dec_med, dec_min)):
        verdict = "ok" if med < TARGET_MS else "SLOW"
        print(f"{name:8} {med:10.2f} {best:9.2f} {TARGET_MS:7.0f}  {verdict}")
    return 0 if max(enc_med, dec_med) < TARGET_MS else 1


if __name__ == "__main__":
    raise SystemExit(main())
