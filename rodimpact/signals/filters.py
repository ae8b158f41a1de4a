"""The measuring chain of thesis section 5.1 as filters: analog Bessel anti-aliasing low-pass,
sampling, digital IIR Bessel low-pass (all designed with :mod:`scipy.signal`).

Thesis Tab. 5.1: analog Bessel, 5th order, corner 100 kHz -> 16-bit ADC at 1 MHz -> digital
IIR Bessel, 4th order, corner 40 kHz (signal conditioner Sirius HS).

Bessel normalisation
--------------------
scipy offers three normalisations of the Bessel prototype: ``'phase'`` (phase response
reaches half its final value at the critical frequency, high-frequency asymptote equal to
a Butterworth's), ``'delay'`` (group delay ``1/Wn`` at DC) and ``'mag'`` (gain
``-3.01 dB = 1/sqrt(2)`` at the critical frequency). The thesis names a *corner frequency*;
in signal-conditioner data sheets that is the -3 dB point, so the default here is
``norm='mag'``: the gain is exactly ``1/sqrt(2)`` at 100 kHz (analog) and 40 kHz (digital).
The digital filter is designed by scipy's bilinear transform with the critical frequency
pre-warped, so the -3 dB point of the *digital* filter is exactly at its corner.

How the analog stage is simulated
---------------------------------
A sampled input cannot be fed to an analog filter without saying what it does between the
samples. Here the input is taken as piecewise linear between samples (``interpolation=
'linear'``) or piecewise constant (``'previous'``, e.g. for lattice results whose node
values are constant during a step). The signal is put on a uniform grid of at least
``analog_rate`` (default 20 MHz = 200 x the corner; an input that is already uniform and at
least that fast is used as it is), and the analog filter is applied *exactly* for a
piecewise-linear input on that grid: the filter is split into its poles (partial fractions,
the Bessel prototype has no zeros) and every first-order mode is discretised exactly with a
first-order hold, which is the input model of ``scipy.signal.lsim``. This parallel form stays
accurate however fine the grid is compared with the corner (a cascade of second-order
sections obtained from ``cont2discrete(..., method='foh')`` loses all accuracy there, as its
poles crowd at z = 1). The ADC then samples the (smooth) analog output at
``t0 + k / sampling_rate`` by linear interpolation, and the digital filter runs on those
samples.

Orders from 1 to 20 are accepted (:data:`MAX_ORDER`): scipy's Bessel design fails from about
order 43 on, and above 20 the partial fractions of the analog stage lose digits.

Causality and start-up
----------------------
Filtering is causal by default (``sosfilt``), as in the real chain: the output is delayed
(see :meth:`MeasuringChain.group_delay`). The filter states start in steady state for the
first sample value (``sosfilt_zi``), i.e. the signal is assumed to have been constant
before the record started. ``zero_phase=True`` runs every stage forward and backward
(``sosfiltfilt``): no delay, but the magnitude response is squared (-6 dB at the corners);
it is *not* the real chain and is meant for shape comparisons only.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import signal

from .._validate import finite_array, fits_in_memory, positive
from .recording import Recording

__all__ = [
    "MAX_ORDER",
    "MeasuringChain",
    "bessel_analog",
    "bessel_digital",
    "simulate_analog_filter",
]

_NORMS = ("mag", "phase", "delay")

#: Highest filter order accepted (module docstring).
MAX_ORDER = 20

# Bytes per sample of the analog simulation grid: grid, input, output, and the complex output of one mode.
_BYTES_PER_GRID_SAMPLE = 48


def _check_order(order: Any, what: str) -> int:
    if isinstance(order, bool) or not isinstance(order, (int, np.integer)):
        raise TypeError(f"{what}: must be an integer from 1 to {MAX_ORDER}, got {type(order).__name__} {order!r}")
    if not 1 <= order <= MAX_ORDER:
        raise ValueError(f"{what}: must be an integer from 1 to {MAX_ORDER}, got {order!r} (scipy's Bessel design "
                         f"and the simulation of the analog stage lose accuracy at high orders; measuring "
                         f"chains use orders up to about 10)")
    return int(order)


def _check_positive(value: Any, what: str, unit: str = "Hz") -> float:
    return positive(what, value, unit)


def _check_norm(norm: Any) -> str:
    if norm not in _NORMS:
        raise ValueError(f"norm: must be one of {_NORMS}, got {norm!r}")
    return norm


def _check_flag(value: Any, what: str) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{what}: must be True or False, got {value!r}")
    return bool(value)


def _check_interpolation(interpolation: Any) -> str:
    if interpolation not in ("linear", "previous"):
        raise ValueError(f"interpolation: must be 'linear' or 'previous', got {interpolation!r}")
    return interpolation


def _frequencies(frequency: Any) -> np.ndarray:
    try:
        f = np.atleast_1d(np.asarray(frequency, dtype=float))
    except (TypeError, ValueError):
        raise TypeError(f"frequency: must be a number or an array of numbers in Hz, got {frequency!r}") from None
    if not np.all(np.isfinite(f)):
        raise ValueError(f"frequency: must be finite, got {frequency!r}")
    return f


def bessel_analog(order: int, corner: float, norm: str = "mag") -> tuple[np.ndarray, np.ndarray, float]:
    """Analog Bessel low-pass as zeros, poles (rad/s) and gain; ``corner`` in Hz; ``order`` 1 to :data:`MAX_ORDER`."""
    order = _check_order(order, "order")
    corner = _check_positive(corner, "corner")
    # the zpk gain is (2 pi corner)^order (times a constant of order one): it must be a normal float
    low, high = (np.finfo(float).tiny * 1e3) ** (1.0 / order), (np.finfo(float).max * 1e-3) ** (1.0 / order)
    if not low <= 2 * np.pi * corner <= high:
        raise ValueError(f"corner: must lie between {low / (2 * np.pi):.3g} Hz and {high / (2 * np.pi):.3g} Hz for "
                         f"order {order} (the analog gain (2 pi corner)^order must be a finite, normal float), "
                         f"got {corner!r} Hz")
    z, p, k = signal.bessel(order, 2 * np.pi * corner, btype="low", analog=True, output="zpk", norm=_check_norm(norm))
    return z, p, float(k)


def bessel_digital(order: int, corner: float, sampling_rate: float, norm: str = "mag") -> np.ndarray:
    """Digital IIR Bessel low-pass as second-order sections (bilinear, pre-warped at ``corner``)."""
    order = _check_order(order, "order")
    corner = _check_positive(corner, "corner")
    fs = _check_positive(sampling_rate, "sampling_rate")
    if corner >= fs / 2:
        raise ValueError(f"corner: {corner} Hz must be below the Nyquist frequency sampling_rate / 2 = {fs / 2} Hz")
    return signal.bessel(order, corner, btype="low", analog=False, output="sos", norm=_check_norm(norm), fs=fs)


def _phi2(a: np.ndarray) -> np.ndarray:
    """``(exp(a) - 1 - a) / a^2`` for complex ``a``, by its series where the formula would cancel."""
    a = np.asarray(a, dtype=complex)
    out = np.empty_like(a)
    small = np.abs(a) < 0.1
    big = a[~small]
    out[~small] = (np.expm1(big) - big) / (big * big)
    s = a[small]
    term = np.full_like(s, 0.5)
    total = term.copy()
    for n in range(3, 20):                 # |a|^17 / 19! < 1e-33 for |a| < 0.1
        term = term * s / n
        total = total + term
    out[small] = total
    return out


@dataclass(frozen=True)
class _FohModes:
    """The analog Bessel low-pass as parallel first-order modes, discretised exactly for piecewise-linear input.

    Mode i obeys ``x_i[k] = lam_i x_i[k-1] + b0_i u[k-1] + b1_i u[k]``; the output is
    ``sum_i weight_i Re(x_i[k]) / dc``. Complex poles come in conjugate pairs, of which one is kept with weight
    2. ``steady_i`` is the state per unit constant input.
    """

    lam: np.ndarray
    b0: np.ndarray
    b1: np.ndarray
    steady: np.ndarray
    weight: np.ndarray
    dc: float
    n_sections: int

    def run(self, u: np.ndarray) -> np.ndarray:
        """Causal response, states in steady state for ``u[0]``."""
        y = np.zeros(u.shape)
        for lam, b0, b1, steady, weight in zip(self.lam, self.b0, self.b1, self.steady, self.weight):
            xi, _ = signal.lfilter([b1, b0], [1.0, -lam], u, zi=[(steady - b1) * u[0]])
            y += weight * xi.real
        return y / self.dc


def _foh_modes(order: int, corner: float, norm: str, dt: float) -> _FohModes:
    """Analog Bessel discretised exactly for piecewise-linear input on a grid of step ``dt`` (module docstring).

    Designed on the prototype with a 1 rad/s corner and the dimensionless step ``h = omega_c dt``. For a mode
    ``x' = p x + r u`` and ``a = p h``: ``lam = exp(a)``, ``b1 = r h phi2(a)``, ``b0 = r h (phi1(a) - phi2(a))``
    with ``phi1 = (exp(a) - 1) / a`` and ``phi2 = (exp(a) - 1 - a) / a^2``.
    """
    z, p, k = signal.bessel(order, 1.0, btype="low", analog=True, output="zpk", norm=norm)
    if z.size:                                  # pragma: no cover - scipy's Bessel low-pass is all-pole
        raise RuntimeError("the analog Bessel prototype has zeros; the modal simulation assumes none")
    residues = np.array([k / np.prod(pi - np.delete(p, i)) for i, pi in enumerate(p)])
    real = np.abs(p.imag) <= 1e-12 * np.abs(p)
    keep = real | (p.imag > 0)
    p, residues, weight = p[keep], residues[keep], np.where(real[keep], 1.0, 2.0)
    h = 2 * np.pi * corner * dt
    a = p * h
    phi1 = np.expm1(a) / a
    phi2 = _phi2(a)
    steady = -residues / p
    # The sum of the modes' DC gains is exactly 1; restore it against round-off of the partial fractions, so
    # that a constant input passes unchanged.
    dc = float(np.sum(weight * steady.real))
    return _FohModes(lam=np.exp(a), b0=residues * h * (phi1 - phi2), b1=residues * h * phi2, steady=steady,
                     weight=weight, dc=dc, n_sections=(order + 1) // 2)


def _padlen(n_sections: int) -> int:
    return 3 * (2 * n_sections + 1)             # scipy.signal.sosfiltfilt's default


def _check_zero_phase_length(n: int, n_sections: int) -> None:
    padlen = _padlen(n_sections)
    if n <= padlen:
        raise ValueError(f"zero_phase: zero-phase filtering needs more than {padlen} samples on the filter's grid, "
                         f"got {n}; use a longer record or zero_phase=False")


def _run_modes(modes: _FohModes, x: np.ndarray, zero_phase: bool) -> np.ndarray:
    if not zero_phase:
        return modes.run(x)
    # forward and backward, as scipy.signal.sosfiltfilt: odd extension, steady-state start on each pass
    _check_zero_phase_length(x.size, modes.n_sections)
    padlen = _padlen(modes.n_sections)
    ext = np.concatenate([2 * x[0] - x[padlen:0:-1], x, 2 * x[-1] - x[-2:-padlen - 2:-1]])
    y = modes.run(ext)
    y = modes.run(y[::-1])[::-1]
    return y[padlen:-padlen]


def _run(sos: np.ndarray, x: np.ndarray, zero_phase: bool) -> np.ndarray:
    if zero_phase:
        _check_zero_phase_length(x.size, len(sos))
        return signal.sosfiltfilt(sos, x)
    y, _ = signal.sosfilt(sos, x, zi=signal.sosfilt_zi(sos) * x[0])
    return y


def _validated_signal(time: Any, values: Any) -> tuple[np.ndarray, np.ndarray]:
    t = finite_array("time", time, min_size=0)
    x = finite_array("values", values, min_size=0)
    if t.shape != x.shape:
        raise ValueError(f"time and values: must be 1-D arrays of equal length, got {t.size} and {x.size} samples")
    if t.size < 2:
        raise ValueError(f"time and values: need at least 2 samples, got {t.size}")
    bad = np.flatnonzero(np.diff(t) <= 0)
    if bad.size:
        i = int(bad[0]) + 1
        raise ValueError(f"time: must be strictly increasing, sample {i} (t = {t[i]!r} s) is not after sample "
                         f"{i - 1} (t = {t[i - 1]!r} s)")
    return t, x


def _on_uniform_grid(t: np.ndarray, x: np.ndarray, min_rate: float, interpolation: str,
                     rate_name: str = "simulation_rate") -> tuple[np.ndarray, np.ndarray]:
    """The signal on a uniform grid at least ``min_rate`` fast (the input itself if it qualifies)."""
    interpolation = _check_interpolation(interpolation)
    steps = np.diff(t)
    step = float(np.median(steps))
    uniform = np.all(np.abs(steps - step) <= 1e-6 * step)
    if uniform and 1.0 / step >= min_rate * (1 - 1e-9):
        return t, x
    intervals = (t[-1] - t[0]) * min_rate * (1 + 1e-12)
    fits_in_memory(rate_name, (intervals + 1) * _BYTES_PER_GRID_SAMPLE,
                   f"simulating the analog filter on a {min_rate:.4g} Hz grid over the {t[-1] - t[0]:.4g} s record "
                   f"({intervals + 1:.3g} samples)",
                   f"lower {rate_name} (at least 10 x the corner; 20 MHz by default) or shorten the record")
    n = int(np.floor(intervals)) + 1
    grid = t[0] + np.arange(n) / min_rate
    if interpolation == "linear":
        return grid, np.interp(grid, t, x)
    index = np.clip(np.searchsorted(t, grid, side="right") - 1, 0, t.size - 1)
    return grid, x[index]


def _simulate_analog(t: np.ndarray, x: np.ndarray, order: int, corner: float, norm: str, rate: float,
                     interpolation: str, zero_phase: bool, rate_name: str) -> tuple[np.ndarray, np.ndarray]:
    grid, u = _on_uniform_grid(t, x, rate, interpolation, rate_name)
    dt = float(np.median(np.diff(grid)))
    return grid, _run_modes(_foh_modes(order, corner, norm, dt), u, zero_phase)


def simulate_analog_filter(
    time: Any,
    values: Any,
    order: int = 5,
    corner: float = 100e3,
    norm: str = "mag",
    simulation_rate: float = 20e6,
    interpolation: str = "linear",
    zero_phase: bool = False,
) -> tuple[np.ndarray, np.ndarray]:
    """Output of an analog Bessel low-pass driven by a sampled signal (module docstring).

    Returns ``(grid, output)`` on the uniform simulation grid (the input's own grid when it
    is uniform and at least ``simulation_rate`` fast).
    """
    t, x = _validated_signal(time, values)
    order = _check_order(order, "order")
    corner = _check_positive(corner, "corner")
    norm = _check_norm(norm)
    rate = _check_positive(simulation_rate, "simulation_rate")
    interpolation = _check_interpolation(interpolation)
    zero_phase = _check_flag(zero_phase, "zero_phase")
    if rate < 10 * corner:
        raise ValueError(f"simulation_rate: {rate} Hz should be at least 10 x the corner frequency {corner} Hz")
    return _simulate_analog(t, x, order, corner, norm, rate, interpolation, zero_phase, "simulation_rate")


@dataclass(frozen=True)
class MeasuringChain:
    """Analog Bessel low-pass -> sampling -> digital IIR Bessel low-pass (thesis Tab. 5.1).

    Frequencies in Hz. Set ``analog_order=None`` or ``digital_order=None`` to leave a stage
    out. ``analog_rate`` is the minimum rate of the grid on which the analog stage is
    simulated. The same object filters measured and simulated signals, so both pass through
    an identical chain.
    """

    analog_order: int | None = 5
    analog_corner: float = 100e3
    digital_order: int | None = 4
    digital_corner: float = 40e3
    sampling_rate: float = 1e6
    analog_rate: float = 20e6
    norm: str = "mag"

    def __post_init__(self) -> None:
        _check_norm(self.norm)
        fs = _check_positive(self.sampling_rate, "sampling_rate")
        if self.analog_order is not None:
            _check_order(self.analog_order, "analog_order")
            corner = _check_positive(self.analog_corner, "analog_corner")
            if _check_positive(self.analog_rate, "analog_rate") < 10 * corner:
                raise ValueError(f"analog_rate: {self.analog_rate} Hz should be at least 10 x analog_corner "
                                 f"{corner} Hz")
        if self.digital_order is not None:
            _check_order(self.digital_order, "digital_order")
            if _check_positive(self.digital_corner, "digital_corner") >= fs / 2:
                raise ValueError(
                    f"digital_corner: {self.digital_corner} Hz must be below the Nyquist frequency "
                    f"sampling_rate / 2 = {fs / 2} Hz"
                )

    # -- designed filters --------------------------------------------------------------
    def analog_zpk(self) -> tuple[np.ndarray, np.ndarray, float]:
        """Zeros, poles (rad/s) and gain of the analog stage."""
        if self.analog_order is None:
            raise ValueError("this chain has no analog stage (analog_order=None)")
        return bessel_analog(self.analog_order, self.analog_corner, self.norm)

    def digital_sos(self) -> np.ndarray:
        """Second-order sections of the digital stage at ``sampling_rate``."""
        if self.digital_order is None:
            raise ValueError("this chain has no digital stage (digital_order=None)")
        return bessel_digital(self.digital_order, self.digital_corner, self.sampling_rate, self.norm)

    def analog_response(self, frequency: Any) -> np.ndarray:
        """Complex response of the designed analog stage at ``frequency`` (Hz), via ``freqs_zpk``."""
        f = _frequencies(frequency)
        if self.analog_order is None:
            return np.ones(f.shape, dtype=complex)
        z, p, k = self.analog_zpk()
        return signal.freqs_zpk(z, p, k, worN=2 * np.pi * f)[1]

    def digital_response(self, frequency: Any) -> np.ndarray:
        """Complex response of the digital stage at ``frequency`` (Hz), via ``sosfreqz``."""
        f = _frequencies(frequency)
        if self.digital_order is None:
            return np.ones(f.shape, dtype=complex)
        return signal.sosfreqz(self.digital_sos(), worN=f, fs=self.sampling_rate)[1]

    def response(self, frequency: Any) -> np.ndarray:
        """Complex response of the whole chain (analog x digital), valid below the Nyquist frequency."""
        return self.analog_response(frequency) * self.digital_response(frequency)

    def group_delay(self, frequency: Any) -> np.ndarray:
        """Group delay ``-d(phase)/d(omega)`` of the chain in s at ``frequency`` (Hz).

        Analog stage: ``sum_poles Re(1 / (j omega - p))`` (exact for an all-pole filter);
        digital stage: ``scipy.signal.group_delay`` of the designed sections.
        """
        f = _frequencies(frequency)
        delay = np.zeros(f.shape)
        if self.analog_order is not None:
            z, p, _ = self.analog_zpk()
            jw = 1j * 2 * np.pi * f[:, None]
            delay += np.sum(np.real(1.0 / (jw - p[None, :])), axis=1)
            if z.size:
                delay -= np.sum(np.real(1.0 / (jw - z[None, :])), axis=1)
        if self.digital_order is not None:
            b, a = signal.sos2tf(self.digital_sos())
            delay += signal.group_delay((b, a), w=f, fs=self.sampling_rate)[1] / self.sampling_rate
        return delay

    # -- filtering -----------------------------------------------------------------------
    def apply(
        self,
        time: Any,
        values: Any,
        zero_phase: bool = False,
        interpolation: str = "linear",
    ) -> tuple[np.ndarray, np.ndarray]:
        """Pass a signal through the chain; returns ``(t_k, y_k)`` at ``t_k = t0 + k / sampling_rate``.

        ``interpolation`` says how the input behaves between its samples (``'linear'`` or
        ``'previous'``); see the module docstring for the analog simulation. The record must span at least one
        sample interval of the chain, ``1 / sampling_rate``.
        """
        t, x = _validated_signal(time, values)
        zero_phase = _check_flag(zero_phase, "zero_phase")
        interpolation = _check_interpolation(interpolation)
        span = t[-1] - t[0]
        intervals = span * self.sampling_rate * (1 + 1e-12)
        if intervals < 1:
            raise ValueError(
                f"time: the signal spans {span:.6g} s, shorter than one sample interval of the chain "
                f"(1 / sampling_rate = {1 / self.sampling_rate:.6g} s)"
            )
        fits_in_memory("sampling_rate", (intervals + 1) * 32,
                       f"sampling the {span:.4g} s record at {self.sampling_rate:.4g} Hz ({intervals + 1:.3g} samples)",
                       "lower sampling_rate or shorten the record")
        if self.analog_order is not None:
            grid, y = _simulate_analog(t, x, self.analog_order, self.analog_corner, self.norm, self.analog_rate,
                                       interpolation, zero_phase, "analog_rate")
        else:
            grid, y = t, x
        n = int(np.floor(intervals)) + 1
        t_k = grid[0] + np.arange(n) / self.sampling_rate
        if self.analog_order is None and interpolation == "previous":
            index = np.clip(np.searchsorted(grid, t_k, side="right") - 1, 0, grid.size - 1)
            y_k = y[index]
        else:
            y_k = np.interp(t_k, grid, y)
        if self.digital_order is not None:
            y_k = _run(self.digital_sos(), y_k, zero_phase)
        return t_k, y_k

    def apply_recording(
        self,
        recording: Recording,
        channels: Sequence[str] | None = None,
        zero_phase: bool = False,
        interpolation: str = "linear",
    ) -> Recording:
        """Filter channels of a recording; the result is sampled at ``sampling_rate``."""
        if not isinstance(recording, Recording):
            raise TypeError(f"recording: must be a Recording, got {type(recording).__name__}")
        if channels is None:
            names = recording.channel_names
        elif isinstance(channels, str):
            names = [channels]
        else:
            names = list(channels)
        if not names:
            raise ValueError(f"channels: name at least one channel; channels: {recording.channel_names}")
        for name in names:
            recording[name]                         # KeyError naming the channels if unknown
        out: dict[str, np.ndarray] = {}
        t_k = None
        for name in names:
            t_k, out[name] = self.apply(recording.time, recording[name], zero_phase, interpolation)
        metadata = dict(recording.metadata)
        metadata["measuring_chain"] = repr(self) + (" (zero-phase)" if zero_phase else "")
        return Recording(t_k, out, {n: recording.units[n] for n in names}, metadata, recording.source)
