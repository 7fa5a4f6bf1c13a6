"""Talking to devices: the request/response engine, reading one device, scanning the bus."""
