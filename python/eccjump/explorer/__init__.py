"""The explorer: sliders, the JARM region slice, the animated full motion and its numbers,
in a Jupyter widget (:func:`explore`) or a local web page (``eccjump explore``,
``eccjump.explorer.server.ExplorerServer``); the user guide's page "The explorer" describes it.

- ``controls``: the sliders, described once (ranges, steps, units);
- ``api``: the page's requests as plain functions of a query (``handle``);
- ``server``: the local HTTP server of the page (standard library);
- ``probability``: the P(JARM) panel of an uncertainty map given to the explorer (the file
  checked once, the slice of the current k_m);
- ``widget``: the anywidget, whose messages reach the same ``api.handle``;
- ``static/``: the page (one HTML file, one script, one style sheet; nothing from the
  internet).
"""

from eccjump.explorer.widget import explore

__all__ = ["explore"]
