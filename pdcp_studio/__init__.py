"""PDCP Studio: see, configure and repair the PDCP bus inside a powered prosthesis."""

__version__ = "0.1.0"
