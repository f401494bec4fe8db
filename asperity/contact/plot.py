"""Pictures of a contact solution: the contact map and the pressure (``asperity contact
--plot``).  Height maps: two images on the map's own axes (x along axis 0, undefined
pixels blank), downsampled by whole strides to at most :data:`MAX_SIDE` points a side;
a wedge texture's profile (one period, uniform along the ridges): the profile with its
contact marked, and the pressure along it."""
from __future__ import annotations

import numpy as np

#: largest number of points drawn along a side (strided, not interpolated)
MAX_SIDE = 1024


def _stride(n: int) -> int:
    return max(1, -(-n // MAX_SIDE))


def _unit(length: float) -> tuple[float, str]:
    """(factor, name) of the length unit of the axes: um below 1 cm, else mm."""
    return (1e6, "um") if length < 1e-2 else (1e3, "mm")


def plot_contact(result, path, *, heights=None, title: str = "", profile: bool = False) -> None:
    """Draw ``result`` (a :class:`~asperity.contact.ContactResult`) to ``path``
    atomically; ``profile``: the map is a texture's profile (its first column is drawn,
    with ``heights`` the profile's)."""
    from ..io import pyplot, save_figure_atomic
    plt = pyplot()
    p = result.pressure
    dx, dy = result.pixel_size
    if profile:
        fig, (a0, a1) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
        f, unit = _unit(p.shape[0] * dx)
        x = np.arange(p.shape[0]) * dx * f
        z = heights[:, 0]
        a0.plot(x, z, color="0.4", lw=1, label="rigid surface")
        c = result.contact[:, 0]
        a0.plot(x, np.where(c, z, np.nan), color="C3", lw=2.5, label="in contact")
        a0.set_ylabel("height, m")
        a0.legend(loc="best", fontsize=8)
        a1.plot(x, p[:, 0], color="C0")
        a1.set_xlabel(f"x across the ridges, {unit} (one period)")
        a1.set_ylabel("pressure, Pa")
    else:
        sx, sy = _stride(p.shape[0]), _stride(p.shape[1])
        ps = p[::sx, ::sy]
        f, unit = _unit(max(p.shape[0] * dx, p.shape[1] * dy))
        extent = (0.0, p.shape[0] * dx * f, 0.0, p.shape[1] * dy * f)
        state = np.where(np.isnan(ps), np.nan, result.contact[::sx, ::sy].astype(float))
        fig, (a0, a1) = plt.subplots(1, 2, figsize=(11, 4.8))
        cmap = plt.get_cmap("Greys").with_extremes(bad="tab:orange")
        a0.imshow(state.T, origin="lower", extent=extent, cmap=cmap, vmin=0, vmax=1,
                  interpolation="nearest", aspect="equal")
        a0.set_title(f"contact (black; undefined: orange), area fraction "
                     f"{result.area_fraction:.4g}", fontsize=9)
        im = a1.imshow(ps.T, origin="lower", extent=extent, cmap="viridis",
                       interpolation="nearest", aspect="equal")
        fig.colorbar(im, ax=a1, label="pressure, Pa", shrink=0.85)
        a1.set_title(f"pressure, max {result.max_pressure:.4g} Pa", fontsize=9)
        for a in (a0, a1):
            a.set_xlabel(f"x, {unit}")
            a.set_ylabel(f"y, {unit}")
    H = "none" if result.hardness is None else f"{result.hardness:.3g} Pa"
    fig.suptitle(f"{title}\np = {result.mean_pressure:.4g} Pa, E* = {result.E_star:.4g} Pa, "
                 f"boundary {result.boundary}, hardness {H}", fontsize=9)
    fig.tight_layout()
    save_figure_atomic(fig, path, dpi=110)
    plt.close(fig)
