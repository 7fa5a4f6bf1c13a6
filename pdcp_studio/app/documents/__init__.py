"""What the app opens and edits: documents, undo commands, files, recovery."""
