"""Helpers below every layer, with no other ``pas`` import: argument checks
(:mod:`.checks`), strict JSON (:mod:`.strict_json`), lazy package exports
(:mod:`.lazy`) and one BLAS thread for small linear algebra (:mod:`.threads`)."""

DOCS_URL = "https://pas.readthedocs.io/"
"""The documentation site (``site_url`` of ``mkdocs.yml``): messages name its pages."""


def docs_page(page: str) -> str:
    """The address of the docs page ``page`` (its path under ``docs/``), for messages.

    >>> docs_page("reference/settings.md")
    'https://pas.readthedocs.io/reference/settings/'
    """
    return f"{DOCS_URL}{page.removesuffix('.md')}/"
