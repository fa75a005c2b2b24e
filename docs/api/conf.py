"""Sphinx configuration of the API reference (built by tests/docs/test_docs_build.py with ``-n -W``)."""

project = "MR Modeler"
extensions = ["sphinx.ext.autodoc", "sphinx.ext.autosummary", "numpydoc"]
autosummary_generate = True
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
autodoc_default_options: dict[str, object] = {}
html_theme = "alabaster"
exclude_patterns = ["_build"]

# Every reference must resolve (nitpicky, as the test builds it). The library's annotations are strings
# (``from __future__ import annotations``); these names are shown and linked as the documented aliases.
nitpicky = True
autodoc_type_aliases = {
    name: f"mrm.api.{name}"
    for name in (
        "Batch",
        "Image",
        "ModelLike",
        "ModelName",
        "Number",
        "ObjectArray",
        "Polygonal",
        "Shape",
        "TransformLike",
    )
}

# Targets outside this project. Their inventories (intersphinx) cannot be fetched here: the build runs
# offline, in the tests. Each is named, none of the project's own names is ignored.
nitpick_ignore_regex = [
    # numpy (arrays, dtypes, scalar types, numpy.typing and the private aliases ArrayLike expands to)
    (r"py:.*", r"numpy(\..*)?"),
    (r"py:.*", r"np\..*"),
    (r"py:.*", r"npt\..*"),
    # shapely (geometries) and affine (rasterio's Affine)
    (r"py:.*", r"shapely(\..*)?"),
    (r"py:.*", r"affine(\..*)?"),
    # the Python standard library
    (r"py:.*", r"(os|pathlib|collections\.abc|fractions|importlib|typing|enum|dataclasses)(\..*)?"),
]


def _short_names(app, env, node, contnode):
    """Resolve a short name in a docstring to the one documented object it names.

    ``:class:`ParameterError```, ``:meth:`GeoRef.to_world``` or ``:func:`mrm.voxelize``` (a name of the
    curated namespace) written in a module that does not define the name; several candidates stay unresolved.
    """
    if node.get("refdomain") != "py":
        return None
    import importlib

    domain = env.get_domain("py")
    target = node["reftarget"].lstrip("~.")
    if target.startswith("mrm.") and target.count(".") >= 1:  # a name of the curated namespace, mrm.X[.y]
        head, _, rest = target[4:].partition(".")
        try:
            obj = getattr(importlib.import_module("mrm"), head)
            target = f"{obj.__module__}.{obj.__qualname__}" + (f".{rest}" if rest else "")
        except (AttributeError, ImportError):
            pass
    names = [n for n in domain.objects if n == target or n.endswith("." + target)]
    if len(names) > 1:  # prefer the module the reference is written in
        here = node.get("py:module") or ""
        names = [n for n in names if here and n.startswith(here + ".")] or names
    if len(names) != 1:
        return None
    return domain.resolve_xref(env, node["refdoc"], app.builder, node["reftype"], names[0], node, contnode)


def setup(app):
    """Sphinx's hook: install the short-name resolver."""
    app.connect("missing-reference", _short_names)
