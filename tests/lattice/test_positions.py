"""Node and element-centre positions of the lattice: the compiled kernel equals the numpy reference bit for bit,
and both equal the direct definition (rod's left end plus the lengths of the elements left of it)."""

import numpy as np
from hypothesis import given, settings, strategies as st

import rodimpact as ri
from rodimpact.lattice._kernels import positions, positions_numpy


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**31 - 1), counts=st.lists(st.integers(1, 40), min_size=1, max_size=4))
def test_compiled_positions_equal_the_numpy_reference(seed, counts):
    rng = np.random.default_rng(seed)
    length = rng.uniform(1e-4, 1e-1, size=sum(counts))
    rod_start = np.array([0, *np.cumsum(counts)], dtype=np.int64)
    offsets = np.cumsum(rng.uniform(-1.0, 1.0, size=len(counts)))
    node_x, element_x = positions(length, rod_start, offsets)
    ref_nodes, ref_elements = positions_numpy(length, rod_start, offsets)
    assert np.array_equal(node_x, ref_nodes) and np.array_equal(element_x, ref_elements)
    for r, off in enumerate(offsets):
        own = length[rod_start[r]:rod_start[r + 1]]
        nodes = node_x[rod_start[r] + r:rod_start[r + 1] + r + 1]
        np.testing.assert_allclose(nodes, off + np.r_[0.0, [own[:k + 1].sum() for k in range(own.size)]],
                                   rtol=0, atol=1e-12)
        np.testing.assert_allclose(element_x[rod_start[r]:rod_start[r + 1]], 0.5 * (nodes[:-1] + nodes[1:]),
                                   rtol=0, atol=1e-12)


def test_lattice_of_two_rods_in_contact_starts_at_minus_the_striker_length():
    striker = ri.Rod([ri.Cylinder(0.3, 0.02)])
    bar = ri.Rod([ri.Cylinder(1.0, 0.02), ri.Cylinder(0.5, 0.03)])
    lat = ri.build_lattice(ri.System([striker, bar], [1.0, 0.0], junctions=[ri.Contact(gap=1e-3)]), 1e-6)
    s, b = lat.node_index(0, 0), lat.node_index(1, 0)
    assert lat.node_x[s] == -0.3 and abs(lat.node_x[b] - 1e-3) < 1e-15
    assert abs(lat.node_x[-1] - (1e-3 + 1.5)) < 1e-12
