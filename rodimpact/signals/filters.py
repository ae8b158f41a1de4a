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
piecewise-linear input on that grid: the state-space model is discretised with a
first-order hold (``scipy.signal.cont2discrete(..., method='foh')``), which is the same
input model as ``scipy.signal.lsim``, and run as second-order sections. The ADC then
samples the (smooth) analog output at ``t0 + k / sampling_rate`` by linear interpolation,
and the digital filter runs on those samples.

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

from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import signal

from .recording import Recording

__all__ = [
    "MeasuringChain",
    "bessel_analog",
    "bessel_digital",
    "simulate_analog_filter",
]

_NORMS = ("mag", "phase", "delay")


def _check_order(order: Any, what: str) -> int:
    if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or order < 1:
        raise ValueError(f"{what} must be a positive integer, got {order!r}")
    return int(order)


def _check_positive(value: Any, what: str) -> float:
    try:
        value = float(value)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{what} must be a number, got {value!r}") from exc
    if not np.isfinite(value) or value <= 0:
        raise ValueError(f"{what} must be positive and finite, got {value!r}")
    return value


def _check_norm(norm: str) -> str:
    if norm not in _NORMS:
        raise ValueError(f"norm must be one of {_NORMS}, got {norm!r}")
    return norm


def bessel_analog(order: int, corner: float, norm: str = "mag") -> tuple[np.ndarray, np.ndarray, float]:
    """Analog Bessel low-pass as zeros, poles (rad/s) and gain; ``corner`` in Hz."""
    order = _check_order(order, "order")
    corner = _check_positive(corner, "corner frequency")
    z, p, k = signal.bessel(order, 2 * np.pi * corner, btype="low", analog=True, output="zpk", norm=_check_norm(norm))
    return z, p, float(k)


def bessel_digital(order: int, corner: float, sampling_rate: float, norm: str = "mag") -> np.ndarray:
    """Digital IIR Bessel low-pass as second-order sections (bilinear, pre-warped at ``corner``)."""
    order = _check_order(order, "order")
    corner = _check_positive(corner, "corner frequency")
    fs = _check_positive(sampling_rate, "sampling_rate")
    if corner >= fs / 2:
        raise ValueError(f"corner frequency {corner} Hz must be below the Nyquist frequency {fs / 2} Hz")
    return signal.bessel(order, corner, btype="low", analog=False, output="sos", norm=_check_norm(norm), fs=fs)


def _foh_sos(order: int, corner: float, norm: str, dt: float) -> np.ndarray:
    """Analog Bessel discretised exactly for piecewise-linear input on a grid of step ``dt``.

    Designed on the prototype with a 1 rad/s corner and the dimensionless step
    ``omega_c * dt`` so that the state-space matrices stay well scaled.
    """
    z, p, k = signal.bessel(order, 1.0, btype="low", analog=True, output="zpk", norm=norm)
    a, b, c, d = signal.zpk2ss(z, p, k)
    ad, bd, cd, dd, _ = signal.cont2discrete((a, b, c, d), 2 * np.pi * corner * dt, method="foh")
    zd, pd, kd = signal.ss2zpk(ad, bd, cd, dd)
    # The first-order hold keeps the DC gain exactly; restore it against round-off of ss2zpk
    # (~1e-8), so that a constant input passes unchanged.
    dc_analog = np.real(k * np.prod(-z) / np.prod(-p))
    dc_digital = np.real(kd * np.prod(1.0 - zd) / np.prod(1.0 - pd))
    return signal.zpk2sos(zd, pd, kd * dc_analog / dc_digital)


def _run(sos: np.ndarray, x: np.ndarray, zero_phase: bool) -> np.ndarray:
    if zero_phase:
        padlen = 3 * (2 * len(sos) + 1)
        if x.size <= padlen:
            raise ValueError(
                f"zero-phase filtering needs more than {padlen} samples on the filter's grid, got {x.size}"
            )
        return signal.sosfiltfilt(sos, x)
    y, _ = signal.sosfilt(sos, x, zi=signal.sosfilt_zi(sos) * x[0])
    return y


