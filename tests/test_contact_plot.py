"""The contact figures show the map at its physical size: the images span n dx by m dy in
the unit their axes name (um below 1 cm, mm above), the profile's x runs over the profile's
length, and every line drawn is visible."""
from __future__ import annotations

import numpy as np
import pytest

from asperity import io
from asperity.contact import solve_contact
from asperity.contact.bench import self_affine
from asperity.contact.plot import plot_contact

E = 1e11


@pytest.fixture
def drawn(monkeypatch):
    """The figure plot_contact draws, instead of a file."""
    figs = []
    monkeypatch.setattr(io, "save_figure_atomic", lambda fig, path, **kw: figs.append(fig))
    return figs


def solved(n, m, dx, dy):
    z = self_affine(n, m, dx=dx, dy=dy, seed=2)
    return solve_contact(z, (dx, dy), E, 0.004 * E), z


@pytest.mark.parametrize("n,m,dx,dy,unit,f", [
    (40, 24, 1e-6, 2.5e-6, "um", 1e6),         # 40 x 60 um
    (24, 40, 1e-3, 0.4e-3, "mm", 1e3),         # 24 x 16 mm
])
def test_map_images_span_the_map_in_the_named_unit(drawn, tmp_path, n, m, dx, dy, unit, f):
    res, _ = solved(n, m, dx, dy)
    plot_contact(res, tmp_path / "c.png")
    (fig,) = drawn
    images = [im for ax in fig.axes for im in ax.get_images()]
    assert len(images) == 2
    for im in images:
        np.testing.assert_allclose(im.get_extent(), (0, n * dx * f, 0, m * dy * f), rtol=1e-12)
    labels = [ax.get_xlabel() for ax in fig.axes if ax.get_images()]
    assert labels == [f"x, {unit}"] * 2


def test_profile_runs_over_the_profile_and_every_line_shows(drawn, tmp_path):
    n, dx = 48, 2e-6
    res, z = solved(n, 8, dx, dx)
    plot_contact(res, tmp_path / "p.png", heights=z, profile=True)
    (fig,) = drawn
    lines = [ln for ax in fig.axes for ln in ax.get_lines()]
    assert len(lines) == 3
    for ln in lines:
        assert ln.get_linewidth() > 0 and ln.get_visible()
        np.testing.assert_allclose(ln.get_xdata(), np.arange(n) * dx * 1e6, rtol=1e-12)
    assert fig.axes[-1].get_xlabel().startswith("x across the ridges, um")
