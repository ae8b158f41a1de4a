"""Smith soil (ShaftResistance, SoilToe) in model files and its refusals: read with units, written back exactly,
run bit for bit; impossible parameters refused naming the field (Python) or the key path (model file)."""

from __future__ import annotations

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.io.model import ModelError, dump_model, loads_model
from rodimpact.rods.soil import ShaftResistance, SmithSoil, SoilToe

MODEL = """
[[rods]]
name = "ram"
velocity = "3 m/s"
[[rods.segments]]
shape = "cylinder"
length = "1 m"
diameter = "300 mm"

[[rods]]
name = "pile"
[[rods.segments]]
shape = "cylinder"
length = "10 m"
diameter = "300 mm"

[ends]
right = { type = "soil-toe", ultimate = "400 kN", quake = "2.5 mm", unloading_quake = "1 mm", damping = 0.49 }

[[loads]]
type = "shaft-soil"
rod = "pile"
depths = ["2 m", "6 m", "10 m"]
unit_resistance = ["20 kN/m", "60 kN/m"]
quake = "2.5 mm"
damping = 0.3
damping_kind = "smith-viscous"

[simulation]
duration = "8 ms"
dt = "9.66 us"
"""


def test_soil_is_read_with_units() -> None:
    model = loads_model(MODEL)
    toe, shaft = model.system.right, model.system.loads[0]
    assert isinstance(toe, SoilToe) and isinstance(shaft, ShaftResistance)
    assert (toe.ultimate, toe.quake, toe.unloading_quake, toe.damping, toe.damping_kind) == (
        400e3, 2.5e-3, 1e-3, 0.49, "smith")
    assert shaft.depths == (2.0, 6.0, 10.0) and shaft.unit_resistance == (20e3, 60e3)
    assert shaft.total == pytest.approx(4 * 20e3 + 4 * 60e3, rel=1e-12)


def test_written_back_exactly_and_run_bit_for_bit() -> None:
    model = loads_model(MODEL)
    text = dump_model(model)
    again = loads_model(text)
    assert dump_model(again) == text
    a, b = model.simulate(progress=False), again.simulate(progress=False)
    assert np.array_equal(a.end_force["right"], b.end_force["right"])
    assert a.soil.toe_set > 0 and a.energy.work_soil[-1] < 0 and a.energy.balance_error < 1e-12


def test_soil_work_is_saved_and_loaded(tmp_path) -> None:
    res = loads_model(MODEL).simulate(progress=False)
    ri.save(res, tmp_path / "blow")
    back = ri.load(tmp_path / "blow")
    assert np.array_equal(back.energy.work_soil, res.energy.work_soil) and res.energy.work_soil[-1] < 0
    for name in ("rod", "node", "position", "ultimate", "displacement", "resistance", "plastic_set", "work",
                 "dissipated"):
        assert np.array_equal(getattr(back.soil, name), getattr(res.soil, name)), name
    assert (back.soil.toe_end, back.soil.toe_set, back.soil.toe_dissipated) == (
        res.soil.toe_end, res.soil.toe_set, res.soil.toe_dissipated)
    assert ri.next_blow(back).right == ri.next_blow(res).right       # the next blow from the stored result


@pytest.mark.parametrize("old, new, message", [
    ('quake = "2.5 mm", unloading', 'quake = "-2.5 mm", unloading', r"ends\.right\.quake: must be > 0"),
    ('ultimate = "400 kN"', 'ultimate = "-400 kN"', r"ends\.right\.ultimate: must be >= 0"),
    ('unit_resistance = ["20 kN/m", "60 kN/m"]', 'unit_resistance = ["20 kN/m", "-60 kN/m"]',
     r"loads\[0\]\.unit_resistance\[1\]: must be >= 0, got -60000 N/m"),
    ('depths = ["2 m", "6 m", "10 m"]', 'depths = ["2 m", "1 m", "10 m"]', r"loads\[0\]\.depths: must increase"),
    ('depths = ["2 m", "6 m", "10 m"]', 'depths = ["2 m", "6 m", "12 m"]',
     r"loads\[0\]\.depths: the last depth 12 m lies beyond the end of the rod \(10 m\)"),
    ('damping_kind = "smith-viscous"', 'damping_kind = "smith-viscus"',
     r"loads\[0\]\.damping_kind: must be one of 'smith', 'smith-viscous', 'case', got 'smith-viscus' \(did you "
     r"mean 'smith-viscous'\?\)"),
])
def test_impossible_soil_is_refused_by_key_path(old: str, new: str, message: str) -> None:
    assert old in MODEL
    with pytest.raises(ModelError, match=message):
        loads_model(MODEL.replace(old, new))