def _validated_signal(time: Any, values: Any) -> tuple[np.ndarray, np.ndarray]:
    t = np.asarray(time, dtype=float)
    x = np.asarray(values, dtype=float)
    if t.ndim != 1 or t.shape != x.shape:
        raise ValueError(f"time and values must be 1-D arrays of equal length, got {t.shape} and {x.shape}")
    if t.size < 2:
        raise ValueError("need at least 2 samples")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(x))):
        raise ValueError("time and values must be finite")
    if np.any(np.diff(t) <= 0):
        raise ValueError("time must be strictly increasing")
    return t, x


def _on_uniform_grid(t: np.ndarray, x: np.ndarray, min_rate: float, interpolation: str) -> tuple[np.ndarray, np.ndarray]:
    """The signal on a uniform grid at least ``min_rate`` fast (the input itself if it qualifies)."""
    if interpolation not in ("linear", "previous"):
        raise ValueError(f"interpolation must be 'linear' or 'previous', got {interpolation!r}")
    steps = np.diff(t)
    step = float(np.median(steps))
    uniform = np.all(np.abs(steps - step) <= 1e-6 * step)
    if uniform and 1.0 / step >= min_rate * (1 - 1e-9):
        return t, x
    n = int(np.floor((t[-1] - t[0]) * min_rate * (1 + 1e-12))) + 1
    grid = t[0] + np.arange(n) / min_rate
    if interpolation == "linear":
        return grid, np.interp(grid, t, x)
    index = np.clip(np.searchsorted(t, grid, side="right") - 1, 0, t.size - 1)
    return grid, x[index]


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
    corner = _check_positive(corner, "corner frequency")
    rate = _check_positive(simulation_rate, "simulation_rate")
    if rate < 10 * corner:
        raise ValueError(f"simulation_rate {rate} Hz should be at least 10 x the corner frequency {corner} Hz")
    grid, u = _on_uniform_grid(t, x, rate, interpolation)
    dt = float(np.median(np.diff(grid)))
    return grid, _run(_foh_sos(order, corner, _check_norm(norm), dt), u, zero_phase)


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
                raise ValueError(f"analog_rate {self.analog_rate} Hz should be at least 10 x analog_corner {corner} Hz")
        if self.digital_order is not None:
            _check_order(self.digital_order, "digital_order")
            if _check_positive(self.digital_corner, "digital_corner") >= fs / 2:
                raise ValueError(
                    f"digital_corner {self.digital_corner} Hz must be below the Nyquist frequency {fs / 2} Hz"
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
        f = np.atleast_1d(np.asarray(frequency, dtype=float))
        if self.analog_order is None:
            return np.ones(f.shape, dtype=complex)
        z, p, k = self.analog_zpk()
        return signal.freqs_zpk(z, p, k, worN=2 * np.pi * f)[1]

    def digital_response(self, frequency: Any) -> np.ndarray:
        """Complex response of the digital stage at ``frequency`` (Hz), via ``sosfreqz``."""
        f = np.atleast_1d(np.asarray(frequency, dtype=float))
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
        f = np.atleast_1d(np.asarray(frequency, dtype=float))
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
        ``'previous'``); see the module docstring for the analog simulation.
        """
        t, x = _validated_signal(time, values)
        if self.analog_order is not None:
            grid, y = simulate_analog_filter(
                t, x, self.analog_order, self.analog_corner, self.norm, self.analog_rate, interpolation, zero_phase
            )
        else:
            grid, y = t, x
        n = int(np.floor((grid[-1] - grid[0]) * self.sampling_rate * (1 + 1e-12))) + 1
        if n < 2:
            raise ValueError(
                f"signal spans {grid[-1] - grid[0]} s, shorter than one sample interval of the chain"
            )
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
        channels: list[str] | None = None,
        zero_phase: bool = False,
        interpolation: str = "linear",
    ) -> Recording:
        """Filter channels of a recording; the result is sampled at ``sampling_rate``."""
        names = recording.channel_names if channels is None else list(channels)
        out: dict[str, np.ndarray] = {}
        t_k = None
        for name in names:
            t_k, out[name] = self.apply(recording.time, recording[name], zero_phase, interpolation)
        metadata = dict(recording.metadata)
        metadata["measuring_chain"] = repr(self) + (" (zero-phase)" if zero_phase else "")
        return Recording(t_k, out, {n: recording.units[n] for n in names}, metadata, recording.source)
