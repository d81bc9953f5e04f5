"""Fixtures shared by the binding tests: a small catalogue holding every input ``photosolid batch`` reads."""

from __future__ import annotations

import os
import shutil
import subprocess
import zipfile
from pathlib import Path

import pytest

ROOT = Path(os.environ.get("PHOTOSOLID_ROOT", Path(__file__).resolve().parents[2]))
BIN = os.environ.get("PHOTOSOLID_BIN", str(ROOT / "target" / "debug" / "photosolid"))
DATA = ROOT / "data"

# A GLDF product with two photometries (ids ``road`` and ``bat``), as tests/it/gldf_tm33.rs writes it.
PRODUCT_XML = """<?xml version="1.0" encoding="UTF-8"?>
<Root>
<Header/>
<GeneralDefinitions>
<Files>
<File id="f1" contentType="ldc/eulumdat" type="localFileName">roadway.ldt</File>
<File id="f2" contentType="ldc/iesna" type="localFileName">batwing.ies</File>
</Files>
<Photometries>
<Photometry id="road"><PhotometryFileReference fileId="f1"/></Photometry>
<Photometry id="bat"><PhotometryFileReference fileId="f2"/></Photometry>
</Photometries>
</GeneralDefinitions>
</Root>
"""


def write_catalogue(d: Path) -> Path:
    """``d`` holding one file of each kind ``batch`` reads: .ies, .ldt (in a subfolder), a file without an
    extension read by content, a TM-33 document (written by ``photosolid convert``), a GLDF container with two
    photometries, and a text file ``batch`` passes over. Returns ``d``."""
    (d / "sub").mkdir(parents=True)
    shutil.copy(DATA / "isotropic.ies", d / "a.ies")
    shutil.copy(DATA / "lambertian.ldt", d / "sub" / "b.ldt")
    shutil.copy(DATA / "spot_p8_c40.ies", d / "no_extension")
    subprocess.run([BIN, "convert", str(DATA / "cosine_p5.ldt"), str(d / "c.xml")], check=True, capture_output=True)
    with zipfile.ZipFile(d / "lum.gldf", "w") as z:
        z.writestr("product.xml", PRODUCT_XML)
        z.write(DATA / "roadway.ldt", "ldc/roadway.ldt")
        z.write(DATA / "batwing.ies", "ldc/batwing.ies")
    (d / "notes.txt").write_text("not photometric\n")
    return d


@pytest.fixture()
def catalogue(tmp_path) -> Path:
    """A fresh :func:`write_catalogue` folder."""
    return write_catalogue(tmp_path / "cat")
