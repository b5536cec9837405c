"""LightInv desktop application: a thin PySide6 + pyvista shell over ``lightinv_core``."""