@pytest.mark.parametrize("make, message", [
    (lambda: SoilToe(1e5, -1e-3), r"SoilToe\.quake: must be > 0"),
    (lambda: SoilToe(1e5, 0.0), r"SoilToe\.quake: must be > 0, got 0\.0 m \(a quake of zero is a rigid-plastic"),
    (lambda: SoilToe(-1e5), r"SoilToe\.ultimate: must be >= 0"),
    (lambda: SoilToe(1e5, 1e-3, unloading_quake=2e-3), r"SoilToe\.unloading_quake: must be <= SoilToe\.quake"),
    (lambda: SoilToe(1e5, damping_kind="cse"), r"SoilToe\.damping_kind: .* \(did you mean 'case'\?\)"),
    (lambda: SoilToe(1e5, damping_kind="case"), r"SoilToe\.damping: the Case damping factor J_c"),
    (lambda: SoilToe(1e5, resistance=2e5), r"SoilToe\.resistance: must lie in \[0, ultimate"),
    (lambda: ShaftResistance(0, [0.0, 1.0], [-5.0]), r"ShaftResistance\.unit_resistance\[0\]: must be >= 0"),
    (lambda: ShaftResistance(0, [1.0, 1.0], [5.0]), r"ShaftResistance\.depths: must increase"),
    (lambda: ShaftResistance(0, [-1.0, 1.0], [5.0]), r"ShaftResistance\.depths\[0\]: must be >= 0"),
    (lambda: ShaftResistance(0, [0.0, 1.0], [5.0, 6.0]), r"ShaftResistance\.unit_resistance: needs one value per"),
    (lambda: ShaftResistance(0, [0.0, 1.0], [5.0], quake=-1.0), r"ShaftResistance\.quake: must be > 0"),
    (lambda: ShaftResistance(0, [0.0, 1.0], [5.0], damping_kind="viscous"),
     r"ShaftResistance\.damping_kind: .*got 'viscous' \(did you mean 'smith-viscous'\?\)"),
    (lambda: SmithSoil(1e5, -1e-3), r"SmithSoil\.quake: must be > 0"),
    (lambda: ri.System([ri.Rod.from_impedance([1e6] * 10, dt=1e-5)], [0.0],
                       loads=[ShaftResistance(0, [0.0, 9.0], [5.0])]),
     r"loads\[0\]\.depths: the last depth 9 m lies beyond the end of the rod"),
])
def test_impossible_soil_is_refused_naming_the_field(make, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        make()


def test_batch_and_design_refuse_soil_clearly() -> None:
    dt = 1e-5
    striker = ri.Rod.from_impedance([1e6] * 10, dt=dt)
    pile = ri.Rod.from_impedance([1e6] * 50, dt=dt)
    system = ri.System([striker, pile], [3.0, 0.0], right=SoilToe(1e5))
    with pytest.raises(ValueError, match="simulate_batch does not support Smith soil"):
        ri.simulate_batch(system, np.full((2, 10), 1e6), 3.0, ri.TimeGrid(dt, 100))
    from rodimpact.design._adjoint import ImpactProblem
    with pytest.raises(ValueError, match=r"struck\.right: design's exact gradients do not cover Smith soil"):
        ImpactProblem(ri.System.struck([pile], far_end=SoilToe(1e5)), dt, 10, 100)
