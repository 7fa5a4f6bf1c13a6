"""The shipped resources (package data, read through importlib.resources; see
pdcp_studio.paths). In the source tree pdcp_studio/resources links to this folder."""
