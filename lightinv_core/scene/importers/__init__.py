"""Model importers: one module per format (``obj``, ``gltf``, ``ply``, ``ifc`` and their
helpers), the neutral ``assembly`` every format hands its polygons to, and the
``registry`` that ``scene.loading`` looks a file's format up in. docs/obj-import.md is
the user guide; docs/architecture.md says how to add a format.
"""
