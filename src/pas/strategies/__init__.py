"""Screening strategies behind one interface: PAS (copula) and AS (GPR)."""

from .as_ import AS
from .band import ModelBand
from .base import Pairs, Prediction, Strategy
from .estimators import ConditionalLikelihood, SelectedSample
from .pas import PAS

__all__ = ["Strategy", "Pairs", "Prediction", "PAS", "AS", "ConditionalLikelihood",
           "SelectedSample", "ModelBand"]
