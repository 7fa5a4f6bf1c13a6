"""Capture files: every capture format read by its content and written atomically, the node
map saved beside a capture, and a capture replayed as the monitor showed it live."""
