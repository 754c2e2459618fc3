"""Parts in, documents out; nothing here knows a gripper exists.

- :mod:`~fcgrasp.io.parts`: reading a part file (JSON, GeoJSON, WKT, SVG, DXF, images;
  the readers are the private ``_read_*`` modules), choosing one of several;
- :mod:`~fcgrasp.io.demo`: the built-in parts (``demo:NAME``);
- :mod:`~fcgrasp.io.units`: units of length and their conversions;
- :mod:`~fcgrasp.io.report`: every JSON document fcgrasp writes;
- :mod:`~fcgrasp.io.outputs`: outputs written as a set, atomically, never over an input.
"""
