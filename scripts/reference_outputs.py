"""Reference outputs of every shipped example, template and test model file, for the bit-for-bit check.

``tests/test_reference_outputs.py`` runs each case below and compares the SHA-256 of the arrays the compiled
loop writes itself (junction forces, end forces and velocities, probe forces and velocities, final element
states) with the digests stored in ``tests/data/reference-outputs.json``. These are regression references:
they pin today's results so that a refactor (issue 21: the problem object and the schema) provably changes
nothing; the physics is verified elsewhere against closed forms, the modal solution and the thesis. Sums
computed by numpy (energies) are left out: their bits depend on the CPU's SIMD dispatch.

Rewrite the file only for an intended change of results, and say why in the commit::

    python scripts/reference_outputs.py --write
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
from pathlib import Path
from typing import Any, Callable, Iterator

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
STORE = ROOT / "tests" / "data" / "reference-outputs.json"


def digest(a: np.ndarray) -> str:
    """SHA-256 of the array's float64 little-endian bytes in C order, with its shape."""
    b = np.ascontiguousarray(np.asarray(a, dtype="<f8"))
    return hashlib.sha256(repr(b.shape).encode() + b.tobytes()).hexdigest()


def simulation_digests(res: Any) -> dict[str, str]:
    """Digests of the arrays of a :class:`~rodimpact.SimulationResult` that the compiled loop writes."""
    out = {"time": digest(res.time), "junction_force": digest(res.junction_force),
           "final_force": digest(res.final_force), "final_velocity": digest(res.final_velocity)}
    for side in sorted(res.end_force):
        out[f"end_force.{side}"] = digest(res.end_force[side])
        out[f"end_velocity.{side}"] = digest(res.end_velocity[side])
    for name in sorted(res.probes):
        out[f"probe.{name}.force"] = digest(res.probes[name].force)
        out[f"probe.{name}.velocity"] = digest(res.probes[name].velocity)
    return out


def cases() -> Iterator[tuple[str, Callable[[], dict[str, str]]]]:
    """(name, run) for every shipped example model, every template and every model file under tests/data."""
    from rodimpact.examples import EXAMPLES, load_example
    from rodimpact.io.model import load_model, loads_model
    from rodimpact.io.synthesis_spec import TEMPLATE as SYNTHESIS
    from rodimpact.io.synthesis_spec import loads_spec, run
    from rodimpact.io.templates import TEMPLATES

    for name, ex in EXAMPLES.items():
        for i, file in enumerate(ex.models):
            yield f"example:{name}:{file}", (lambda n=name, j=i: simulation_digests(
                load_example(n, j).simulate(progress=False)))
    for kind, (text, _) in TEMPLATES.items():
        yield f"template:{kind}", (lambda t=text: simulation_digests(loads_model(t).simulate(progress=False)))

    def synthesis() -> dict[str, str]:
        r = run(loads_spec(SYNTHESIS))
        return {"impedance": digest(r.result.impedance), **simulation_digests(r.verification.simulation)}
    yield "template:synthesize", synthesis
    for path in sorted((ROOT / "tests" / "data").rglob("*.toml")):
        rel = path.relative_to(ROOT).as_posix()
        yield f"file:{rel}", (lambda p=path: simulation_digests(load_model(p).simulate(progress=False)))


def compute() -> dict[str, dict[str, str]]:
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return {name: run() for name, run in cases()}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--write", action="store_true", help=f"rewrite {STORE.relative_to(ROOT)}")
    args = ap.parse_args(argv)
    now = compute()
    if args.write:
        STORE.write_text(json.dumps(now, indent=1, sort_keys=True) + "\n", encoding="utf-8")
        print(f"wrote {len(now)} cases to {STORE.relative_to(ROOT)}")
        return 0
    stored = json.loads(STORE.read_text(encoding="utf-8"))
    bad = [f"{c}: {k}" for c in sorted(set(now) | set(stored)) for k in sorted(set(now.get(c, {})) | set(stored.get(c, {})))
           if now.get(c, {}).get(k) != stored.get(c, {}).get(k)]
    print("\n".join(bad) if bad else f"all {len(now)} cases bit for bit equal")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
