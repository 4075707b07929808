"""Screening strategies behind one interface: PAS (copula) and AS (GPR)."""

from .base import Pairs, Prediction, Strategy
from .as_ import AS
from .band import ModelBand
from .estimators import ConditionalLikelihood, SelectedSample
from .pas import PAS

__all__ = ["Strategy", "Pairs", "Prediction", "PAS", "AS", "ConditionalLikelihood",
           "SelectedSample", "ModelBand"]
