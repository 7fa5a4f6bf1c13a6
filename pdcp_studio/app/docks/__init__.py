"""The panels docked around the graph: tree, inspector, plans, history, events, simulator."""
