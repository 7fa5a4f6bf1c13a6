"""Simulated devices and the built-in simulated prostheses (rigs)."""
