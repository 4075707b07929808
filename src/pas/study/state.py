"""Where an asked event stands: one enum for the study loop and the study store.

Like Optuna's ``TrialState``: an event is ``PENDING`` from the moment it is
asked until its result is told, then finished in one of three states.  The
values are the ``status`` strings of the history rows; the store writes
``TRUE_POSITIVE`` as ``"done"`` on disk (:data:`pas.study.schema.STORED`).
"""

from __future__ import annotations

from enum import StrEnum

__all__ = ["EventState"]


class EventState(StrEnum):
    """State of an asked event.

    Examples
    --------
    >>> EventState.of_result(2.5, None), EventState.of_result(0.0, None)
    (<EventState.TRUE_POSITIVE: 'true_positive'>, <EventState.FALSE_POSITIVE: 'false_positive'>)
    >>> EventState.of_result(None, "solver diverged").is_finished()
    True
    """

    PENDING = "pending"
    TRUE_POSITIVE = "true_positive"
    FALSE_POSITIVE = "false_positive"
    FAILED = "failed"

    def is_finished(self) -> bool:
        """True once the event's result (a load, 0 or a failure) is in."""
        return self is not EventState.PENDING

    def is_evaluated(self) -> bool:
        """True for an HF evaluation that gave a load (0 included); these count as ``n_hf``."""
        return self in (EventState.TRUE_POSITIVE, EventState.FALSE_POSITIVE)

    @classmethod
    def of_result(cls, value, error) -> EventState:
        """The state a told result puts its event in: failed, true or false positive (HF = 0)."""
        if error is not None:
            return cls.FAILED
        return cls.TRUE_POSITIVE if value > 0 else cls.FALSE_POSITIVE
