"""Published sets of Smith soil parameters (rodimpact/pile/soils/*.toml): every number equals the value of its source
as transcribed here (typed in the tests with the citation, in the source's own units, converted with the exact
foot and inch), every number has a source, and the sets reach SoilDynamics from Python and from a spec.

The values were read from verbatim quotations of the sources in a third-party report, not from the sources
themselves (docs/pile-driving.md, "Soil parameters and their sources"); the files' ``status`` says so and a test
keeps it said."""

from __future__ import annotations

import pytest

import rodimpact as ri

from rodimpact.io.pile_spec import TEMPLATE, loads_spec
from rodimpact.io.quantities import ModelError
from rodimpact.pile import SoilDynamics, soil_set, soil_set_names
from rodimpact.pile.units import FOOT, INCH

#: FHWA GEC-12 (FHWA-NHI-16-009) Vol. II: sec. 12.5 "Shaft quake and toe damping are generally left at the defaults
#: of 0.10 inches and 0.15 s/ft"; sec. 12.8 "shaft damping factors on the order of 0.05 s/ft for non-cohesive soils,
#: 0.10 s/ft for silty sands ..., 0.15 s/ft for cohesive silts and sandy clays, and 0.20 s/ft for cohesive soils
#: ... toe damping factor is about 0.15 s/ft"
GEC12_SHAFT_QUAKE_IN = 0.10
GEC12_TOE_DAMPING_S_FT = 0.15
GEC12_SHAFT_DAMPING_S_FT = {"non-cohesive": 0.05, "silty-sand": 0.10, "cohesive-silt": 0.15, "cohesive": 0.20}

#: Rausche, "GRLWEAP Fundamentals": slide 38 shaft quake "2.5 mm or 0.1 inches"; slide 40 toe quake "D/120 very
#: dense/hard, D/60 softer/loose, 0.1"/2.5 mm non-displacement, 1 mm on hard rock"; slides 41-42 "Clay 0.65 s/m,
#: Sand 0.16 s/m, Silts intermediate, Toe all soils 0.50 s/m"
GRLWEAP_SHAFT_QUAKE_MM = 2.5
GRLWEAP_TOE_DAMPING_S_M = 0.50
GRLWEAP_SHAFT_DAMPING_S_M = {"clay": 0.65, "sand": 0.16}
GRLWEAP_TOE_QUAKE_DIVISORS = {"very-dense-or-hard": 120, "soft-or-loose": 60}
GRLWEAP_TOE_QUAKE_MM = {"non-displacement": 2.5, "hard-rock": 1.0}


def test_shipped_sets():
    assert soil_set_names() == ["gec12", "grlweap"]


def test_gec12_values_are_the_circulars():
    s = soil_set("gec12")
    assert s.shaft_quake == pytest.approx(GEC12_SHAFT_QUAKE_IN * INCH, rel=1e-15)                 # 2.54 mm
    assert s.toe_damping == pytest.approx(GEC12_TOE_DAMPING_S_FT / FOOT, rel=1e-15)              # 0.4921 s/m
    assert s.shaft_damping == pytest.approx({k: v / FOOT for k, v in GEC12_SHAFT_DAMPING_S_FT.items()}, rel=1e-15)
    assert s.toe_quake_rules == []          # no toe quake rule in the quoted sentences: stated for the job


def test_grlweap_values_are_the_slides():
    s = soil_set("grlweap")
    assert s.shaft_quake == pytest.approx(GRLWEAP_SHAFT_QUAKE_MM * 1e-3, rel=1e-15)
    assert s.toe_damping == pytest.approx(GRLWEAP_TOE_DAMPING_S_M, rel=1e-15)
    assert s.shaft_damping == pytest.approx(GRLWEAP_SHAFT_DAMPING_S_M, rel=1e-15)
    assert s.toe_quake_divisors == pytest.approx(GRLWEAP_TOE_QUAKE_DIVISORS, rel=1e-15)
    assert s.toe_quakes == pytest.approx({k: v * 1e-3 for k, v in GRLWEAP_TOE_QUAKE_MM.items()}, rel=1e-15)
    assert s.toe_quake("very-dense-or-hard", 0.610) == pytest.approx(0.610 / 120, rel=1e-15)
    assert s.toe_quake("soft-or-loose", 0.610) == pytest.approx(0.610 / 60, rel=1e-15)


@pytest.mark.parametrize("name", ["gec12", "grlweap"])
def test_every_number_cites_its_source_and_how_it_was_read(name):
    s = soil_set(name)
    keys = {"shaft_quake", "toe_damping", *(f"shaft_damping.{k}" for k in s.shaft_damping),
            *(f"toe_quake.{k}" for k in s.toe_quake_rules)}
    assert set(s.sources) == keys and all(s.sources.values())
    assert s.status.startswith("secondary:")           # not read in the source itself: the file must say so


def test_rods_soil_defaults_are_gec12_non_cohesive():
    """The defaults of ShaftResistance and SoilToe (rodimpact.rods.soil) are GEC-12's, as their docstring says."""
    from rodimpact.rods import soil as rods_soil

    s = soil_set("gec12")
    assert rods_soil.DEFAULT_QUAKE == pytest.approx(s.shaft_quake, rel=1e-15)
    assert rods_soil.DEFAULT_SHAFT_DAMPING == pytest.approx(s.shaft_damping["non-cohesive"], rel=1e-15)
    assert rods_soil.DEFAULT_TOE_DAMPING == pytest.approx(s.toe_damping, rel=1e-15)
    # the toe's default quake: GRLWEAP's toe quake of a non-displacement pile, quoted as '0.1"/2.5 mm' (slide 40)
    assert ri.SoilToe(1e5).quake == pytest.approx(0.1 * 0.0254, rel=1e-15)
    assert soil_set("grlweap").toe_quakes["non-displacement"] == pytest.approx(ri.SoilToe(1e5).quake, rel=0.02)


