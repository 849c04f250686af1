"""Spur single-pair stiffness along the path of contact and load sharing in the double-contact zones.

References: ISO 6336-1:2006 §9 — c' is the maximum single-pair tooth stiffness per unit face width, reached in the
single-contact zone near the pitch point for spur gears (the Weber/Banaschek single-pair stiffness curve has its
maximum near the middle of the path and falls towards both ends, where one tooth is loaded at its tip); method B
values from efficiency.iso6336 (c'_th with C_M = 0.8, C_R = 1, C_B from the basic rack). FZG C (gear_cases.md) at
200 N·m.
"""

import math

import numpy as np
import pytest

from efficiency import iso6336
from efficiency.geometry import GearPair
from efficiency.mesh_cycle import MeshOptions, evaluate_mesh

DEG = math.pi / 180


@pytest.fixture(scope="module")
def spur_c_cycle():
    pair = GearPair(16, 24, 4.5e-3, 20 * DEG, 0.0, 0.014, 0.1817, 0.1715, center_distance=0.0915)
    mesh = evaluate_mesh(pair, 200.0, 157.0, options=MeshOptions(positions=200, slices=4, outputs=frozenset()))
    kin = mesh.kinematics
    lines = kin.in_contact.any(axis=2)
    single = lines.sum(axis=1) == 1
    roll = np.array([kin.roll[m][kin.in_contact[m]].mean() for m in range(kin.shape[0])])
    xi = (roll - kin.contact_start) / (kin.contact_end - kin.contact_start)
    return pair, mesh, lines, single, xi


def test_single_pair_stiffness_peaks_near_the_pitch_point_at_isos_c_prime(spur_c_cycle):
    pair, mesh, _, single, xi = spur_c_cycle
    per_width = mesh.mesh_stiffness / float(pair.face_width)
    c_prime = iso6336.reference_values(pair, 200.0)["c_single_n_per_m2"]
    peak = per_width[single].max()
    xi_pitch = (float(pair.pitch_point) - float(pair.contact_start)) / float(pair.path_of_contact)
    assert peak == pytest.approx(c_prime, rel=0.15)  # measured 11.20 against 12.31 N/(mm·µm): −9 %
    assert abs(xi[single][np.argmax(per_width[single])] - xi_pitch) < 0.1
    # concave: the single-pair stiffness is lower at both ends of the single-contact zone than at its peak
    ends = per_width[single][[np.argmin(xi[single]), np.argmax(xi[single])]]
    assert np.all(ends < peak)


def test_double_contact_sharing_conserves_load_and_the_entering_pair_takes_less(spur_c_cycle):
    _, mesh, lines, single, xi = spur_c_cycle
    shares = mesh.loads.sum(axis=2) / mesh.normal_load
    np.testing.assert_allclose(shares.sum(axis=1), 1.0, rtol=1e-9)
    double = np.flatnonzero(~single)
    entering = []
    for m in double:
        k = np.flatnonzero(lines[m])
        first = k[np.argmin([mesh.kinematics.roll[m, j, 0] for j in k])]  # the pair nearest the path start
        entering.append((xi[m], shares[m, first]))
    entering = np.array(sorted(entering))
    early = entering[entering[:, 0] < 0.05]
    # at the start of the path the entering pair (tip of gear 2) is the most compliant: less than half the load
    assert np.all(early[:, 1] < 0.5)
    assert np.all(early[:, 1] > 0.3)  # measured 0.42
    # and its share grows through the zone as its contact moves down the tip of gear 2
    zone = entering[entering[:, 0] < 0.3]
    assert np.all(np.diff(zone[:, 1]) > 0)
