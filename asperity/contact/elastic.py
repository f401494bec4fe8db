"""The elastic half-space: surface displacement u = K p of a pixel pressure field p.

Two boundary conditions (SPEC.md section 7):

* ``periodic`` -- the map is one period; in Fourier space u_q = 2 p_q / (E* |q|), the
  q = 0 term dropped (the mean displacement of a periodic half-space is undefined; the
  load control sets the approach).  The pixel values are samples of a band-limited field.
* ``free`` -- a non-periodic map on an unloaded half-space: the pressure is constant over
  each dx x dy pixel, and the displacement at a pixel centre due to a unit pressure on a
  rectangle centred (x, y) away is Love's (1929) closed form (Johnson, Contact Mechanics,
  eq. 3.25), written with asinh so that it is exact far from the rectangle too:

      K(x, y) = 1/(pi E*) sum over the corners (+-a, +-b), a = dx/2, b = dy/2, of
                +- F(x + s a, y + t b),   F(x, y) = x asinh(y/|x|) + y asinh(x/|y|)

  (sign + when s t = 1, - else; F(0, y) = y asinh(0) ... = 0 terms drop out).  The linear
  convolution over the nx x ny pixels is a cyclic one on a grid zero-padded to
  2nx x 2ny (DC-FFT, Liu, Wang & Liu, Wear 243, 2000).  K is even in x and y, so its
  spectrum is real and only its real part is kept (half the memory).

:class:`HalfSpace` applies K with scipy.fft (``workers`` threads): the free transform is
pruned (the zero half of the padded input and the unused half of the output are not
transformed along the second axis).  :func:`solver_bytes` is the memory a solve plans.
"""
from __future__ import annotations

import math

import numpy as np

BOUNDARIES = ("periodic", "free")
#: precision of the preconditioner's transforms (an approximate inverse serves as well)
PRECONDITIONER_DTYPE = np.float32

#: planned peak bytes per pixel of a solve (the solver's arrays, the transform's buffers
#: and the result; the caller's heights not counted): measured peaks 83 (periodic) and
#: 142 (free) bytes per pixel at 1024^2 with the preconditioner's array and its
#: single-precision transform (``asperity bench --only contact``), 8 more since the
#: solve works on a copy of the heights in its own length unit (tracemalloc: 70 -> 78 and
#: 114 -> 122), with a margin
BYTES_PER_PIXEL = {"periodic": 100, "free": 200}


def solver_bytes(shape, boundary: str) -> float:
    """Bytes of memory a solve of a map of ``shape`` plans to use at most."""
    return float(BYTES_PER_PIXEL[boundary]) * float(shape[0]) * float(shape[1])


