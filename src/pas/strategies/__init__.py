"""Screening strategies behind one interface: PAS (copula) and AS (GPR)."""

from .base import Pairs, Prediction, Strategy
from .as_ import AS
from .pas import PAS

__all__ = ["Strategy", "Pairs", "Prediction", "PAS", "AS"]
