"""x3p archives (ISO 5436-2 / ISO 25178-72) written by the tests: ``main.xml`` and a binary
member or an inline ``DataList``, every option of the standard the reader must handle or
refuse.  Raw values go in as arrays ``[i, j]`` (i along x) and are written x fastest."""
from __future__ import annotations

import io
import zipfile

import numpy as np

DTYPES = {"I": "<i2", "L": "<i4", "F": "<f4", "D": "<f8"}
NS = "http://www.opengps.eu/2008/ISO5436_2"


def _axis(label, kind, code, inc, off) -> str:
    parts = [f"<AxisType>{kind}</AxisType>"]
    if code is not None:
        parts.append(f"<DataType>{code}</DataType>")
    if inc is not None:
        parts.append(f"<Increment>{inc}</Increment>")
    if off is not None:
        parts.append(f"<Offset>{off}</Offset>")
    return f"<{label}>{''.join(parts)}</{label}>"


def main_xml(*, nx, ny, code="D", feature="SUR", zinc=None, zoff=None, dx=1e-6, dy=2e-6,
             x_abs=None, y_abs=None, size_z=1, list_dim=None, rotation=None, data=None,
             valid=False, z_kind="A") -> str:
    """main.xml text; ``x_abs``/``y_abs``: (code, increment, offset) of an absolute axis;
    ``data``: the inner DataList text (None: a DataLink to bindata/data.bin)."""
    cx = _axis("CX", "A", *x_abs) if x_abs else _axis("CX", "I", "D", dx, 0)
    cy = _axis("CY", "A", *y_abs) if y_abs else _axis("CY", "I", "D", dy, 0)
    cz = _axis("CZ", z_kind, code, zinc, zoff)
    rot = ""
    if rotation is not None:
        rot = "<Rotation>" + "".join(f"<r{i + 1}{j + 1}>{rotation[i][j]}</r{i + 1}{j + 1}>"
                                     for i in range(3) for j in range(3)) + "</Rotation>"
    dim = (f"<ListDimension>{list_dim}</ListDimension>" if list_dim is not None else
           f"<MatrixDimension><SizeX>{nx}</SizeX><SizeY>{ny}</SizeY><SizeZ>{size_z}</SizeZ>"
           f"</MatrixDimension>")
    if data is None:
        vlink = ("<ValidPointsLink>bindata/valid.bin</ValidPointsLink>"
                 "<MD5ChecksumValidPoints>0</MD5ChecksumValidPoints>") if valid else ""
        body = (f"<DataLink><PointDataLink>bindata/data.bin</PointDataLink>"
                f"<MD5ChecksumPointData>0</MD5ChecksumPointData>{vlink}</DataLink>")
    else:
        body = f"<DataList>{data}</DataList>"
    return (f'<?xml version="1.0" encoding="UTF-8"?>\n<p:ISO5436_2 xmlns:p="{NS}">'
            f"<Record1><Revision>ISO5436 - 2000</Revision><FeatureType>{feature}</FeatureType>"
            f"<Axes>{cx}{cy}{cz}{rot}</Axes></Record1>"
            f"<Record2><Date>2024-01-01T00:00:00</Date></Record2>"
            f"<Record3>{dim}{body}</Record3>"
            f"<Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4></p:ISO5436_2>")


def _flat(a):
    return np.ascontiguousarray(np.asarray(a).T).ravel()      # x fastest


def x3p_bytes(z, *, code="D", inline=False, x=None, y=None, xcode="D", ycode="D",
              x_inc=None, y_inc=None, valid=None, members=None, compress=True, **xml) -> bytes:
    """An x3p archive of raw heights ``z[i, j]`` (NaN: a missing point, written as NaN in
    binary float data or as an empty Datum inline); absolute coordinates ``x``/``y``
    (raw, [i, j]) if given; ``valid``: bool [i, j] written as the valid-points member.
    ``members``: extra or replacing archive members {name: bytes}."""
    z = np.asarray(z, dtype=float)
    nx, ny = z.shape
    stored = []
    if x is not None:
        stored.append((_flat(x), xcode))
        xml["x_abs"] = (xcode, x_inc, None)
    if y is not None:
        stored.append((_flat(y), ycode))
        xml["y_abs"] = (ycode, y_inc, None)
    stored.append((_flat(z), code))
    out = {}
    if inline:
        cols = [[("" if np.isnan(v) else repr(float(v)) if c in "FD" else str(int(v)))
                 for v in vals] for vals, c in stored]
        data = "".join("<Datum/>" if any(t == "" for t in row) else
                       "<Datum>" + ";".join(row) + "</Datum>" for row in zip(*cols))
        out["main.xml"] = main_xml(nx=nx, ny=ny, code=code, data=data, **xml).encode()
    else:
        rec = np.dtype([(f"a{k}", DTYPES[c]) for k, (_, c) in enumerate(stored)])
        buf = np.zeros(nx * ny, dtype=rec)
        for k, (vals, c) in enumerate(stored):
            v = vals
            if c in "IL":
                v = np.nan_to_num(vals, nan=0.0)
            buf[f"a{k}"] = v
        out["main.xml"] = main_xml(nx=nx, ny=ny, code=code, valid=valid is not None,
                                   **xml).encode()
        out["bindata/data.bin"] = buf.tobytes()
        if valid is not None:
            out["bindata/valid.bin"] = np.packbits(_flat(valid).astype(bool),
                                                   bitorder="little").tobytes()
    out["md5checksum.hex"] = b"0" * 32
    out.update(members or {})
    b = io.BytesIO()
    with zipfile.ZipFile(b, "w", zipfile.ZIP_DEFLATED if compress else zipfile.ZIP_STORED) as zf:
        for k, v in out.items():
            if v is not None:
                zf.writestr(k, v)
    return b.getvalue()


def zeros_member(path, member: str, nbytes: int, main: str) -> None:
    """An archive whose ``member`` holds ``nbytes`` zero bytes, written in pieces (a small
    file that expands to ``nbytes``)."""
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as zf:
        zf.writestr("main.xml", main)
        with zf.open(member, "w", force_zip64=True) as fh:
            piece = bytes(1 << 24)
            left = nbytes
            while left > 0:
                fh.write(piece[:min(left, len(piece))])
                left -= len(piece)
