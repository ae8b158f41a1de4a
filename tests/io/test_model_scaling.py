"""Model-file validation does work proportional to the file, and stops as soon as it can (issue 20, item 17).

No wall-clock assertions: the tests count the expensive operations (pint conversions, memory queries, rods
validated) for a file of n entries and of 4n entries. The times are in benchmarks/bench_readers.py and
docs/performance.md.
"""

from __future__ import annotations

import random

import pytest

import rodimpact._validate as validate_module
import rodimpact.io.model as model_module
import rodimpact.io.quantities as quantities_module
from rodimpact._quantities import DIMENSIONS
from rodimpact.io.model import loads_model
from rodimpact.io.quantities import ModelError, parse_quantity


def _rods_with_a_duplicate_name(n: int) -> str:
    rods = []
    for i in range(n):
        name = "striker" if i < 2 else f"rod{i}"
        rods.append(f'[[rods]]\nname = "{name}"\nvelocity = "{1 if i == 0 else 0} m/s"\n[[rods.segments]]\n'
                    f'shape = "cylinder"\nlength = "0.1 m"\ndiameter = "20 mm"\n')
    return "[simulation]\nsteps = 5\n" + "\n".join(rods)


def _count_calls(monkeypatch, module, name: str) -> list[int]:
    counter = [0]
    original = getattr(module, name)

    def counted(*args, **kwargs):
        counter[0] += 1
        return original(*args, **kwargs)

    monkeypatch.setattr(module, name, counted)
    return counter


def test_a_duplicate_rod_name_is_reported_before_any_rod_is_validated(monkeypatch):
    # the file of 10,000 rods with a duplicate at rods[1] took 10.9 s: every rod was validated and built first
    calls = _count_calls(monkeypatch, model_module, "validate_table")
    for n in (50, 200):
        calls[0] = 0
        with pytest.raises(ModelError, match=r"^rods\[1\]\.name: 'striker' is already the name of rods\[0\]"):
            loads_model(_rods_with_a_duplicate_name(n))
        assert calls[0] == 0, f"{calls[0]} tables validated before the duplicate name was reported (n = {n})"


def test_a_duplicate_name_of_another_type_is_left_to_the_schema():
    text = _rods_with_a_duplicate_name(3).replace('name = "rod2"', "name = 5", 1)
    with pytest.raises(ModelError, match=r"^rods\[1\]\.name: 'striker' is already"):
        loads_model(text)
    text = _rods_with_a_duplicate_name(3).replace('name = "striker"', "name = 5", 1)
    with pytest.raises(ModelError, match=r"^rods\[0\]\.name: expected a string"):
        loads_model(text)


def _table_rod(n: int) -> str:
    x = ", ".join(f'"{i} mm"' for i in range(n))
    d = ", ".join(f'"{20 + (i % 5) * 0.5} mm"' for i in range(n))
    return (f'[simulation]\nsteps = 5\n[[rods]]\nvelocity = "9 m/s"\n[[rods.segments]]\nshape = "table"\n'
            f"x = [{x}]\ndiameter = [{d}]\n")


def test_pint_converts_each_unit_once_not_each_value(monkeypatch):
    # an array of 10^5 unit strings took seconds: pint converted every value (~0.1 ms each)
    convert = _count_calls(monkeypatch, quantities_module, "si_magnitude")
    counts = []
    for n in (100, 400):
        quantities_module._unit_factor.cache_clear()
        convert[0] = 0
        model = loads_model(_table_rod(n))
        assert model.system.rods[0].length == pytest.approx((n - 1) * 1e-3, rel=1e-12)
        counts.append(convert[0])
    assert counts[0] == counts[1], f"pint conversions grow with the number of values: {counts}"


def test_the_fast_path_gives_pints_value_bit_for_bit():
    # number * cached factor against pint's own parse and conversion of the whole string
    units = {"length": ["mm", "m", "um", "in", "ft", "cm"], "time": ["ms", "us", "ns", "min"],
             "velocity": ["m/s", "mm/ms", "km/h"], "force": ["kN", "MN", "lbf"], "pressure": ["GPa", "MPa", "psi"],
             "density": ["kg/m^3", "g/cm**3"], "mass": ["kg", "g", "lb"], "impedance": ["kN s/m", "N*s/m"],
             "stiffness": ["MN/m", "N/mm"], "area": ["mm^2", "cm**2"], "acceleration": ["m/s^2", "N/kg"]}
    rnd = random.Random(20)
    fast = 0
    for dim, names in units.items():
        target = DIMENSIONS[dim].pint
        for unit in names:
            for _ in range(60):
                number = rnd.choice([f"{rnd.uniform(-1e4, 1e4):.{rnd.randint(1, 17)}g}", str(rnd.randint(-10**7, 10**7)),
                                     f"{rnd.uniform(0, 10):.9e}", f"{rnd.random():.17f}"])
                text = f"{number} {unit}"
                expected = quantities_module.si_magnitude(quantities_module.pint_quantity(text, "k"), target, text,
                                                          "k", "")
                assert parse_quantity(text, dim, "k") == expected, text
                m = quantities_module._NUMBER_UNIT.fullmatch(text)
                fast += m is not None and quantities_module._unit_factor(m.group(2), dim) is not None
    assert fast == 60 * sum(map(len, units.values()))     # every one of them took the fast path


@pytest.mark.parametrize("text, dim, match", [
    ("5 kg", "length", r'expected a length .* got "5 kg" \(a mass\)'),
    ("1e400 mm", "length", "must be finite"),
    ("20 degC", "pressure", "expected a pressure"),
    ("5 furlongs_x", "length", "cannot read"),
])
def test_values_outside_the_fast_path_keep_their_messages(text, dim, match):
    with pytest.raises(ModelError, match=match):
        parse_quantity(text, dim, "k")


def _runs(n: int) -> str:
    runs = ", ".join(f'{{ impedance = "{51 + i % 3} kN s/m", count = 100 }}' for i in range(n))
    return (f'[simulation]\nsteps = 5\n[[rods]]\nvelocity = 9\n[rods.elements]\nelement_length = "5 mm"\n'
            f"runs = [{runs}]\n")


def test_the_memory_of_impedance_runs_is_asked_for_once(monkeypatch):
    # psutil was asked after every run (0.1 ms each): 12 s of a 160,000-run file
    asked = [0]

    def memory():
        asked[0] += 1
        return 2.0**40

    monkeypatch.setattr(validate_module, "physical_memory", memory)
    counts = []
    for n in (1000, 4000):          # 100 elements a run: past the 8 MiB below which memory is not asked
        asked[0] = 0
        assert loads_model(_runs(n)).system.rods[0].native.impedance.size == 100 * n
        counts.append(asked[0])
    assert counts == [1, 1]


def test_the_first_run_that_does_not_fit_is_named(monkeypatch):
    # a machine of 100 MB: 0.8 x 100 MB / 128 bytes = 625,000 elements fit; run 6250 ends at 625,100
    monkeypatch.setattr(validate_module, "physical_memory", lambda: 100e6)
    with pytest.raises(ModelError, match=r"^rods\[0\]\.elements\.runs\[6250\]\.count: 625,100 elements "
                                         r"\(runs\[0\.\.6250\]\) would need"):
        loads_model(_runs(8000))


def test_a_file_without_overrides_is_not_copied(monkeypatch):
    def refuse(*args):
        raise AssertionError("apply_overrides called without overrides")

    monkeypatch.setattr(model_module, "apply_overrides", refuse)
    assert loads_model(_table_rod(300)).system.rods[0].length == pytest.approx(0.299)
