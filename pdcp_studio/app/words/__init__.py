"""Plain words for prosthetists: part names, plan steps, findings, plural counts."""
