"""Surface files written by the tests: text matrices, meshes with degenerate triangles,
minimal x3p archives, gzipped copies."""
from __future__ import annotations

import gzip
import zipfile
from pathlib import Path

import numpy as np


def gz_copy(path: Path) -> Path:
    out = path.with_name(path.name + ".gz")
    out.write_bytes(gzip.compress(path.read_bytes()))
    return out


def write_matrix(path: Path, m: np.ndarray, header: str = "", sep: str = " "):
    lines = [sep.join(f"{v:.17g}" for v in row) for row in m]
    path.write_text(header + "\n".join(lines) + "\n", encoding="utf-8")


def mesh_with_degenerates():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 1], [2, 0, 0], [3, 0, 0]], float)
    f = np.array([[0, 1, 2], [1, 3, 2], [0, 1, 1],          # repeated vertex
                  [0, 1, 4], [1, 3, 4]])                    # collinear (zero area), good
    return v, f


def write_x3p(path: Path, z_raw: np.ndarray, dtype: str, *, inc="1e-6", off="<Offset/>",
         valid: np.ndarray | None = None, dx=1e-6, dy=2e-6):
    """A minimal x3p file; ``z_raw`` is (nx, ny), written x fastest."""
    nx, ny = z_raw.shape
    np_dt = {"I": "<i2", "L": "<i4", "F": "<f4", "D": "<f8"}[dtype]
    zinc = f"<Increment>{inc}</Increment>" if inc is not None else ""
    vlink = "<ValidPointsLink>bindata/valid.bin</ValidPointsLink>" if valid is not None else ""
    xml = f"""<?xml version="1.0" encoding="UTF-8"?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2">
 <Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType>
  <Axes>
   <CX><AxisType>I</AxisType><DataType>D</DataType><Increment>{dx}</Increment><Offset>0</Offset></CX>
   <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>{dy}</Increment><Offset>0</Offset></CY>
   <CZ><AxisType>A</AxisType><DataType>{dtype}</DataType>{zinc}{off}</CZ>
  </Axes></Record1>
 <Record2><Date>2024-01-01T00:00:00</Date></Record2>
 <Record3><MatrixDimension><SizeX>{nx}</SizeX><SizeY>{ny}</SizeY><SizeZ>1</SizeZ></MatrixDimension>
  <DataLink><PointDataLink>bindata/data.bin</PointDataLink>{vlink}</DataLink></Record3>
 <Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4>
</p:ISO5436_2>"""
    with zipfile.ZipFile(path, "w") as zf:
        zf.writestr("main.xml", xml)
        zf.writestr("bindata/data.bin", np.ascontiguousarray(z_raw.T).astype(np_dt).tobytes())
        if valid is not None:
            zf.writestr("bindata/valid.bin",
                        np.packbits(valid.T.ravel(), bitorder="little").tobytes())
        zf.writestr("md5checksum.hex", "0" * 32)
