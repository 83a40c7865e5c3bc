"""The private base of the package: argument checks, arrays, the bridge to the core, the HTML
cards, size guards, the user's files and the one overwrite policy; and the body (``Cylinder``)
and the units (``Units``), public as ``eccjump.Cylinder`` and ``eccjump.Units``. The lowest
layer: nothing here imports from a layer above (``tests/test_structure.py``, ``LAYERS``)."""
