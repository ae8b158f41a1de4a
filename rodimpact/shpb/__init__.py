"""Split-Hopkinson (Kolsky) bar: the forward model with specimens and pulse shapers between the bars."""

from .kolsky import Gauge, KolskyBar, KolskyPrediction, incident_for_constant_rate

__all__ = ["Gauge", "KolskyBar", "KolskyPrediction", "incident_for_constant_rate"]
