"""Dialogs and secondary windows: connect, compare, write configuration, help."""
