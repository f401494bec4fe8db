"""Reservoirs built by hand for the law tests."""
import numpy as np

from asperity.friction.reservoir import Reservoir


def reservoir(psi, p, contact="all-faces"):
    """A Reservoir of the points p (m, 2) at the directions psi (m,), none locked."""
    m = len(psi)
    return Reservoir(psi=np.asarray(psi, float), p=np.asarray(p, float), locked=np.zeros(m, bool),
                     locked_face=np.full(m, -1), set_valued=np.zeros(m, bool), contact=contact)


def grid(n):
    """n equally spaced directions over a full turn."""
    return 2 * np.pi * np.arange(n) / n