def test_published_dynamics_from_python():
    d = SoilDynamics.published("grlweap", "clay", "very-dense-or-hard", toe_diameter=0.508)
    assert d == SoilDynamics(2.5e-3, 0.508 / 120, 0.65, 0.50, "smith")
    g = SoilDynamics.published("gec12", "non-cohesive", "2.54 mm")
    assert (g.shaft_quake, g.toe_quake, g.damping_kind) == (pytest.approx(2.54e-3), pytest.approx(2.54e-3), "smith")
    assert (g.shaft_damping, g.toe_damping) == (pytest.approx(0.05 / FOOT), pytest.approx(0.15 / FOOT))


@pytest.mark.parametrize("args, kwargs, message", [
    (("gec12", "clay", "2.5 mm"), {}, "shaft_soil: 'clay' is not a soil of the 'gec12' set; one of 'non-cohesive'"),
    (("grlweap", "sand", "dense"), {}, "toe_quake: 'dense' is not a toe quake rule of the 'grlweap' set; its rules: "
                                       "'hard-rock', 'non-displacement', 'soft-or-loose', 'very-dense-or-hard'"),
    (("grlweap", "sand", "soft-or-loose"), {}, "toe_diameter: missing; the 'grlweap' toe quake rule "
                                               "'soft-or-loose' is the toe diameter / 60"),
    (("grlweap", "sand", "2 mm"), {"toe_diameter": 0.5}, "toe_diameter: only with a toe quake rule"),
    (("gec12", "cohesive", "hard-rock"), {}, "toe_quake: 'hard-rock' is not a toe quake rule of the 'gec12' set; "
                                             "its rules: none"),
    (("smith1960", "sand", "2.5 mm"), {}, "parameter_set: no soil parameter set 'smith1960'; shipped: gec12, grlweap"),
    (("grlweap", "sand", "5 kg"), {}, "SoilDynamics.toe_quake: expected a quantity in m"),
])
def test_bad_published_dynamics_name_the_argument(args, kwargs, message):
    with pytest.raises(ValueError, match=message):
        SoilDynamics.published(*args, **kwargs)


def _template_soil(lines: str) -> str:
    """The template with its four quake and damping lines replaced by ``lines``."""
    old = 'shaft_quake = "2.54 mm"\ntoe_quake = "2.54 mm"\nshaft_damping = 0.164\ntoe_damping = 0.492\n'
    assert old in TEMPLATE
    return TEMPLATE.replace(old, lines)


def test_spec_takes_a_parameter_set():
    spec = loads_spec(_template_soil('parameter_set = "grlweap"\nshaft_soil = "sand"\n'
                                     'toe_quake_rule = "very-dense-or-hard"\ntoe_diameter = "610 mm"\n'))
    assert spec.soil.dynamics == SoilDynamics(2.5e-3, 0.610 / 120, 0.16, 0.50, "smith")
    spec = loads_spec(_template_soil('parameter_set = "gec12"\nshaft_soil = "cohesive"\ntoe_quake = "0.1 in"\n'))
    assert spec.soil.dynamics.shaft_damping == pytest.approx(0.20 / FOOT, rel=1e-15)


@pytest.mark.parametrize("lines, message", [
    ('parameter_set = "gec12"\nshaft_soil = "cohesive"\n',
     "soil.toe_quake_rule: with a parameter_set give the toe quake rule or the toe_quake, got neither"),
    ('parameter_set = "gec12"\ntoe_quake = "1 mm"\n', "soil.shaft_soil: missing; the parameter_set 'gec12' gives"),
    ('parameter_set = "gec12"\nshaft_soil = "sand"\ntoe_quake = "1 mm"\n', "soil.shaft_soil: 'sand' is not a soil"),
    ('parameter_set = "grlweap"\nshaft_soil = "sand"\ntoe_quake_rule = "soft-or-loose"\n',
     "soil.toe_diameter: missing"),
    ('parameter_set = "grlweap"\nshaft_soil = "sand"\ntoe_quake_rule = "loose"\n',
     "soil.toe_quake_rule: 'loose' is not a toe quake rule"),
    ('parameter_set = "grlweap"\nshaft_soil = "sand"\ntoe_quake = "1 mm"\nshaft_damping = 0.2\n',
     "soil.shaft_damping: the parameter_set 'grlweap' gives it"),
    ('shaft_quake = "1 mm"\ntoe_quake = "1 mm"\nshaft_damping = 0.1\n', "soil.toe_damping: missing; give it, or"),
    ('shaft_quake = "1 mm"\ntoe_quake = "1 mm"\nshaft_damping = 0.1\ntoe_damping = 0.1\nshaft_soil = "sand"\n',
     "soil.shaft_soil: only with soil.parameter_set"),
])
def test_bad_parameter_set_specs_name_the_key(lines, message):
    with pytest.raises(ModelError, match=message):
        loads_spec(_template_soil(lines))


def test_parameter_set_keeps_smith_damping():
    spec = _template_soil('parameter_set = "grlweap"\nshaft_soil = "sand"\ntoe_quake = "1 mm"\n')
    with pytest.raises(ModelError, match="soil.damping_kind: the parameter_set 'grlweap' gives Smith damping"):
        loads_spec(spec.replace('damping_kind = "smith"', 'damping_kind = "case"'))
