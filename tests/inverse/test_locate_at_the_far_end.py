"""A position at the far end of a long struck rod: the lattice's node positions are cumulative sums of ~40,000
element lengths, whose rounding (1e-12 relative here) put the located node beyond the rod's geometry, so the
direct solver refused a probe there ("must lie within rod 0, 0 <= x <= 2 m, got 2 m"). The node is kept inside."""

import warnings

import numpy as np

import rodimpact as ri
from rodimpact.inverse import percussion_drilling_example
from rodimpact.inverse.struck import locate, position_probe


def test_the_far_end_node_is_inside_the_rod_and_can_be_probed():
    n = 10_000
    ex = percussion_drilling_example(n)
    dt = 0.5 / n / ri.STEEL.wave_speed                   # a time step that smears the 5 mm segments
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        system = ex.struck_system
        loc = locate(system, ex.options["position"], dt)
        length = system.rods[loc.rod].length
        assert loc.local <= length
        assert loc.node == ri.build_lattice(system, dt).rod_start[loc.rod + 1]      # the rod's last node
        res = ri.simulate(ri.Problem.of(system, steps=2, dt=dt, outputs=ri.Outputs(probes=[position_probe(loc)]),
                                        allow_discretization_error=True))
    assert np.all(res.probe("synthesis_position").force == 0.0)      # no wave has arrived at the far end
