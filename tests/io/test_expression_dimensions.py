"""Expressions in model files are checked against the units their [parameters] were written with."""

import math

import pytest

from rodimpact.io import ModelError, loads_model

ROD = '''
[parameters]
{params}
[[rods]]
name = "bar"
velocity = "1 m/s"
[[rods.segments]]
shape = "expression"
length = "0.5 m"
area = "{area}"
[simulation]
steps = 10
'''


def model(params, area):
    return loads_model(ROD.format(params=params, area=area))


@pytest.mark.parametrize("params, area, expected", [
    # expected: the area at s = 0.1 m (L = 0.5 m) worked out by hand in SI units
    ('A0 = "1260 mm^2"', "A0", 1.26e-3),
    ('A0 = "1260 mm^2"', "A0 * (1 + 0.5 * s / L)", 1.26e-3 * 1.1),
    ('A0 = "1260 mm^2"\nk = "2 1/m"', "A0 * exp(-k * s)", 1.26e-3 * math.exp(-0.2)),
    ('d = "40 mm"', "pi * d**2 / 4", math.pi * 0.04**2 / 4),
    ('d = "40 mm"', "pi / 4 * (d + 0.01 * s / L)**2", math.pi / 4 * 0.042**2),   # bare numbers may carry any unit
    ("A0 = 1.26e-3", "A0 * (1 + s)", 1.26e-3 * 1.1),          # a bare parameter: SI, no check possible
    ('A0 = "1260 mm^2"\nA1 = "800 mm^2"', "A1 if s < L / 2 else A0", 0.8e-3),
    ('r = "20 mm"', "pi * sqrt(r**4)", math.pi * 0.02**2),
])
def test_dimensionally_sound_areas_are_accepted(params, area, expected):
    rod = model(params, area).system.rods[0]
    assert rod.area(0.1) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("params, area, match", [
    ('A0 = "1260 mm"', "A0", r"has dimension \[length\], but an area \(m\^2\) is expected \(A0 in \[length\]\)"),
    ('A0 = "1 kg"', "A0 * (1 + s / L)", r"has dimension \[mass\]"),
    ('A0 = "1260 mm^2"', "A0 + s", "sum or difference of different dimensions"),
    ('k = "2 m"', "1e-3 * exp(-k * s)", r"exp\(\) of a quantity of dimension \[length\] \*\* 2"),
    ('A0 = "1260 mm^2"\nd = "40 mm"', "A0 if s < d else d", "branches"),
    ('A0 = "1260 mm^2"\nn = "2 m"', "A0 ** n", "exponent of dimension"),
])
def test_inconsistent_areas_name_the_key_and_the_parameter_units(params, area, match):
    with pytest.raises(ModelError, match=r"rods\[0\]\.segments\[0\]\.area: .*" + match):
        model(params, area)


def test_histories_and_initial_fields_are_checked_too():
    text = '''
[parameters]
F0 = "-50 kN"
tau = "0.1 ms"
v0 = "2 m/s"
Lr = "1 m"
[[rods]]
velocity = "0 m/s"
segments = [{shape = "cylinder", length = "1 m", diameter = "40 mm"}]
initial = {velocity = {expression = "v0 * (1 - x / Lr)"}}
[ends]
left = {type = "force", force = {expression = "F0 * exp(-t / tau)"}}
[simulation]
steps = 10
'''
    loads_model(text)
    with pytest.raises(ModelError, match=r"ends\.left\.force\.expression: .*has dimension \[time\]"):
        loads_model(text.replace("F0 * exp(-t / tau)", "tau"))
    with pytest.raises(ModelError, match=r"exp\(\) of a quantity of dimension \[time\]"):
        loads_model(text.replace("F0 * exp(-t / tau)", "F0 * exp(-t)"))
    with pytest.raises(ModelError, match=r"rods\[0\]\.initial\.velocity\.expression: .*\[length\]"):
        loads_model(text.replace("v0 * (1 - x / Lr)", "v0 * x"))


def test_synthesis_target_expression_is_checked():
    from rodimpact.io.synthesis_spec import loads_spec

    spec = '''
[parameters]
F0 = "-200 kN"
tau = "0.3 ms"
[striker]
velocity = "6 m/s"
elements = 20
[target]
type = "expression"
force = "F0 * exp(-t / tau)"
duration = "0.1 ms"
[[struck]]
segments = [{shape = "cylinder", length = "1 m", diameter = "50 mm"}]
[synthesis]
dt = "1.93 us"
verify = false
'''
    loads_spec(spec)
    with pytest.raises(ModelError, match=r"target\.force: .*has dimension \[time\], but a force"):
        loads_spec(spec.replace("F0 * exp(-t / tau)", "tau * exp(-t / tau)"))


@pytest.mark.parametrize("source, match", [
    ("A0 * where(s < 0.1)", r"where\(\) takes 3 arguments: where\(condition, a, b\), got 1"),
    ("min(A0, A0, A0)", r"min\(\) takes 2 arguments: min\(a, b\), got 3"),   # numpy would take A0 as out=
    ("A0 * sin(s, s)", r"sin\(\) takes 1 argument: sin\(x\), got 2"),
    ("A0 * clip(s, 0)", r"clip\(\) takes 3 arguments"),
])
def test_function_argument_counts_are_checked_when_read(source, match):
    with pytest.raises(ModelError, match=r"rods\[0\]\.segments\[0\]\.area: " + match):
        model('A0 = "1260 mm^2"', source)


def test_a_byte_order_mark_is_accepted(tmp_path):
    from rodimpact.io import load_model

    text = ROD.format(params='A0 = "1260 mm^2"', area="A0")
    (tmp_path / "bom.toml").write_bytes(b"\xef\xbb\xbf" + text.encode())
    assert load_model(tmp_path / "bom.toml").system.rods[0].length == 0.5
