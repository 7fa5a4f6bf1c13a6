"""The main window's controllers: each receives what it needs (the document, the live
connection, the status line, a parent for its dialogs), never the window itself."""
