"""The profile layer on the bus: start-up, the hot-swap duty cycle, plans, and their thread."""
