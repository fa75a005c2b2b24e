"""Sphinx configuration of the API reference (built by tests/docs/test_docs_build.py)."""

project = "MR Modeler"
extensions = ["sphinx.ext.autodoc", "sphinx.ext.autosummary", "numpydoc"]
autosummary_generate = True
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
autodoc_default_options: dict[str, object] = {}
html_theme = "alabaster"
exclude_patterns = ["_build"]
