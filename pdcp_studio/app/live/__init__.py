"""The live bus behind a document: connecting, the session bridge, layout, plot."""
