"""mkdocs hook: the docstrings' Sphinx roles and ``pas.X`` names become links.

The docstrings cross-reference with Sphinx roles (``:func:`pas.run_pas```,
``:class:`~pas.strategies.screening.Event```), which ``help()`` and numpydoc
tools read.  mkdocstrings renders a role as its name before a code span; this
hook turns the pair into a cross-reference that the ``autorefs`` plugin
resolves to the object's entry in the API reference (a leading ``~`` shows
only the last name, as Sphinx does).  A role naming an object the reference
does not document stays plain code.

Each public name is documented from the module that defines it
(``pas.api.run_pas``); :func:`on_env` lets ``pas.run_pas``, the name users
import, point to that entry too.
"""

from __future__ import annotations

import re

from mkdocs.plugins import event_priority

_ROLE = re.compile(r":(?:py:)?(?:func|class|mod|meth|attr|data|obj|exc|const):"
                   r"<code>(~?)([^<]+)</code>")


def _autoref(match):
    tilde, target = match.groups()
    target = target.strip()
    shown, _, identifier = target.partition(" &lt;")  # :meth:`title <target>`
    if identifier:
        identifier = identifier.removesuffix("&gt;")
    else:
        identifier, shown = target, target.rsplit(".", 1)[-1] if tilde else target
    if not identifier.startswith("pas."):  # a name relative to its module: try the public one
        identifier = f"pas.{identifier}"
    return f'<autoref identifier="{identifier}" optional><code>{shown}</code></autoref>'


def on_page_content(html, **kwargs):
    return _ROLE.sub(_autoref, html)


def public_names() -> dict[str, str]:
    """``pas.X`` -> the full name of the object it is, for every public name of ``pas``."""
    import pas

    out = {}
    for name in pas.__all__:
        obj = getattr(pas, name)
        module = getattr(obj, "__module__", None)
        if module and module.startswith("pas") and hasattr(obj, "__qualname__"):
            out[f"pas.{name}"] = f"{module}.{obj.__qualname__}"
    return out


@event_priority(0)  # before autorefs (-50) applies the cross-references
def on_env(env, config, files, **kwargs):
    autorefs = config.plugins["autorefs"]
    pages = {f.page.url: f.page for f in files if f.page is not None}
    for alias, full in public_names().items():
        try:
            url, _ = autorefs.get_item_url(full)
        except KeyError:
            continue
        page_url, _, anchor = url.partition("#")
        autorefs.register_anchor(pages[page_url], alias, anchor, primary=False)
    return env
