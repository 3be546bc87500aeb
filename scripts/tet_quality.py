"""Tetrahedron measures shared by scripts/mesh_quality and scripts/make_scene."""
import numpy as np


def signed_volumes(P):
    """P: (n, 4, 3) corner coordinates; the signed volumes (positive: gmsh's orientation)."""
    a, b, c = P[:, 1] - P[:, 0], P[:, 2] - P[:, 0], P[:, 3] - P[:, 0]
    return np.einsum("ij,ij->i", a, np.cross(b, c)) / 6


def skewness(P):
    """Volume skewness 1 - V / V_regular(circumradius), the measure of the ALE checks and of the
    paper (0: regular, 1: flat)."""
    a, b, c = P[:, 1] - P[:, 0], P[:, 2] - P[:, 0], P[:, 3] - P[:, 0]
    V = np.abs(signed_volumes(P))
    rhs = 0.5 * np.stack([(a * a).sum(1), (b * b).sum(1), (c * c).sum(1)], 1)
    R = np.linalg.norm(np.linalg.solve(np.stack([a, b, c], 1), rhs[..., None])[..., 0], axis=1)
    return 1 - V / (8 * np.sqrt(3) / 27 * R**3)