def love_primitive(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """F(x, y) = x asinh(y/|x|) + y asinh(x/|y|), the primitive of 1/sqrt(x^2 + y^2) over
    a quadrant (terms in one variable only dropped: they cancel in the corner sum)."""
    ax = np.where(x == 0.0, 1.0, np.abs(x))
    ay = np.where(y == 0.0, 1.0, np.abs(y))
    return x * np.arcsinh(y / ax) + y * np.arcsinh(x / ay)


def love_coefficients(x: np.ndarray, y: np.ndarray, dx: float, dy: float,
                      E_star: float) -> np.ndarray:
    """Displacement at (x, y) from the centre of a dx x dy rectangle carrying unit
    pressure, on a half-space of effective modulus E_star (m/Pa)."""
    a, b = 0.5 * dx, 0.5 * dy
    s = (love_primitive(x + a, y + b) - love_primitive(x + a, y - b)
         - love_primitive(x - a, y + b) + love_primitive(x - a, y - b))
    return s / (math.pi * E_star)


class HalfSpace:
    """u = K p on an (nx, ny) grid of pixels dx x dy: ``apply(p, out)``.

    The spectrum of K is computed once (the periodic one is 2/(E*|q|) on the half
    spectrum; the free one the real FFT of Love's coefficients on the padded grid).
    """

    def __init__(self, shape, dx: float, dy: float, E_star: float, boundary: str,
                 workers: int | None = None):
        self.nx, self.ny = int(shape[0]), int(shape[1])
        self.dx, self.dy, self.E_star = float(dx), float(dy), float(E_star)
        self.boundary = boundary
        self.workers = workers
        if boundary == "periodic":
            self.kernel = self._periodic_spectrum()
        else:
            self.kernel = self._free_spectrum()
        #: displacement at a pixel under unit pressure on that pixel alone (m/Pa)
        self.self_compliance = self._self_compliance()
        self._inverse = None

    def precondition(self, g: np.ndarray, out: np.ndarray) -> np.ndarray:
        """``out`` = M ``g``, M the inverse of the periodic half-space on this grid:
        |q| E* / 2 in Fourier space, the mean (q = 0) dropped (Vollebregt's preconditioner,
        J. Comput. Phys. 257, 333, 2014; on a free map too, where it is an approximate
        inverse: any symmetric positive M keeps the iteration exact)."""
        import scipy.fft as sf
        w = self.workers
        if self._inverse is None:
            qx = 2 * np.pi * np.fft.fftfreq(self.nx, self.dx)
            qy = 2 * np.pi * np.fft.rfftfreq(self.ny, self.dy)
            m = np.empty((self.nx, qy.size))
            for i in range(self.nx):              # row by row: no (nx, ny) temporaries
                m[i] = np.sqrt(qx[i] * qx[i] + qy * qy) * (0.5 * self.E_star)
            self._inverse = m.astype(PRECONDITIONER_DTYPE)
        spec = sf.rfft2(g.astype(PRECONDITIONER_DTYPE), workers=w)
        spec *= self._inverse
        spec = sf.ifft(spec, axis=0, workers=w, overwrite_x=True)
        out[...] = sf.irfft(spec, n=self.ny, axis=1, workers=w, overwrite_x=True)
        return out

    # ------------------------------------------------------------------ spectra
    def _periodic_spectrum(self) -> np.ndarray:
        nx, ny = self.nx, self.ny
        qx = 2 * np.pi * np.fft.fftfreq(nx, self.dx)
        qy = 2 * np.pi * np.fft.rfftfreq(ny, self.dy)
        k = np.empty((nx, qy.size))
        for i in range(nx):                   # row by row: no (nx, ny) temporaries
            q = np.sqrt(qx[i] * qx[i] + qy * qy)
            with np.errstate(divide="ignore"):
                k[i] = 2.0 / (self.E_star * q)
        k[0, 0] = 0.0                          # q = 0 dropped: load control sets the mean
        return k

    def _free_spectrum(self) -> np.ndarray:
        import scipy.fft as sf
        nx, ny = self.nx, self.ny
        # offsets of the padded, cyclic grid: 0 .. nx, then -(nx - 1) .. -1 (even in x)
        ix = np.arange(2 * nx)
        ix = np.where(ix <= nx, ix, ix - 2 * nx) * self.dx
        iy = np.arange(2 * ny)
        iy = np.where(iy <= ny, iy, iy - 2 * ny) * self.dy
        g = np.empty((2 * nx, 2 * ny))
        for i in range(2 * nx):
            g[i] = love_coefficients(ix[i], iy, self.dx, self.dy, self.E_star)
        spec = sf.rfft2(g, workers=self.workers)
        del g
        return np.ascontiguousarray(spec.real)

    def _self_compliance(self) -> float:
        if self.boundary == "free":
            return float(love_coefficients(np.zeros(1), np.zeros(1), self.dx, self.dy,
                                           self.E_star)[0])
        # K at zero offset: the mean of the full spectrum (the half spectrum's inner
        # columns stand for two)
        k = self.kernel
        inner = k[:, 1:-1] if self.ny % 2 == 0 else k[:, 1:]
        total = k[:, 0].sum() + 2.0 * inner.sum() + (k[:, -1].sum() if self.ny % 2 == 0
                                                      and k.shape[1] > 1 else 0.0)
        return float(total / (self.nx * self.ny))

    # ------------------------------------------------------------------ K p
    def apply(self, p: np.ndarray, out: np.ndarray) -> np.ndarray:
        """``out`` = K ``p`` (both (nx, ny) float64; ``out`` may not be ``p``)."""
        import scipy.fft as sf
        w = self.workers
        if self.boundary == "periodic":
            spec = sf.rfft2(p, workers=w)
            spec *= self.kernel
            # axis by axis: pocketfft's two-dimensional c2r is 1.5 x slower (measured)
            spec = sf.ifft(spec, axis=0, workers=w, overwrite_x=True)
            out[...] = sf.irfft(spec, n=self.ny, axis=1, workers=w, overwrite_x=True)
            return out
        nx, ny = self.nx, self.ny
        a = sf.rfft(p, n=2 * ny, axis=1, workers=w)               # (nx, ny + 1)
        spec = sf.fft(a, n=2 * nx, axis=0, workers=w, overwrite_x=True)   # (2nx, ny + 1)
        del a
        spec *= self.kernel
        b = sf.ifft(spec, axis=0, workers=w, overwrite_x=True)[:nx]
        del spec
        out[...] = sf.irfft(b, n=2 * ny, axis=1, workers=w, overwrite_x=True)[:, :ny]
        return out
