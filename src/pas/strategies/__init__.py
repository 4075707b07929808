"""Screening strategies behind one interface: PAS (copula) and AS (GPR)."""

from .base import Pairs, Prediction, Strategy
from .pas import PAS

__all__ = ["Strategy", "Pairs", "Prediction", "PAS"]
