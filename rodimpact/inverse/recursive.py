"""Impactor synthesis by the recursive method (thesis Sec. 4.1): :func:`synthesize`.

Fast formulation (O(n^2), no re-simulation): once the impact-force windows X_j are known, the struck system
alone gives the face velocity V(t) (one run of the direct solver with the force prescribed at the face, or a
closed form for a uniform bar), and the striker is peeled layer by layer from the face histories (N, V) by
:mod:`rodimpact.inverse._kernels`. Each peeled layer yields Z_q and the reflection R_q of the wavefront, from
which K_q, Delta N_q and the force reserve |K_q N_0| of eqs. 4.6-4.9 and the existence condition (4.20)
follow. The straightforward recursion of the thesis (re-simulate from t = 0 for every element, O(n^3)) is
:func:`rodimpact.inverse.reference.synthesize_by_resimulation`; both agree to rounding.
"""

from __future__ import annotations

import time as _time
import warnings
from typing import Any, Optional

import numpy as np

from .._version import __version__
from .._validate import caller_stacklevel, finite, positive
from ..rods.material import STEEL, Material
from . import _kernels as K
from .result import ExistenceFailure, SynthesisResult
from .._moved import moved
from .struck import STRUCK_KEYWORDS, as_struck_system, face_response, locate
from .targets import as_target
from ._schur import chosen_method, peel
from ._toeplitz import TOEPLITZ_METHODS
from .diagnosis import explain_failure
from .transform import checked_quantity, struck_time_step, transform_windows, window_count

#: Default threshold of the estimated relative error of Z_q above which a precision warning is issued.
PRECISION_WARNING = 1e-6
#: Relative size of the within-window face-velocity change above which the odd-step content is reported.
ODD_STEP_TOLERANCE = 1e-9


class SynthesisWarning(UserWarning):
    """The synthesized striker is shorter than requested or cannot be trusted to full precision."""


