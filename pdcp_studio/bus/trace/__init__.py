"""The trace: frame decoder, statistics, capture formats, bus time, replay."""
