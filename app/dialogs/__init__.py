"""The window's dialogs, one per module, and ``ask``: its questions as functions."""