@moved(STRUCK_KEYWORDS)
def synthesize(target: Any, struck: Any, striker_velocity: float, n: Optional[int] = None,
               dt: Optional[float] = None, *, position: Optional[float] = None, quantity: str = "force",
               rule: str = "midpoint", material: Material = STEEL, backend: str = "numba",
               toeplitz_method: str = "auto", precision_warning: float = PRECISION_WARNING) -> SynthesisResult:
    """Find the striker impedance profile that produces a prescribed force history (recursive method,
    thesis chapter 4).

    Parameters
    ----------
    target:
        The prescribed force (N, tension positive, so an impact force is negative): a callable f(t), samples
        (t, F), window values X_1..X_n or a :class:`~rodimpact.inverse.targets.ForceTarget`. Time in s from
        the impact (from the wavefront's arrival when ``position`` is set). See
        :mod:`rodimpact.inverse.targets` for how it becomes window values (``rule``).
    struck:
        The struck system: a :class:`~rodimpact.Rod` or rods listed from the impact face outwards (bonded, at
        rest, free far end), or a :class:`~rodimpact.System` whose left end is the impact face, best made by
        :meth:`ri.System.struck(rods, far_end=..., velocity=..., junctions=..., loads=..., initial=...)
        <rodimpact.rods.system.System.struck>`.
    striker_velocity:
        Initial velocity v_in of the striker, m/s (> 0: moving towards the struck system). The striker is
        stress-free, moves uniformly and carries no loads (the prerequisites of thesis Sec. 4.1).
    n:
        Number of striker elements = number of force windows of length 2 dt (default: as many as the target
        covers).
    dt:
        Time step = travel time through one element, s (default: from impedance-level struck rods).
    position:
        Distance from the impact face into the struck system (m) where the target is prescribed (thesis Sec.
        4.1.2); None: at the impact face.
    quantity:
        With ``position``: ``"force"`` (normal force at the node) or ``"incident"`` (force wave arriving
        from the impact side).
    rule:
        How a continuous target becomes window values: "midpoint" (default), "start" (thesis), "mean".
    material:
        Striker material, used for lengths, positions and shapes (the impedances do not depend on it).
    backend:
        "numba" (compiled kernel) or "numpy" (reference path), also used for the direct solver.
    toeplitz_method:
        Solver of the transformation: "auto", "substitution", "fft".
    precision_warning:
        Threshold of the estimated relative rounding error of Z_q above which :class:`SynthesisWarning` is
        issued.

    Returns
    -------
    SynthesisResult
        Impedances Z_1..Z_m (m <= n) from the impact face with the per-element quantities of thesis tables
        4.3/4.4 and, when the target cannot be produced for its whole duration, the failing element.
    """
    wall0 = _time.perf_counter()
    if backend not in ("numba", "numpy"):
        raise ValueError(f"backend: must be 'numba' or 'numpy', got {backend!r}")
    v_in = finite("striker_velocity", striker_velocity, "m/s")
    checked_quantity(quantity)       # also without position, so that a typo does not pass unnoticed
    if toeplitz_method not in TOEPLITZ_METHODS:
        raise ValueError(f"toeplitz_method: must be one of {TOEPLITZ_METHODS}, got {toeplitz_method!r}")
    precision_warning = positive("precision_warning", precision_warning)
    if not isinstance(material, Material):
        raise TypeError(f"material: must be a Material, got {type(material).__name__}")
    system = as_struck_system(struck)
    dt = struck_time_step(system, dt)
    tgt = as_target(target, rule)
    n = window_count(tgt, n, dt)
    windows = tgt.window_values(n, dt)
    _check_finite(windows, "target")
    transformation = None
    if position is None:
        _check_compressive(windows)
        x = windows
    else:
        transformation = transform_windows(system, locate(system, position, dt), windows, dt, quantity,
                                           toeplitz_method, backend)
        x = transformation.impact_force
        _check_finite(x, "impact force obtained by the transformation")
        if not x[0] < 0.0:
            raise ValueError(f"target: producing it at {transformation.location.used:.6g} m needs an impact force "
                             f"X_1 = {x[0]:.6g} N in the first window, which is not compressive; a striker can only "
                             "push")
    face = face_response(system, x, dt, backend)
    v_face = face.velocity
    u = v_face[0::2] - v_in
    _check_first_element(x[0], v_face[0], v_in, face.face_impedance)
    z, refl, kappa, m_kernel = peel(x, u, backend)       # O(n^2) or superfast by size (_schur.CROSSOVER)
    tensile = np.flatnonzero(x >= 0.0)
    m = min(m_kernel, int(tensile[0]) if tensile.size else n)

    z1s = face.face_impedance
    z = z[:m].copy()
    r_all = refl.copy()
    r_all[0] = (z[0] - z1s) / (z[0] + z1s)
    n0 = float(x[0] * (z[0] + z1s) / (2.0 * z[0]))
    k_upto = np.concatenate([[1.0], np.cumprod(1.0 - r_all[:max(m_kernel, 1)] ** 2)])
    kf = k_upto[:m]
    reflection = r_all[:m]
    dn = kf * reflection * n0
    reserve = np.abs(kf * n0)
    err = K.error_estimate(r_all, kappa, m)

    warn_list: list[str] = []
    failure = None
    if m < n:
        q = m + 1
        kq = float(k_upto[m])
        rq = float(r_all[m])
        if m < m_kernel or (m == m_kernel and tensile.size and tensile[0] == m):
            reason = "tension"
            msg = (f"element {q} (theta = {m * dt:.6g} s): the impact force required in window {q}, "
                   f"{x[m]:.6g} N, is not compressive; the striker would have to pull. The target can be "
                   f"produced for {2 * m * dt:.6g} s (striker travel time {m * dt:.6g} s).")
        else:
            reason = "existence"
            msg = (f"element {q} (theta = {m * dt:.6g} s): existence condition |dN_q| < |K_q N_0| (thesis eq. 4.20) "
                   f"violated, |dN_q| = {abs(kq * rq * n0):.6g} N >= |K_q N_0| = {abs(kq * n0):.6g} N; a solution "
                   f"exists for a wavefront travel time of {(m - 1) * dt:.6g} s ({m} elements, striker travel time "
                   f"{m * dt:.6g} s) and the target can be produced for {2 * m * dt:.6g} s. "
                   + explain_failure(q, x, dt, v_in, z1s, float(kq * rq * n0), float(abs(kq * n0))))
        failure = ExistenceFailure(q, m * dt, kq, float(kq * rq * n0), float(abs(kq * n0)), rq, reason, msg)
        warn_list.append(f"only {m} of {n} striker elements exist: {msg}")
    if m and err[-1] > precision_warning:
        bad = int(np.argmax(err > precision_warning)) + 1
        warn_list.append(
            f"peeled wave amplitudes grew up to {kappa[:m].max():.3g} times the wavefront amplitude; the estimated "
            f"relative rounding error of Z_q exceeds {precision_warning:g} from element {bad} on (reaches "
            f"{err[-1]:.3g} at element {m}); impedances beyond element {bad} cannot be trusted")
    odd = _odd_step_content(v_face[:2 * m], u[:m])
    if odd > ODD_STEP_TOLERANCE:
        warn_list.append(
            f"the struck system's face velocity changes within force windows (by up to {odd:.3g} of its range); a "
            "striker can only shape what changes every second step (thesis Sec. 4.1), so the synthesized "
            "striker reproduces the target only approximately; check with verify()")
    for w in warn_list:
        warnings.warn(w, SynthesisWarning, stacklevel=caller_stacklevel())
    diagnostics = {
        "version": __version__, "wall_time_s": _time.perf_counter() - wall0, "backend": backend,
        "face_response": face.method, "peeling": chosen_method(n), "odd_step_content": odd,
        "max_error_estimate": float(err[-1]) if m else 0.0,
        "max_amplitude_growth": float(kappa[:m].max()) if m else 0.0,
        "striker_prerequisites": "stress-free, uniform velocity v_in, no nodal loads (thesis Sec. 4.1): "
                                 "satisfied by construction",
        "warnings": warn_list,
    }
    if transformation is not None:
        diagnostics["transformation_residual"] = transformation.residual
        diagnostics["transformation_notes"] = list(transformation.notes)
    return SynthesisResult(
        impedance=z, reflection=reflection, transmission_factor=kf, force_difference=dn, force_reserve=reserve,
        amplitude_growth=kappa[:m].copy(), error_estimate=err, window_values=x, face_velocity=v_face, dt=dt,
        striker_velocity=v_in, struck_face_impedance=z1s, impact_force_n0=float(n0), n_requested=n,
        struck=system, failure=failure, transformation=transformation, material=material,
        diagnostics=diagnostics)


