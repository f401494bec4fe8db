"""NumPy height maps (``.npy``, ``.npz``).

The array is ``heights[i, j]`` (first index along x), in ``unit``, on a grid of spacing
``pixel_size``; both are required.  NaN marks undefined pixels.  A ``.npz`` holds the array
as ``heights`` (or as its only array) and optionally a boolean ``mask`` (True = undefined).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ...errors import InputError, TextureFileError
from ..topography import UNIT_HELP, HeightMap, finish_heightmap, one_line, pixel_pair, unit_factor


def load_array(data: bytes, suffix: str, name) -> np.ndarray:
    """A float array from .npy/.npz bytes, masked pixels (npz 'mask') as NaN."""
    import io
    try:
        obj = np.load(io.BytesIO(data), allow_pickle=False)
    except Exception as exc:
        raise TextureFileError(f"{name}: not a readable {suffix} file ({one_line(exc)})") from None
    if suffix == ".npz" or hasattr(obj, "files"):
        if not hasattr(obj, "files"):
            raise TextureFileError(f"{name}: not a .npz archive")
        keys = list(obj.files)
        arrays = [k for k in keys if k != "mask"]
        if "heights" in keys:
            key = "heights"
        elif len(arrays) == 1:
            key = arrays[0]
        else:
            raise TextureFileError(f"{name}: a .npz file needs an array named 'heights' "
                                   f"(found {', '.join(keys) or 'none'})")
        arr = obj[key]
        mask = obj["mask"] if "mask" in keys else None
    else:
        arr, mask = obj, None
    if arr.dtype.kind not in "biuf":
        raise TextureFileError(f"{name}: the array must hold real numbers, got dtype {arr.dtype}")
    arr = np.array(arr, dtype=np.float64)
    if mask is not None:
        mask = np.asarray(mask)
        if mask.shape != arr.shape or mask.dtype.kind not in "bi":
            raise TextureFileError(f"{name}: 'mask' must be a boolean array of the shape of "
                                   f"the heights {arr.shape}, got {mask.dtype} {mask.shape}")
        arr[mask.astype(bool)] = np.nan
    return arr


def read(data: bytes, *, suffix: str, gz: bool, name: Path, unit, pixel_size,
                height_scale: float) -> HeightMap:
    if unit is None or pixel_size is None:
        missing = " and ".join(k for k, v in (("unit", unit), ("pixel_size", pixel_size))
                               if v is None)
        raise InputError(f"{name}: a {suffix} height map carries no length unit or pixel size; "
                         f"pass {missing} (unit one of {UNIT_HELP}; pixel_size in that unit, "
                         f"a number or (dx, dy))")
    factor = unit_factor(unit)
    dx, dy = pixel_pair(pixel_size, factor)
    z = load_array(data, suffix, name)
    if z.ndim != 2:
        raise TextureFileError(f"{name}: a height map must be a 2-D array, got shape {z.shape}")
    return finish_heightmap(z * factor, dx, dy, name.name, height_scale, name)
