"""The main window, its controllers, menus and toolbar, the start page."""