def _check_finite(x: np.ndarray, what: str) -> None:
    bad = ~np.isfinite(x)
    if bad.any():
        j = int(np.flatnonzero(bad)[0])
        raise ValueError(f"{what}: window {j + 1} (from t = {2 * j} dt) is {float(x[j])}; forces must be finite")


def _check_compressive(x: np.ndarray) -> None:
    bad = np.flatnonzero(~(x < 0.0))
    if bad.size:
        j = int(bad[0])
        raise ValueError(f"target: window {j + 1} has the force {float(x[j]):.6g} N, which is not compressive; an "
                         "impact force must be negative (tension positive) in every window, since a contact cannot "
                         "pull")


def _check_first_element(x1: float, v0: float, v_in: float, z1s: float) -> None:
    """Z_1 = X_1 / (V_0 - v_in) (eq. 4.4) must be positive and finite: the striker must be faster than the
    face of the struck system under the first force."""
    if not v0 < v_in:
        raise ValueError(
            f"striker_velocity: {v_in:.6g} m/s cannot produce the first force window X_1 = {x1:.6g} N: under that "
            f"force the struck face moves at {v0:.6g} m/s (face impedance {z1s:.6g} N s/m), so the striker must be "
            f"faster than {v0:.6g} m/s; raise striker_velocity or lower |X_1|")


def _odd_step_content(v: np.ndarray, u_even: np.ndarray) -> float:
    """max |V(2s+1) - V(2s)| relative to the range of the face velocity relative to the striker."""
    if v.size < 2:
        return 0.0
    scale = max(float(np.max(np.abs(u_even))), 1e-300)
    return float(np.max(np.abs(v[1::2] - v[0::2])) / scale)
