"""A griffe extension for the API reference: the site shows what ``help()`` shows.

What the static reading of the sources cannot do by itself:

* a docstring completed at import (``JarmResult`` lists the fields of
  ``eccjump.classification.fields``; the shared entries of ``eccjump._base.docs`` fill the
  ``%(alpha)s`` placeholders) is taken from the imported object, so the page and ``help()``
  agree;
* the compiled core (``eccjump._core``) is read by inspection, which gives its constants the
  docstring of their type (``str``): their docstrings come from its stub, ``_core.pyi``;
* a result's ``plot``, made at import from its class's ``_plot_doc``
  (``eccjump._base.canvas.Plottable``), is shown as a method of the class: the signatures of
  ``Plottable.plot`` with the class's docstring;
* a numpydoc "See Also" section (``name : what``) becomes a list of links;
* the Sphinx roles of the docstrings (``:func:`~eccjump.region```, ``:class:`Reason```, ...),
  which read well in ``help()``, become links to the documented object, or plain code where
  the object has no page (an optional cross-reference: never a broken link).
"""

from __future__ import annotations

import copy
import importlib
import inspect
import re
from pathlib import Path
from typing import Any

import griffe

_ROLE = re.compile(r":(?:py:)?(?:func|class|meth|attr|data|mod|obj|exc|const):`(~?)([\w.]+)`")


def _runtime(path: str) -> Any:
    """The imported object at ``path``, or None."""
    parts = path.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj: Any = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        try:
            for name in parts[cut:]:
                obj = getattr(obj, name)
        except AttributeError:
            return None
        return obj
    return None


def _target(obj: griffe.Object, name: str) -> str | None:
    """The full path ``name`` means in the scope of ``obj``, or None."""
    if name.startswith("eccjump."):
        return name
    head, _, rest = name.partition(".")
    scope: griffe.Object | None = obj
    while scope is not None:
        try:
            path = scope.resolve(head)
        except (griffe.NameResolutionError, griffe.AliasResolutionError, KeyError):
            scope = scope.parent
            continue
        return f"{path}.{rest}" if rest else path
    return None


_SEE_ALSO = re.compile(r"^See Also\n-+\n(.*?)(?=\n\n\S|\Z)", re.MULTILINE | re.DOTALL)
_ENTRY = re.compile(r"^([\w.]+) : ", re.MULTILINE)


def _see_also(text: str) -> str:
    """Each ``name : what`` entry of "See Also" as a list item naming ``:func:`name```."""

    def items(match: re.Match[str]) -> str:
        body = _ENTRY.sub(lambda m: f"- :obj:`{m.group(1)}`: ", match.group(1))
        body = re.sub(r"\n(?!- )\s*", " ", body)  # an entry's continuation lines
        return "See Also\n--------\n" + body

    return _SEE_ALSO.sub(items, text)


def _links(obj: griffe.Object, text: str) -> str:
    def link(match: re.Match[str]) -> str:
        short, name = match.group(1), match.group(2)
        shown = name.rsplit(".", 1)[-1] if short else name
        path = _target(obj, name)
        if path is None:
            return f"`{shown}`"
        return f'<autoref identifier="{path}" optional><code>{shown}</code></autoref>'

    return _ROLE.sub(link, text)


def _stub_docstrings(pkg: griffe.Module) -> None:
    """The docstrings of the core's module-level names, from ``_core.pyi``."""
    core = pkg.members.get("_core")
    if core is None or core.filepath is None:
        return
    stub_path = Path(str(core.filepath)).with_name("_core.pyi")
    if not stub_path.exists():
        return
    stub = griffe.visit("_core", filepath=stub_path, code=stub_path.read_text())
    for name, member in stub.members.items():
        if member.is_alias or name not in core.members:
            continue
        if member.is_attribute and member.docstring is not None:
            core.members[name].docstring = griffe.Docstring(
                member.docstring.value, parent=core.members[name]
            )


def _own_plot(cls: griffe.Class, base: griffe.Function) -> None:
    """The ``plot`` that ``cls`` gets at import from its ``_plot_doc``, where that stands."""
    runtime = _runtime(f"{cls.path}.plot")
    doc = cls.members["_plot_doc"]
    own = griffe.Function(
        "plot",
        lineno=doc.lineno,
        endlineno=doc.endlineno,
        parameters=griffe.Parameters(*map(copy.copy, base.parameters)),  # a Function owns them
        returns=base.returns,
    )
    own.overloads = base.overloads
    own.docstring = griffe.Docstring(inspect.getdoc(runtime) or "", parent=own)
    cls.set_member("plot", own)
    # in its place: the page lists members in the order of ``members`` (by an alias, it
    # has no line numbers), so the ones after ``_plot_doc`` move behind ``plot``
    names = list(cls.members)
    for name in names[names.index("_plot_doc") + 1 : -1]:
        cls.members[name] = cls.members.pop(name)


class EccjumpDocstrings(griffe.Extension):
    """Runtime docstrings where they differ, and the Sphinx roles as cross-references."""

    def on_package(self, *, pkg: griffe.Module, **kwargs: Any) -> None:
        if pkg.name == "eccjump":
            _stub_docstrings(pkg)
            self._visit(pkg, seen=set())

    def _visit(self, obj: griffe.Object, seen: set[str]) -> None:
        if obj.path in seen:
            return
        seen.add(obj.path)
        if isinstance(obj, griffe.Class) and "_plot_doc" in obj.members:
            _own_plot(obj, obj.modules_collection["eccjump._base.canvas.Plottable.plot"])
        if obj.docstring is not None:
            if obj.kind in (griffe.Kind.CLASS, griffe.Kind.FUNCTION):
                runtime = _runtime(obj.path)
                doc = inspect.getdoc(runtime) if runtime is not None else None
                completed = "{" in obj.docstring.value or "%(" in obj.docstring.value
                if doc and doc != obj.docstring.value and completed:
                    obj.docstring.value = doc
            obj.docstring.value = _links(obj, _see_also(obj.docstring.value))
        for member in obj.members.values():
            if not member.is_alias:
                self._visit(member, seen)  # type: ignore[arg-type]
