"""Force equilibrium of a split-Hopkinson-bar specimen: the ratio R(t) of the face-force difference to the mean
face force, its pass/review/fail bands and the time from which the specimen is in equilibrium.

    R(t) = 2 |F1(t) - F2(t)| / |F1(t) + F2(t)|,   F1 = E_I A_I (eps_I + eps_R),   F2 = E_T A_T eps_T

F1 is the force on the specimen's front face (incident bar), F2 on its back face (transmitted bar), both from
the bar strains at the faces (tension positive). Ravichandran and Subhash (1994) introduced this ratio (their
R(t) = Delta P / P_avg) and took a specimen to be in equilibrium while R <= 5 %, the limit used widely since
(e.g. Chen and Song 2011). Defaults here: **pass** R <= 5 % (that limit), **review** 5 % < R <= 10 %
(twice it: a band in which data may serve with the imbalance stated; a convention of this package, not a
published limit), **fail** R > 10 %.

References: G. Ravichandran and G. Subhash, "Critical appraisal of limiting strain rates for compression testing
of ceramics in a split Hopkinson pressure bar", J. Am. Ceram. Soc. 77(1), 263-267 (1994); W. Chen and B. Song,
*Split Hopkinson (Kolsky) Bar: Design, Testing and Applications*, Springer (2011).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from .._validate import positive

__all__ = ["EquilibriumCheck", "PASS_LIMIT", "REVIEW_LIMIT", "check_equilibrium"]

#: Largest R(t) of the pass band (Ravichandran and Subhash 1994).
PASS_LIMIT = 0.05
#: Largest R(t) of the review band (twice the pass limit; this package's convention).
REVIEW_LIMIT = 0.10
#: R(t) is undefined (NaN) where the mean face force is below this fraction of its peak: noise over noise.
UNLOADED = 0.01
#: Band codes of :attr:`EquilibriumCheck.band`.
BANDS = {-1: "undefined", 0: "pass", 1: "review", 2: "fail"}


@dataclass(frozen=True)
class EquilibriumCheck:
    """R(t) of a shot and what it says (module docstring).

    ``time`` (s), ``front_force`` F1 and ``back_force`` F2 (N, tension positive), ``ratio`` R(t) (NaN where
    the mean face force is below 1 % of its peak), the band limits, ``loading_end`` (s: the peak of the mean
    face force, after which the specimen unloads), ``equilibrium_time`` (s: from it until ``loading_end`` R
    stays within the pass band; ``None`` if R exceeds it at the loading end) and ``review_time`` (the same for
    the review band).
    """

    time: np.ndarray
    front_force: np.ndarray
    back_force: np.ndarray
    ratio: np.ndarray
    pass_limit: float
    review_limit: float
    loading_end: float
    equilibrium_time: Optional[float]
    review_time: Optional[float]

    @property
    def band(self) -> np.ndarray:
        """Per sample: 0 pass, 1 review, 2 fail, -1 undefined (``BANDS``)."""
        r = self.ratio
        band = np.where(r <= self.pass_limit, 0, np.where(r <= self.review_limit, 1, 2))
        return np.where(np.isnan(r), -1, band).astype(np.int8)


def check_equilibrium(time: np.ndarray, front_force: np.ndarray, back_force: np.ndarray,
                      bands: tuple[float, float] = (PASS_LIMIT, REVIEW_LIMIT)) -> EquilibriumCheck:
    """R(t) of the face forces F1 (``front_force``) and F2 (``back_force``), N, on the time axis ``time`` (s),
    judged over the loading part of the pulse: from the first sample to the peak of the mean face force.
    ``bands``: the pass and review limits of R (fractions, pass < review)."""
    if len(bands) != 2:
        raise ValueError(f"bands: give the pass and the review limit of R, got {bands!r}")
    pass_limit, review_limit = (positive("bands", b) for b in bands)
    if not pass_limit < review_limit:
        raise ValueError(f"bands: the pass limit must be below the review limit, got {bands!r}")
    total = np.abs(front_force + back_force)
    peak = int(np.argmax(total))
    if total[peak] == 0.0:
        raise ValueError("the face forces are zero everywhere: the windows hold no pulse")
    loaded = total >= UNLOADED * total[peak]
    ratio = np.full(total.shape, np.nan)
    ratio[loaded] = 2.0 * np.abs(front_force - back_force)[loaded] / total[loaded]
    return EquilibriumCheck(time, front_force, back_force, ratio, pass_limit, review_limit, float(time[peak]),
                            _held_from(time, ratio, pass_limit, peak), _held_from(time, ratio, review_limit, peak))


def _held_from(time: np.ndarray, ratio: np.ndarray, limit: float, end: int) -> Optional[float]:
    """The earliest time from which ``ratio <= limit`` holds at every sample up to index ``end`` (None if not
    even at ``end``)."""
    outside = np.flatnonzero(~(ratio[:end + 1] <= limit))       # NaN counts as outside
    first = int(outside[-1]) + 1 if outside.size else 0
    return float(time[first]) if first <= end else None
