"""The window's panels, one per module: each reads the document and writes back through
its setters."""
