"""PDCP Studio's tests: a package, so helper modules are imported by their full name."""
