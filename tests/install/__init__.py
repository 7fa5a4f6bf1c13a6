"""Installation tests: the package as users get it (wheel, prefix install, README)."""
