"""BC6H textures in DDS files (`photosolid texture -o OUT.dds`), read back as a user would:
OpenImageIO's DDS reader (half floats; it parses the container itself, and decodes the blocks
with bcdec in C, the same algorithm as the library's bcdec_rs port) and texture2ddecoder
(Perfare's Texture2DDecoder, a decoder written separately, 8-bit channels).

Checks, on the synthetic roadway (steep gradients, so BC6H's error is not trivially small):
- OpenImageIO reads the file as a BC6H (unsigned) texture of the rendered size;
- its texels' error against the float texture (the EXR of the same render) is the error the
  CLI prints for the DDS (max and RMS, % of I_max, to the printed 3 significant digits): the
  decoders agree on what the blocks hold;
- texture2ddecoder's 8-bit red channel is OpenImageIO's value x 255 to within rounding.

Needs PHOTOSOLID_BIN (the CLI binary), as scripts/python.sh sets it.
"""

from __future__ import annotations

import os
import re
import struct
import subprocess
from pathlib import Path

import numpy as np
import OpenImageIO as oiio
import pytest
import texture2ddecoder

ROOT = Path(os.environ.get("PHOTOSOLID_ROOT", Path(__file__).resolve().parents[2]))
BIN = os.environ.get("PHOTOSOLID_BIN", str(ROOT / "target" / "debug" / "photosolid"))


def run(*args: str, cwd: Path) -> str:
    return subprocess.run([BIN, *args], check=True, capture_output=True, text=True, cwd=cwd).stdout


def read_oiio(path: Path) -> tuple[np.ndarray, oiio.ImageSpec]:
    inp = oiio.ImageInput.open(str(path))
    assert inp is not None, oiio.geterror()
    spec = inp.spec()
    pixels = np.asarray(inp.read_image("float"))
    inp.close()
    return pixels, spec


@pytest.mark.parametrize("factor", ["1", "5"])
def test_dds_reads_back_in_two_independent_decoders(tmp_path: Path, factor: str):
    run("synth", "roadway", "-o", "road.ldt", cwd=tmp_path)
    run("texture", "road.ldt", "--backend", "cpu", "--factor", factor, "-o", "t.exr", cwd=tmp_path)
    out = run("texture", "road.ldt", "--backend", "cpu", "--factor", factor, "-o", "t.dds", cwd=tmp_path)
    m = re.search(r"max ([0-9.e+-]+) %, RMS ([0-9.e+-]+) % of I_max", out)
    assert m, out
    printed_max, printed_rms = float(m.group(1)), float(m.group(2))

    exr, _ = read_oiio(tmp_path / "t.exr")
    exr = exr[..., 0]
    dds, spec = read_oiio(tmp_path / "t.dds")
    assert spec.getattribute("compression") == "BC6HU", spec.getattribute("compression")
    assert (spec.height, spec.width) == exr.shape
    # The red channel holds I / I_max; green and blue repeat it.
    assert np.array_equal(dds[..., 0], dds[..., 1]) and np.array_equal(dds[..., 0], dds[..., 2])
    # The float texture clamps at 0 by default, so it is what BC6H_UF16 stores.
    assert exr.min() >= 0.0
    err = np.abs(dds[..., 0].astype(np.float64) - exr.astype(np.float64))
    e_max, e_rms = 100 * err.max(), 100 * np.sqrt((err**2).mean())
    assert e_max > 0.0, "BC6H is lossy: an error of exactly 0 means the texels were not compressed"
    assert e_max == pytest.approx(printed_max, rel=6e-3), (e_max, out)
    assert e_rms == pytest.approx(printed_rms, rel=6e-3), (e_rms, out)

    raw = (tmp_path / "t.dds").read_bytes()
    height, width = struct.unpack("<II", raw[12:20])
    assert (height, width) == exr.shape
    assert struct.unpack("<I", raw[128:132])[0] == 95  # DXGI_FORMAT_BC6H_UF16
    bgra = np.frombuffer(texture2ddecoder.decode_bc6(raw[148:], width, height), dtype=np.uint8)
    red = bgra.reshape(height, width, 4)[..., 2].astype(np.float64)
    assert np.abs(red - np.clip(dds[..., 0], 0.0, 1.0) * 255.0).max() <= 0.5 + 1e-6
