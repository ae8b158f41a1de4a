"""Strain gauges and Wheatstone bridges: voltage -> strain -> normal force (thesis section 5.1-5.2).

Sign convention
---------------
Strain and normal force are positive in **tension** (architecture convention; an impact
gives negative values). A bridge is described by the relative resistance change of its four
arms per unit of the measured strain,

    Delta R_i / R = GF * k_i * eps,          i = 1..4,

and its normalised output is taken as

    V_r = V_out / (V_exc * gain) = R1 / (R1 + R2) - R4 / (R3 + R4),     R_i = R (1 + GF k_i eps).

Arms 1 and 3 therefore raise ``V_r`` when they elongate and arms 2 and 4 lower it: with the
active gauge of a quarter bridge in arm 1, a tensile strain gives a positive output.
Measuring systems that show compression as a positive voltage are handled with
``polarity=-1`` in :class:`GaugedBar` (or a negative ``gain``).

The exact relation between ``V_r`` and ``x = GF * eps`` is quadratic,

    (V_r s12 s34 - (k1 k3 - k2 k4)) x^2 + (2 V_r (s12 + s34) - (k1 - k2 + k3 - k4)) x + 4 V_r = 0,

with ``s12 = k1 + k2`` and ``s34 = k3 + k4``; :meth:`Bridge.strain` takes the root that tends
to the linear result ``x = 4 V_r / (k1 - k2 + k3 - k4)`` as ``V_r -> 0``. For the quarter
bridge it reduces to the familiar nonlinearity correction

    eps = 4 V_r / (GF (1 - 2 V_r)).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validate import finite, positive
from .dispersion import PochhammerChree

__all__ = [
    "Bridge",
    "GaugedBar",
    "bending_ratio",
    "bending_stress",
    "bridge_to_strain",
    "gauge_length_average",
    "opposite_gauge_average",
    "strain_to_force",
]

BRIDGE_NAMES = ("quarter", "half-axial", "half-bending", "half-poisson", "full-bending", "full-poisson")


#: SI units of the quantities checked by :func:`_positive` (a string with a unit, "210 GPa", is converted)
_UNITS = {"youngs_modulus": "Pa", "density": "kg/m^3", "area": "m^2", "excitation_voltage": "V", "gauge_length": "m",
          "wave_speed": "m/s"}


def _positive(value: float, what: str) -> float:
    """``value`` as a float after checking it is a real number (not a string, a bool or None: a gauge factor
    ``"5"`` is refused, not read as 5), finite and > 0; quantities with a unit in :data:`_UNITS` also accept a
    unit string or pint Quantity (``"210 GPa"``)."""
    return positive(what, value, _UNITS.get(what, ""))


def _as_float_array(values: Any, what: str) -> np.ndarray:
    """``values`` as a float array after checking that it holds real numbers (strings, bools and objects such as
    None are refused, not coerced) and only finite ones."""
    try:
        array = np.asarray(values)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{what} must be numeric, got {type(values).__name__}") from exc
    if array.dtype.kind not in "iuf":
        text = repr(values)
        raise TypeError(f"{what} must be real numbers, got {type(values).__name__} "
                        f"{text if len(text) <= 60 else text[:57] + '...'} (dtype {array.dtype})")
    array = array.astype(float)
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{what} contains non-finite values")
    return array


def _real(value: Any) -> bool:
    """A real number that is not a bool (Python or numpy)."""
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))


@dataclass(frozen=True)
class Bridge:
    """A Wheatstone bridge given by the strain factors ``k1..k4`` of its arms (module docstring).

    Use the named constructors, e.g. ``Bridge.quarter()`` or ``Bridge.named("half-axial")``.
    ``k_i = 0`` marks a completion resistor (or an unstrained dummy gauge).
    """

    arms: tuple[float, float, float, float]
    name: str = ""

    def __post_init__(self) -> None:
        try:
            items = [] if isinstance(self.arms, (str, bytes)) else list(self.arms)
        except TypeError:
            items = []
        if not items or not all(_real(k) for k in items):      # "1" or True are refused, not coerced
            raise TypeError(f"arms: must be four strain factors (numbers), got {self.arms!r}")
        arms = tuple(float(k) for k in items)
        if len(arms) != 4 or not all(np.isfinite(arms)):
            raise ValueError(f"arms: must be four finite strain factors, got {self.arms!r}")
        if arms[0] - arms[1] + arms[2] - arms[3] == 0.0:
            raise ValueError(f"bridge arms {arms} have zero sensitivity (k1 - k2 + k3 - k4 = 0)")
        object.__setattr__(self, "arms", arms)

    # -- named configurations ----------------------------------------------------------
    @classmethod
    def quarter(cls) -> Bridge:
        """One active gauge (arm 1), three completion resistors: ``eps = 4 V_r / (GF (1 - 2 V_r))``."""
        return cls((1.0, 0.0, 0.0, 0.0), "quarter")

    @classmethod
    def half_axial(cls) -> Bridge:
        """Two axial gauges in opposite arms (1 and 3), e.g. diametrically opposite gauges.

        Bending cancels, the axial output doubles: ``eps = 2 V_r / (GF (1 - V_r))``.
        """
        return cls((1.0, 0.0, 1.0, 0.0), "half-axial")

    @classmethod
    def half_bending(cls) -> Bridge:
        """Two opposite-face gauges in adjacent arms (1, 2): measures the bending strain
        ``eps_b`` of the arm-1 face, linear: ``eps_b = 2 V_r / GF``; axial strain cancels."""
        return cls((1.0, -1.0, 0.0, 0.0), "half-bending")

    @classmethod
    def half_poisson(cls, poisson_ratio: float) -> Bridge:
        """Axial gauge (arm 1) and transverse Poisson gauge (arm 2) on a bar in uniaxial stress."""
        nu = _poisson(poisson_ratio)
        return cls((1.0, -nu, 0.0, 0.0), "half-poisson")

    @classmethod
    def full_bending(cls) -> Bridge:
        """Four gauges, top in arms 1 and 3, bottom in 2 and 4: ``eps_b = V_r / GF`` (linear)."""
        return cls((1.0, -1.0, 1.0, -1.0), "full-bending")

    @classmethod
    def full_poisson(cls, poisson_ratio: float) -> Bridge:
        """Two axial gauges (arms 1, 3) and two transverse Poisson gauges (arms 2, 4)."""
        nu = _poisson(poisson_ratio)
        return cls((1.0, -nu, 1.0, -nu), "full-poisson")

    @classmethod
    def named(cls, name: str, poisson_ratio: float | None = None) -> Bridge:
        """One of ``"quarter"``, ``"half-axial"``, ``"half-bending"``, ``"half-poisson"``,
        ``"full-bending"``, ``"full-poisson"`` (the ``*-poisson`` ones need ``poisson_ratio``)."""
        key = str(name).strip().lower().replace("_", "-")
        if key not in BRIDGE_NAMES:
            raise ValueError(f"unknown bridge {name!r}; valid: {', '.join(BRIDGE_NAMES)}")
        if key.endswith("poisson"):
            if poisson_ratio is None:
                raise ValueError(f"bridge {name!r} needs poisson_ratio")
            return cls.half_poisson(poisson_ratio) if key.startswith("half") else cls.full_poisson(poisson_ratio)
        return {
            "quarter": cls.quarter,
            "half-axial": cls.half_axial,
            "half-bending": cls.half_bending,
            "full-bending": cls.full_bending,
        }[key]()

    # -- physics ---------------------------------------------------------------------
    @property
    def sensitivity(self) -> float:
        """Small-signal ``dV_r / d(GF eps)`` at zero strain, ``(k1 - k2 + k3 - k4) / 4``."""
        k1, k2, k3, k4 = self.arms
        return (k1 - k2 + k3 - k4) / 4.0

    def output_ratio(self, strain: Any, gauge_factor: float) -> np.ndarray:
        """Exact normalised output ``V_r = V_out / (V_exc gain)`` for a strain (forward model)."""
        gf = _positive(gauge_factor, "gauge_factor")
        x = gf * _as_float_array(strain, "strain")
        k1, k2, k3, k4 = self.arms
        r1, r2, r3, r4 = (1 + k1 * x), (1 + k2 * x), (1 + k3 * x), (1 + k4 * x)
        return r1 / (r1 + r2) - r4 / (r3 + r4)

    def strain(self, output_ratio: Any, gauge_factor: float, linearize: bool = False) -> np.ndarray:
        """Strain from the normalised bridge output ``V_r`` (exact inverse of :meth:`output_ratio`).

        ``linearize=True`` drops the bridge nonlinearity: ``eps = V_r / (GF * sensitivity)``.
        """
        gf = _positive(gauge_factor, "gauge_factor")
        vr = _as_float_array(output_ratio, "bridge output ratio")
        k1, k2, k3, k4 = self.arms
        if linearize:
            return vr / (gf * self.sensitivity)
        s12, s34 = k1 + k2, k3 + k4
        a = vr * s12 * s34 - (k1 * k3 - k2 * k4)
        b = 2.0 * vr * (s12 + s34) - (k1 - k2 + k3 - k4)
        c = 4.0 * vr
        disc = b * b - 4.0 * a * c
        if np.any(disc < 0):
            worst = float(np.ravel(vr)[np.argmin(np.ravel(disc))])
            raise ValueError(
                f"bridge output ratio V_r = {worst!r} cannot be produced by a {self.name or self.arms} "
                "bridge; check excitation voltage, gain and bridge type"
            )
        sign_b = np.where(b >= 0, 1.0, -1.0)
        denom = -b - sign_b * np.sqrt(disc)
        with np.errstate(divide="ignore", invalid="ignore"):
            x = np.where(c == 0, 0.0, 2.0 * c / denom)
        resistances = 1.0 + np.multiply.outer(np.asarray(self.arms), x)
        if not np.all(np.isfinite(x)) or np.any(resistances <= 0):
            worst = float(np.ravel(vr)[np.argmax(np.ravel(np.abs(vr)))])
            raise ValueError(
                f"bridge output ratio V_r = {worst!r} cannot be produced by a {self.name or self.arms} "
                "bridge with positive gauge resistances; check excitation voltage, gain and bridge type"
            )
        return x / gf


def _poisson(value: float) -> float:
    nu = finite("poisson_ratio", value)
    if not -1.0 < nu < 0.5:
        raise ValueError(f"poisson_ratio must lie in (-1, 0.5), got {value!r}")
    return nu


def _bridge(bridge: Bridge | str, poisson_ratio: float | None) -> Bridge:
    if isinstance(bridge, Bridge):
        return bridge
    if isinstance(bridge, str):
        return Bridge.named(bridge, poisson_ratio)
    raise TypeError(f"bridge must be a Bridge or one of {BRIDGE_NAMES}, got {bridge!r}")


def bridge_to_strain(
    voltage: Any,
    gauge_factor: float,
    excitation_voltage: float,
    gain: float = 1.0,
    bridge: Bridge | str = "quarter",
    poisson_ratio: float | None = None,
    linearize: bool = False,
) -> np.ndarray:
    """Strain (tension positive) from the amplified bridge output voltage.

    ``V_r = voltage / (excitation_voltage * gain)`` is inverted exactly for the given bridge
    (module docstring); for a quarter bridge ``eps = 4 V_r / (GF (1 - 2 V_r))``. A negative
    ``gain`` describes an inverting amplifier (compression shown as positive voltage).
    """
    exc = _positive(excitation_voltage, "excitation_voltage")
    g = finite("gain", gain)
    if g == 0:
        raise ValueError(f"gain must be finite and non-zero, got {gain!r}")
    vr = _as_float_array(voltage, "voltage") / (exc * g)
    return _bridge(bridge, poisson_ratio).strain(vr, gauge_factor, linearize=linearize)


def strain_to_force(strain: Any, youngs_modulus: float, area: float) -> np.ndarray:
    """Normal force ``N = E A eps`` (N, tension positive) from axial strain."""
    return _positive(youngs_modulus, "youngs_modulus") * _positive(area, "area") * _as_float_array(strain, "strain")


def opposite_gauge_average(first: Any, second: Any) -> np.ndarray:
    """Bending-compensated value from two diametrically opposite gauges, thesis eq. (5.1).

    ``N_k = (N_k,0deg + N_k,180deg) / 2``; works equally for strains, stresses or forces.
    """
    a = _as_float_array(first, "first gauge signal")
    b = _as_float_array(second, "second gauge signal")
    if a.shape != b.shape:
        raise ValueError(f"gauge signals differ in shape: {a.shape} vs {b.shape}")
    return 0.5 * (a + b)


def bending_stress(force_first: Any, force_second: Any, area: float) -> np.ndarray:
    """Maximum bending stress in the plane of two opposite gauges, thesis eq. (5.2), in Pa.

    ``sigma_bend = (N_0deg - N_180deg) / (2 A)``, where ``N_x`` are the normal forces
    ``E A eps_x`` evaluated from each gauge alone. Positive when the first gauge's face is
    the more stretched one.
    """
    a = _as_float_array(force_first, "first gauge force")
    b = _as_float_array(force_second, "second gauge force")
    if a.shape != b.shape:
        raise ValueError(f"gauge forces differ in shape: {a.shape} vs {b.shape}")
    return (a - b) / (2.0 * _positive(area, "area"))


def bending_ratio(
    force_0: Any,
    force_180: Any,
    force_90: Any | None = None,
    force_270: Any | None = None,
) -> float:
    """Ratio of maximum bending stress to maximum normal stress, thesis eq. (5.3), as a fraction.

    Definition used here (the thesis multiplies by 100 and reports per cent):

        e = max_t |sigma_bend(t)| / max_t |sigma(t)|,

    with ``sigma = N / A`` the bending-compensated normal stress (mean of the gauges, eq.
    5.1) and ``sigma_bend`` from eq. (5.2). The two maxima are taken independently over the
    samples passed in, so pass the analysis window (e.g. the incident pulse), not a record
    dominated by noise. The area cancels, so forces, stresses or strains may be passed.

    With only the 0/180 deg pair, ``sigma_bend`` is the bending stress in that plane. If the
    90/270 deg pair is also given, the resultant bending stress
    ``sqrt(sigma_b,0-180^2 + sigma_b,90-270^2)`` is used and ``sigma`` is the mean of all four.
    """
    a = _as_float_array(force_0, "force_0")
    b = _as_float_array(force_180, "force_180")
    if a.shape != b.shape or a.ndim != 1 or a.size == 0:
        raise ValueError("force_0 and force_180 must be non-empty 1-D arrays of equal length")
    bend = 0.5 * (a - b)
    normal = 0.5 * (a + b)
    if (force_90 is None) != (force_270 is None):
        raise ValueError("give both force_90 and force_270, or neither")
    if force_90 is not None:
        c = _as_float_array(force_90, "force_90")
        d = _as_float_array(force_270, "force_270")
        if c.shape != a.shape or d.shape != a.shape:
            raise ValueError("all four gauge signals must have the same length")
        bend = np.hypot(bend, 0.5 * (c - d))
        normal = 0.25 * (a + b + c + d)
    peak_normal = float(np.max(np.abs(normal)))
    if peak_normal == 0.0:
        raise ValueError("the normal (compensated) signal is zero everywhere; bending ratio undefined")
    return float(np.max(np.abs(bend))) / peak_normal


@dataclass(frozen=True)
class GaugedBar:
    """A bar with a gauge station: material, cross-section and the measuring bridge.

    Attributes are SI: ``youngs_modulus`` (Pa), ``density`` (kg/m^3), ``area`` (m^2),
    ``excitation_voltage`` (V). ``polarity = -1`` for acquisition systems that record
    compression as positive voltage. Converts recorded voltages to strain (tension positive)
    and to the normal force ``N = E A eps``.
    """

    youngs_modulus: float
    density: float
    area: float
    gauge_factor: float
    excitation_voltage: float
    gain: float = 1.0
    bridge: Bridge | str = "quarter"
    polarity: int = 1
    poisson_ratio: float | None = None
    name: str = ""

    def __post_init__(self) -> None:
        for what in ("youngs_modulus", "density", "area", "gauge_factor", "excitation_voltage"):
            object.__setattr__(self, what, _positive(getattr(self, what), what))
        if not _real(self.polarity):
            raise TypeError(f"polarity must be +1 or -1 (an integer), got {type(self.polarity).__name__} "
                            f"{self.polarity!r}")
        if self.polarity not in (1, -1):
            raise ValueError(f"polarity must be +1 or -1, got {self.polarity!r}")
        if self.poisson_ratio is not None:
            object.__setattr__(self, "poisson_ratio", _poisson(self.poisson_ratio))
        object.__setattr__(self, "bridge", _bridge(self.bridge, self.poisson_ratio))
        gain = finite("gain", self.gain)
        if gain == 0:
            raise ValueError(f"gain must be finite and non-zero, got {self.gain!r}")
        object.__setattr__(self, "gain", gain)

    @property
    def wave_speed(self) -> float:
        """Bar wave speed ``c0 = sqrt(E / rho)`` (m/s)."""
        return float(np.sqrt(self.youngs_modulus / self.density))

    @property
    def impedance(self) -> float:
        """Mechanical impedance ``Z = rho c0 A = A sqrt(E rho)`` (N s/m)."""
        return float(self.area * np.sqrt(self.youngs_modulus * self.density))

    def strain(self, voltage: Any, linearize: bool = False) -> np.ndarray:
        """Axial strain (tension positive) from recorded voltage."""
        return bridge_to_strain(
            self.polarity * _as_float_array(voltage, "voltage"),
            self.gauge_factor,
            self.excitation_voltage,
            self.gain,
            self.bridge,
            linearize=linearize,
        )

    def force(self, voltage: Any, linearize: bool = False) -> np.ndarray:
        """Normal force ``N = E A eps`` (N, tension positive) from recorded voltage."""
        return strain_to_force(self.strain(voltage, linearize), self.youngs_modulus, self.area)


def gauge_length_average(
    time: Any,
    values: Any,
    gauge_length: float,
    wave_speed: float | None = None,
    model: Any = None,
) -> np.ndarray:
    """What a gauge of finite length reads from a wave travelling along the bar.

    A gauge averages the strain over its length ``L_g``. For a wave component of frequency
    ``f`` and wavelength ``Lambda = c / f`` this multiplies its amplitude by
    ``sinc(L_g / Lambda) = sin(pi L_g / Lambda) / (pi L_g / Lambda)`` without a phase shift
    (gauge centre as reference). ``c`` is ``wave_speed`` (non-dispersive) or the phase
    velocity of a :class:`~rodimpact.signals.dispersion.PochhammerChree` ``model``. Applied
    with an FFT on the uniform time axis (zero-padded to twice the length).
    """
    t = _as_float_array(time, "time")
    x = _as_float_array(values, "values")
    if t.ndim != 1 or x.shape != t.shape or t.size < 2:
        raise ValueError("time and values must be 1-D arrays of equal length")
    steps = np.diff(t)
    dt = float(np.median(steps))
    if dt <= 0 or np.any(np.abs(steps - dt) > 1e-6 * dt):
        raise ValueError("gauge_length_average needs a uniform, increasing time axis")
    length = _positive(gauge_length, "gauge_length")
    n_total = 2 * x.size
    f = np.fft.rfftfreq(n_total, dt)
    if model is not None:
        if not isinstance(model, PochhammerChree):
            raise TypeError(f"model: must be a PochhammerChree (or None with wave_speed), got {type(model).__name__}")
        speed = model.phase_velocity(f)
    elif wave_speed is not None:
        speed = np.full(f.shape, _positive(wave_speed, "wave_speed"))
    else:
        raise ValueError("give wave_speed or a dispersion model")
    spectrum = np.fft.rfft(x, n_total) * np.sinc(length * f / speed)
    return np.fft.irfft(spectrum, n_total)[: x.size]
