"""Live bus sessions: one face for the CLI and the app, their transports, bus URLs."""
