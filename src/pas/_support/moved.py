"""Keywords that moved: a one-line ``TypeError`` naming the new place of an old keyword."""

from __future__ import annotations

import functools
import inspect

__all__ = ["keywords_moved"]


def keywords_moved(moved: dict, page: str, name: str | None = None):
    """Decorate a function so that a keyword it does not take, but ``moved`` names, raises
    ``TypeError: f: name is now <place>; see <page>`` (its signature stays as written);
    ``name`` is what the message calls the function (default its ``__name__``).

    Examples
    --------
    >>> @keywords_moved({"k1": "stopping=Stopping(k1=...)"}, "docs/x.md")
    ... def f(*, eps2=0.1):
    ...     return eps2
    >>> f(k1=3)
    Traceback (most recent call last):
    ...
    TypeError: f: k1 is now stopping=Stopping(k1=...); see docs/x.md
    """
    def decorate(func):
        names = set(inspect.signature(func).parameters)
        where = name or func.__name__

        @functools.wraps(func)
        def wrapper(*args, **kwargs):
            for key in kwargs:
                if key not in names:
                    place = moved.get(key)
                    if place is None:
                        raise TypeError(f"{where}: unknown keyword argument {key!r}; see {page}")
                    raise TypeError(f"{where}: {key} is now {place}; see {page}")
            return func(*args, **kwargs)

        return wrapper

    return decorate
