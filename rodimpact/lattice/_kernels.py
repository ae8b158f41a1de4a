"""Kernels of the lattice layer: the reference positions of the nodes and element centres (compiled, with the
readable numpy path it is tested against)."""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def positions(length: np.ndarray, rod_start: np.ndarray, offsets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Reference positions (m) of the nodes (n_j + 1 per rod, rod by rod) and of the element centres of rods
    whose elements have the lengths ``length`` (all rods concatenated, ``rod_start[r]`` the first element of rod
    r) and whose left ends lie at ``offsets``: the rod's left end plus the running sum of its element lengths;
    an element's centre is its right node minus half its length. Sums in the order of :func:`positions_numpy`
    (bit-identical)."""
    n_rods = rod_start.size - 1
    node_x = np.empty(length.size + n_rods)
    element_x = np.empty(length.size)
    for r in range(n_rods):
        right = 0.0
        node_x[rod_start[r] + r] = offsets[r] + 0.0
        for j in range(rod_start[r], rod_start[r + 1]):
            right += length[j]
            node_x[j + r + 1] = offsets[r] + right
            element_x[j] = offsets[r] + right - 0.5 * length[j]
    return node_x, element_x


def positions_numpy(length: np.ndarray, rod_start: np.ndarray, offsets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The readable reference of :func:`positions`."""
    node_x, element_x = [], []
    for r, off in enumerate(offsets):
        own = length[rod_start[r]:rod_start[r + 1]]
        right = np.cumsum(own)
        node_x.append(off + np.concatenate([[0.0], right]))
        element_x.append(off + right - 0.5 * own)
    return np.concatenate(node_x), np.concatenate(element_x)
