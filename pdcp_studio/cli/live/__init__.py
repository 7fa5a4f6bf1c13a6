"""Commands on a live prosthesis or bus: the changes that go through the change road
(``apply``, ``policy``, ``param set``, ``config read/write/save``, ``history re-anchor``),
``scan``, the headless arbitrator and its log, the SLCAN bridge and the host-link
conformance suite."""
