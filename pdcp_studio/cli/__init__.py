"""The command line: one small module per subcommand (``main`` reads the table); the
commands on files and systems offline here, those on a live prosthesis or bus in ``live/``."""
