"""Where a friction computation starts: a wedge-texture file or a surface file."""
from __future__ import annotations

import os


def is_texture_file(path: str) -> bool:
    return str(path).lower().endswith(".toml")


def load_texture_or_surface(path):
    """A wedge texture (TOML) or a surface file, with the surface defaults."""
    if isinstance(path, (str, os.PathLike)) and is_texture_file(str(path)):
        from ..texture.wedges import load_texture
        return load_texture(path)
    from ..surface.facets import load_surface
    return load_surface(path)
