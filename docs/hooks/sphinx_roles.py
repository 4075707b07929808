"""mkdocs hook: show the Sphinx roles of the numpydoc docstrings as plain code.

The docstrings cross-reference with ``:func:`pas.run_pas``` and
``:class:`~pas.strategies.screening.Event``` (Sphinx roles, read by ``help()`` and by
numpydoc tools).  mkdocstrings renders the role name as text before the code
span; this drops it, and a leading ``~`` keeps only the last name, as Sphinx
shows it.
"""

import re

_ROLE = re.compile(r":(?:py:)?(?:func|class|mod|meth|attr|data|obj|exc|const):<code>(~?)([^<]+)</code>")


def _plain(match):
    tilde, target = match.groups()
    return f"<code>{target.rsplit('.', 1)[-1] if tilde else target}</code>"


def on_page_content(html, **kwargs):
    return _ROLE.sub(_plain, html)
