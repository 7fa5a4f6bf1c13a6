"""The trace's files: which files are captures, opening one into a store off the GUI thread,
saving what the trace shows, and recording the live frames."""
