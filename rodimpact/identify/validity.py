"""Where the 1D model of identification holds (docs/identification.md, "Where the 1D model holds").

* **Pulse length.** A pulse of spatial length c w (w its width at half maximum) carries wavelengths of about
  that size or longer. The first Pochhammer-Chree mode (:func:`rodimpact.signals.dispersion.
  phase_velocity_at_wavelength`, Bancroft 1941) runs 1.5 % below the bar speed c0 at a wavelength of 4
  diameters (Poisson ratio 0.3; 0.7 % at 0.2) and 8 % below at 2 diameters: below :data:`PULSE_DIAMETERS`
  diameters the echoes are distorted enough that the 1D depths and beta are no longer trustworthy.
* **Near field.** Within a few diameters of the head the wave is not yet plane (Saint-Venant's principle: the
  load's distribution over the head face decays over about a diameter or two); reflectors shallower than
  :data:`NEAR_FIELD_DIAMETERS` diameters are flagged (a rule of practice, not derived here).
* **Toe.** Shaft resistance and damping weaken the toe echo with depth; low-strain practice quotes a length to
  diameter ratio of about 30 as where the toe is still usually seen in soil (:data:`TOE_SLENDERNESS`: as quoted
  for ASTM D5882 by practitioners; the standard's own text was not available to this work, so the number is
  unverified here). Lossless records (no soil) have no such limit.
"""

from __future__ import annotations

from typing import Optional, Sequence

__all__ = ["IdentificationWarning", "NEAR_FIELD_DIAMETERS", "PULSE_DIAMETERS", "TOE_SLENDERNESS",
           "one_dimensional_warnings", "resolution_warnings"]

class IdentificationWarning(UserWarning):
    """An identification ran outside the conditions its method assumes (docs/identification.md)."""


PULSE_DIAMETERS = 4.0
NEAR_FIELD_DIAMETERS = 4.0
TOE_SLENDERNESS = 30.0


def resolution_warnings(diameter: Optional[float], element_length: float, depths: Sequence[float]) -> list[str]:
    """Messages for a peeled profile (module docstring): elements (c T / 2 long) shorter than
    :data:`PULSE_DIAMETERS` diameters resolve features the 1D model does not describe (the record's shortest
    wavelengths are about two elements), and reflectors within :data:`NEAR_FIELD_DIAMETERS` diameters of the
    head. ``diameter`` None: no check."""
    out = one_dimensional_warnings(diameter, float("inf"), depths, None)
    if diameter is not None and element_length < PULSE_DIAMETERS * float(diameter):
        out.insert(0, f"the elements are {element_length:.4g} m long (c T / 2), shorter than {PULSE_DIAMETERS:g} "
                      f"diameters ({PULSE_DIAMETERS * float(diameter):.4g} m): the profile resolves features the 1D "
                      f"model does not describe; low-pass the record and resample it coarser")
    return out


def one_dimensional_warnings(diameter: Optional[float], pulse_length: float, depths: Sequence[float],
                             length: Optional[float]) -> list[str]:
    """Messages for every 1D limit (module docstring) that a record breaks: ``diameter`` (m; None: no check),
    ``pulse_length`` = c w (m), the reflector ``depths`` (m) and the rod's ``length`` (m or None)."""
    if diameter is None:
        return []
    d = float(diameter)
    if not d > 0:
        raise ValueError(f"diameter: must be > 0 m, got {diameter!r}")
    out = []
    if pulse_length < PULSE_DIAMETERS * d:
        out.append(f"the pulse is {pulse_length:.4g} m long (c x width at half maximum), shorter than "
                   f"{PULSE_DIAMETERS:g} diameters ({PULSE_DIAMETERS * d:.4g} m): dispersion distorts its echoes "
                   f"and the 1D depths and beta are not reliable; use a softer hammer tip (a longer pulse)")
    shallow = [x for x in depths if x < NEAR_FIELD_DIAMETERS * d]
    if shallow:
        out.append(f"reflector(s) at {', '.join(f'{x:.3g}' for x in shallow)} m lie within "
                   f"{NEAR_FIELD_DIAMETERS:g} diameters ({NEAR_FIELD_DIAMETERS * d:.3g} m) of the head, where "
                   f"the wave is not yet plane: not resolved by the 1D model")
    if length is not None and length / d > TOE_SLENDERNESS:
        out.append(f"length / diameter = {length / d:.3g} exceeds {TOE_SLENDERNESS:g}: in soil the toe echo may "
                   f"be too weak to see (a limit quoted in practice, unverified here)")
    return out
