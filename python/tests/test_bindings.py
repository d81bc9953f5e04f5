"""The Python bindings against the CLI: every value equals the CLI's JSON (or its files, read with independent
readers: OpenImageIO for the EXR, trimesh for the solid, pyarrow for the Parquet table), arrays have the
documented shapes, dtypes and units, errors carry path/line/message.

Needs PHOTOSOLID_BIN (the CLI binary) and PHOTOSOLID_ROOT (the repository), as scripts/python.sh sets them.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq
import pytest

import photosolid

ROOT = Path(os.environ.get("PHOTOSOLID_ROOT", Path(__file__).resolve().parents[2]))
BIN = os.environ.get("PHOTOSOLID_BIN", str(ROOT / "target" / "debug" / "photosolid"))
DATA = ROOT / "data"
FILES = sorted(p for p in DATA.iterdir() if p.suffix in (".ies", ".ldt"))


def cli_json(*args: str):
    out = subprocess.run([BIN, *args], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_grid_and_photometry_equal_the_cli(path: Path):
    lum = photosolid.load(path)
    grid = cli_json("grid", str(path))
    assert lum.c_deg.dtype == np.float64 and lum.c_deg.shape == (len(grid["c_deg"]),)
    assert lum.gamma_deg.shape == (len(grid["gamma_deg"]),)
    assert lum.candela.shape == (lum.c_deg.size, lum.gamma_deg.size)
    np.testing.assert_array_equal(lum.c_deg, grid["c_deg"])
    np.testing.assert_array_equal(lum.gamma_deg, grid["gamma_deg"])
    np.testing.assert_array_equal(lum.candela, np.array(grid["cd"]))
    assert lum.symmetry == grid["symmetry"]
    # The same serialiser on both sides: the dicts are equal, key for key.
    assert lum.photometry() == cli_json("info", str(path), "--json")


def test_sample_reproduces_the_measurements_and_directions_agree():
    lum = photosolid.load(DATA / "roadway.ldt")
    c, g = np.meshgrid(lum.c_deg, lum.gamma_deg, indexing="ij")
    # Interpolating filters return the measured values at the measured angles (cd), with the input's shape.
    for f in ("bilinear", "catmull-rom", "pchip"):
        v = lum.sample(f, c, g)
        assert v.shape == c.shape and v.dtype == np.float64
        np.testing.assert_allclose(v, lum.candela, rtol=0, atol=1e-9 * lum.candela.max())
    # sample_dirs in the luminaire frame: +x = C0, +y = C90, -z = nadir; any length.
    rng = np.random.default_rng(7)
    cs, gs = rng.uniform(0, 360, 500), rng.uniform(0, 180, 500)
    cr, gr = np.radians(cs), np.radians(gs)
    dirs = np.stack([np.sin(gr) * np.cos(cr), np.sin(gr) * np.sin(cr), -np.cos(gr)], axis=1) * 3.0
    a = lum.sample_dirs("catmull-rom", dirs)
    b = lum.sample("catmull-rom", cs, gs)
    assert a.shape == (500,)
    np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-9 * lum.candela.max())
    with pytest.raises(ValueError, match="shape"):  # (2,) against (1,) broadcasts; (2,) against (3,) does not
        lum.sample("bilinear", [0.0, 1.0], [0.0, 1.0, 2.0])
    with pytest.raises(ValueError, match="filter"):
        lum.sample("no-such-filter", [0.0], [0.0])


def test_texture_equals_the_cli_exr(tmp_path: Path):
    import OpenImageIO as oiio

    path = DATA / "batwing.ldt"
    exr = tmp_path / "t.exr"
    subprocess.run([BIN, "texture", str(path), "--filter", "pchip", "--factor", "2", "-o", str(exr)],
                   check=True, capture_output=True)
    ours = photosolid.load(path).texture("pchip", 2)
    assert ours.dtype == np.float32
    inp = oiio.ImageInput.open(str(exr))
    theirs = inp.read_image(format="float")[:, :, 0]
    inp.close()
    assert ours.shape == theirs.shape
    np.testing.assert_array_equal(ours, theirs)


def test_texture_backends_equal_the_cli(tmp_path: Path):
    """``backend`` is ``--backend``: the GPU's texture (on the adapter WGPU_BACKEND picks) equals the CLI's with
    ``--backend gpu`` texel for texel and the CPU's within f32 rounding; without an adapter both refuse ``gpu``."""
    import OpenImageIO as oiio

    path = DATA / "batwing.ldt"
    lum = photosolid.load(path)
    cpu = lum.texture("catmull-rom", 2, backend="cpu")
    exr = tmp_path / "gpu.exr"
    r = subprocess.run([BIN, "texture", str(path), "--factor", "2", "--backend", "gpu", "-o", str(exr)],
                       capture_output=True, text=True)
    if r.returncode != 0:
        with pytest.raises(photosolid.PhotosolidError) as caught:
            lum.texture("catmull-rom", 2, backend="gpu")
        assert caught.value.code in r.stderr, (caught.value.code, r.stderr)
        return
    gpu = lum.texture("catmull-rom", 2, backend="gpu")
    inp = oiio.ImageInput.open(str(exr))
    theirs = inp.read_image(format="float")[:, :, 0]
    inp.close()
    np.testing.assert_array_equal(gpu, theirs)
    assert gpu.shape == cpu.shape
    assert np.max(np.abs(gpu - cpu)) <= 1e-5 * np.max(cpu), np.max(np.abs(gpu - cpu))
    with pytest.raises(ValueError, match="backend"):
        lum.texture(backend="tpu")


def test_mesh_goes_into_trimesh_and_equals_the_cli(tmp_path: Path):
    import trimesh

    path = DATA / "spot_p8_c40.ies"
    v, f = photosolid.load(path).mesh("bilinear", 3)
    assert v.shape[1] == 3 and f.shape[1] == 3 and f.dtype == np.int64
    m = trimesh.Trimesh(v, f, process=False)
    cli = cli_json("mesh", str(path), "--filter", "bilinear", "--factor", "3", "-o", str(tmp_path / "s.ply"),
                   "--json")
    assert len(f) == cli["triangles"]
    # Volume (cd^3) by trimesh's own formula on our arrays against the CLI's: f32 vertices, relative 1e-5.
    assert m.volume == pytest.approx(cli["volume"], rel=1e-5)
    assert m.area == pytest.approx(cli["area"], rel=1e-5)


def test_fit_and_compare_equal_the_cli():
    path = DATA / "cosine_p5.ldt"
    lum = photosolid.load(path)
    assert lum.fit() == cli_json("fit", str(path), "--json")
    with pytest.warns(UserWarning, match="ignored|withheld reference"):  # directions: no effect on withheld
        ours = lum.compare(recons=["bilinear", "catmull-rom"], against="withheld", directions="dense:2000")
    theirs = cli_json("compare", str(path), "--recon", "bilinear,catmull-rom", "--against", "withheld",
                      "--directions", "dense:2000", "--json")
    assert ours["reference"] == theirs["reference"]
    assert [r["name"] for r in ours["results"]] == [r["name"] for r in theirs["results"]]
    # Everything but the timings (measured anew on each run) is equal.
    for a, b in zip(ours["results"], theirs["results"]):
        for k in a:
            if "time" not in k and "pareto" not in k:
                assert a[k] == b[k], k
    assert ours["smallest_within_1pct"] == theirs["smallest_within_1pct"]


def test_compare_names_the_smallest_within_1pct():
    """`smallest_within_1pct` of `compare` follows its rule on the rows it returns:
    the fewest bytes with radial max <= 1 % (ties: the smaller error), else None."""
    lum = photosolid.load(DATA / "cosine_p5.ldt")
    c = lum.compare(recons=["bilinear", "sh:2", "lobes:1", "fitted-gl"], directions="dense:2000", factor=1)
    within = [r for r in c["results"] if r["radial_max_pct"] <= 1.0]
    want = min(within, key=lambda r: (r["bytes"], r["radial_max_pct"]))["name"] if within else None
    assert c["smallest_within_1pct"] == want
    assert want is not None  # a cos^5 lobe is one lobe: lobes:1 (20 bytes) is exact
    none = lum.compare(recons=["sh:2"], directions="dense:2000", factor=1)
    assert none["results"][0]["radial_max_pct"] > 1.0
    assert none["smallest_within_1pct"] is None


def test_errors_carry_path_line_and_message(tmp_path: Path):
    bad = tmp_path / "bad.ies"
    bad.write_text("IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 x\n")
    with pytest.raises(photosolid.PhotosolidError) as e:
        photosolid.load(bad)
    assert e.value.path == str(bad)
    assert e.value.line == 3
    assert e.value.code == "invalid"
    assert str(bad) in e.value.message and str(e.value) == e.value.message
    with pytest.raises(photosolid.PhotosolidError) as e:
        photosolid.load(tmp_path / "missing.ldt")
    assert e.value.code == "io" and e.value.line is None and e.value.path.endswith("missing.ldt")


def test_batch_equals_the_cli_table(tmp_path: Path):
    work = tmp_path / "files"
    shutil.copytree(DATA, work, ignore=shutil.ignore_patterns("*.toml"))
    (work / "broken.ldt").write_text("not eulumdat\n")
    table = photosolid.batch([work])
    subprocess.run([BIN, "batch", str(work), "-o", str(tmp_path / "t.parquet")], check=True, capture_output=True)
    cli = pq.read_table(tmp_path / "t.parquet")
    assert table.schema == cli.schema
    assert table.num_rows == len(FILES) + 1
    timing = {"parse_ms", "holdout_ms", "fit_ms", "compact_ms"}
    for name in table.column_names:
        if name not in timing:
            assert table[name].to_pylist() == cli[name].to_pylist(), name
    rows = {r["path"]: r for r in table.to_pylist()}
    broken = rows[str(work / "broken.ldt")]
    assert broken["ok"] is False and broken["errors"] and broken["flux_lm"] is None
    # Units as documented: flux in lm equal to info --json, angles in degrees, errors in % of I_max.
    info = cli_json("info", str(work / "roadway.ldt"), "--json")
    assert rows[str(work / "roadway.ldt")]["flux_lm"] == info["flux_lm"]


def test_batch_compact_equals_the_cli(tmp_path: Path):
    """``compact=True`` is ``batch --compact``: the same ``smallest_within_1pct`` per file, each measured."""
    work = tmp_path / "files"
    shutil.copytree(DATA, work, ignore=shutil.ignore_patterns("*.toml"))
    table = photosolid.batch(work, compact=True)
    out = tmp_path / "t.parquet"
    subprocess.run([BIN, "batch", str(work), "-o", str(out), "--compact"], check=True, capture_output=True)
    cli = pq.read_table(out)
    assert table.schema == cli.schema
    assert table["smallest_within_1pct"].to_pylist() == cli["smallest_within_1pct"].to_pylist()
    ok = [r for r in table.to_pylist() if r["ok"] and not r["errors"]]
    assert ok and all(r["compact_ms"] is not None and r["compact_ms"] > 0 for r in ok)
    plain = photosolid.batch(work)
    assert all(v is None for v in plain["compact_ms"].to_pylist())


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_full_grid_equals_grid_full(path: Path):
    c, g, cd = photosolid.load(path).full_grid()
    ref = cli_json("grid", str(path), "--full")
    np.testing.assert_array_equal(c, ref["c_deg"])
    np.testing.assert_array_equal(g, ref["gamma_deg"])
    np.testing.assert_array_equal(cd, np.array(ref["cd"]))


def test_list_inputs_is_what_batch_reads(catalogue, tmp_path):
    """``list_inputs`` lists what ``photosolid batch`` reads, in its order: every format, a file without an
    extension read by content, a TM-33 document, one ``FILE#ID`` per photometry of a GLDF container; the Dask
    recipe shards exactly that list. ``list_files`` is the same function under its earlier name."""
    import importlib.util

    d = catalogue
    subprocess.run([BIN, "batch", str(d), "-o", str(tmp_path / "cli.parquet")], check=True, capture_output=True)
    cli = pq.read_table(tmp_path / "cli.parquet")["path"].to_pylist()
    listed = photosolid.list_inputs([d])
    assert listed == cli
    assert photosolid.list_files([d]) == listed
    assert any(p.endswith("no_extension") for p in listed) and any(p.endswith("c.xml") for p in listed)
    assert sorted(p.rsplit("/", 1)[-1] for p in listed if ".gldf" in p) == ["lum.gldf#bat", "lum.gldf#road"]
    assert not any(p.endswith("notes.txt") for p in listed)
    assert len(listed) == 6
    spec = importlib.util.spec_from_file_location("dask_batch", ROOT / "python" / "examples" / "dask_batch.py")
    dask_batch = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(dask_batch)
    assert dask_batch.list_files([d]) == cli
    table = photosolid.batch(listed)
    assert table["path"].to_pylist() == cli
    assert all(table["ok"].to_pylist()), table.to_pylist()


def _flux(lum):
    """A module-level function a process pool can pickle: the luminaire's total flux (lm)."""
    return lum.photometry()["flux_lm"]


def test_luminaires_pickle_copy_and_travel(catalogue, tmp_path):
    """A luminaire pickles (its path and source bytes; parsed again where no file is), deep-copies and goes
    through a process pool; the round trip is equal, with the same arrays and numbers. Its arrays are
    read-only."""
    import concurrent.futures
    import copy
    import multiprocessing
    import pickle

    own = tmp_path / "own.ies"
    shutil.copy(DATA / "batwing.ies", own)
    lums = [photosolid.load(p) for p in photosolid.list_inputs([catalogue])] + [photosolid.load(own)]
    blobs = [pickle.dumps(lum) for lum in lums]
    own.unlink()  # the file is gone: the pickle carries what the luminaire was read from
    shutil.rmtree(catalogue)
    for lum, blob in zip(lums, blobs):
        back = pickle.loads(blob)
        assert back == lum and back.path == lum.path and hash(back) == hash(lum)
        np.testing.assert_array_equal(back.candela, lum.candela)
        np.testing.assert_array_equal(back.c_deg, lum.c_deg)
        assert back.photometry() == lum.photometry()
        assert copy.deepcopy(lum) == lum and copy.copy(lum) == lum
    assert lums[0] != lums[1]
    with concurrent.futures.ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")) as pool:
        assert list(pool.map(_flux, lums)) == [_flux(lum) for lum in lums]
    lum = lums[-1]
    for name in ("candela", "c_deg", "gamma_deg"):
        a = getattr(lum, name)
        assert not a.flags.writeable, name
    with pytest.raises(ValueError):
        lum.candela[0, 0] = -999.0
    assert lum.candela.copy().flags.writeable


@pytest.mark.parametrize("recon", ["catmull-rom", "measured", "fitted-gl", "lobes:3", "sh:4",
                                   "catmull-rom@x2/bilinear", "bilinear+gamma:0-90"])
def test_fields_are_built_once_and_answer_as_sample(recon):
    """``Luminaire.field(recon)`` answers as ``sample``/``sample_dirs`` on a fresh luminaire (whose first call
    builds the reconstruction), and a second ``sample`` on the same luminaire (which looks it up) answers the same."""
    path = DATA / "batwing.ies"
    lum = photosolid.load(path)
    c = np.array([0.0, 45.0, 90.0, 200.0, 359.5])
    g = np.array([0.0, 30.0, 60.0, 90.0, 150.0])
    fresh = photosolid.load(path).sample(recon, c, g)
    field = lum.field(recon)
    assert field.name == recon
    np.testing.assert_array_equal(field.sample(c, g), fresh)
    np.testing.assert_array_equal(lum.sample(recon, c, g), fresh)
    dirs = np.array([[0.0, 0.0, -1.0], [1.0, 0.0, -1.0], [0.0, 1.0, 0.2]])
    np.testing.assert_array_equal(field.sample_dirs(dirs), photosolid.load(path).sample_dirs(recon, dirs))
    for k in range(len(c)):  # one point at a time, as a loop over single calls would
        assert lum.sample(recon, c[k:k + 1], g[k:k + 1])[0] == fresh[k]


def test_field_names_are_checked():
    lum = photosolid.load(DATA / "batwing.ies")
    with pytest.raises(ValueError):
        lum.field("no-such-filter")


def test_errors_are_the_builtins_python_users_catch(tmp_path):
    """A missing file is a FileNotFoundError, a malformed file a ValueError, an unsupported one a
    NotImplementedError; each is still a PhotosolidError with its code, path and line."""
    with pytest.raises(FileNotFoundError) as e:
        photosolid.load(tmp_path / "missing.ies")
    assert isinstance(e.value, photosolid.PhotosolidError) and e.value.code == "io"
    assert e.value.path.endswith("missing.ies") and str(e.value) == e.value.message
    bad = tmp_path / "bad.ies"
    bad.write_text("IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 x\n")
    with pytest.raises(ValueError) as e:
        photosolid.load(bad)
    assert isinstance(e.value, photosolid.PhotosolidValueError) and (e.value.code, e.value.line) == ("invalid", 3)
    utf16 = tmp_path / "utf16.ies"
    utf16.write_bytes("IESNA:LM-63-2002\nTILT=NONE\n".encode("utf-16"))
    with pytest.raises(NotImplementedError) as e:
        photosolid.load(utf16)
    assert isinstance(e.value, photosolid.PhotosolidError) and e.value.code == "unsupported"
    lum = photosolid.load(DATA / "batwing.ies")
    with pytest.raises(ValueError) as e:  # a value outside its domain, from the library
        lum.compare(recons="bilinear", against="withheld", folds=1, directions="dense:200", factor=1)
    assert isinstance(e.value, photosolid.PhotosolidError) and e.value.code == "model"


def test_bad_arguments_name_the_argument_in_python_words():
    """No Rust type names: negative counts are ValueErrors naming the argument, recons takes a string or a list,
    dirs of the wrong shape say the shape expected."""
    lum = photosolid.load(DATA / "batwing.ies")
    for call, words in [
        (lambda: lum.fit(max_lights=-1), "max_lights = -1"),
        (lambda: lum.fit(max_lights=3), "max_lights = 3"),
        (lambda: lum.texture(factor=-1), "factor = -1"),
        (lambda: lum.mesh(factor=0), "factor = 0"),
        (lambda: lum.sample_dirs("bilinear", [[0.0, 0.0]]), "expected (N, 3)"),
        (lambda: lum.sample("bilinear", [1.0, 2.0], [1.0, 2.0, 3.0]), "do not broadcast"),
    ]:
        with pytest.raises(ValueError) as e:
            call()
        assert words in str(e.value), str(e.value)
        assert not any(w in str(e.value) for w in ("usize", "Vec", "dimensionality mismatch", "integral type"))
    with pytest.raises(TypeError) as e:
        lum.compare(recons=3)
    assert "recons = 3" in str(e.value)
    one = lum.compare(recons="bilinear", directions="dense:200", factor=1)
    listed = lum.compare(recons=["bilinear"], directions="dense:200", factor=1)
    assert [r["name"] for r in one["results"]] == [r["name"] for r in listed["results"]] == ["bilinear"]


def test_angles_broadcast_and_nan_is_refused():
    """c_deg and gamma_deg broadcast as numpy does; NaN or infinity is refused in sample and sample_dirs alike;
    one direction (3,) gives a 0-d result."""
    lum = photosolid.load(DATA / "batwing.ies")
    c = np.array([0.0, 30.0, 90.0, 180.0])
    full = lum.sample("bilinear", np.repeat(c, 3).reshape(4, 3), np.tile([10.0, 40.0, 70.0], (4, 1)))
    np.testing.assert_array_equal(lum.sample("bilinear", c[:, None], np.array([10.0, 40.0, 70.0])), full)
    scalar_gamma = lum.sample("bilinear", c, 40.0)
    assert scalar_gamma.shape == (4,)
    np.testing.assert_array_equal(scalar_gamma, full[:, 1])
    for bad in (np.nan, np.inf):
        with pytest.raises(ValueError, match="finite"):
            lum.sample("bilinear", [bad], [0.0])
        with pytest.raises(ValueError, match="finite"):
            lum.sample("bilinear", [0.0], [bad])
        with pytest.raises(ValueError, match="finite"):
            lum.sample_dirs("bilinear", [[0.0, bad, -1.0]])
    one = lum.sample_dirs("bilinear", [0.0, 0.0, -1.0])
    assert one.shape == () and float(one) == lum.sample_dirs("bilinear", [[0.0, 0.0, -1.0]])[0]


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_texture_shape_is_the_documented_one(path: Path):
    """``texture(factor=K)`` has shape (K R, K P): R the mean measured gamma steps in 180 degrees, P the planes
    of ``full_grid()``, as the docstring says."""
    lum = photosolid.load(path)
    g = lum.gamma_deg
    steps = max(1, round(180 * (g.size - 1) / (g.max() - g.min()))) if g.size >= 2 else 1
    planes = lum.full_grid()[0].size
    for k in (1, 3):
        assert lum.texture(factor=k).shape == (k * steps, k * planes)


DUPLICATED_GAMMA = """IESNA:LM-63-2002
[TEST] duplicated gamma
TILT=NONE
1 1000 1 4 1 1 2 0 0 0
1 1 10
0 45 45 90
0
100 80 80 50
"""


def test_reader_options_are_the_clis(catalogue, tmp_path):
    """load, load_all and batch take the CLI's reader options by the CLI's names: repair reads a file with a
    duplicated angle that fails without it (as grid --repair does), front moves the luminaire's front as
    --front does, bad words are ValueErrors saying what is expected; load_all gives every photometry of a GLDF
    container with its id; a pickle keeps the options."""
    import pickle

    dup = tmp_path / "dup.ies"
    dup.write_text(DUPLICATED_GAMMA)
    with pytest.raises(ValueError) as e:
        photosolid.load(dup)
    assert "repair" in str(e.value)
    lum = photosolid.load(dup, repair=True)
    grid = cli_json("grid", str(dup), "--repair")
    np.testing.assert_array_equal(lum.gamma_deg, grid["gamma_deg"])
    assert pickle.loads(pickle.dumps(lum)) == lum
    table = photosolid.batch([dup], repair=True)
    assert table["ok"].to_pylist() == [True]
    assert photosolid.batch([dup])["ok"].to_pylist() == [False]

    road = DATA / "roadway.ies"
    turned = photosolid.load(road, front=90.0)
    assert turned.photometry() == cli_json("info", str(road), "--front", "90", "--json")
    assert turned.photometry() != photosolid.load(road).photometry()
    assert pickle.loads(pickle.dumps(turned)).photometry() == turned.photometry()
    for kwargs, words in [({"handedness": "left"}, "ccw"), ({"lamp_sets": "all"}, "first"),
                          ({"front": float("nan")}, "finite")]:
        with pytest.raises(ValueError) as e:
            photosolid.load(road, **kwargs)
        assert words in str(e.value), str(e.value)
    cw = photosolid.load(road, handedness="cw", lamp_sets="sum")
    np.testing.assert_array_equal(cw.candela, photosolid.load(road).candela)  # a Type C file: no change

    both = photosolid.load_all(catalogue / "lum.gldf")
    assert [lum.id for lum in both] == ["road", "bat"]
    assert [lum.path for lum in both] == [str(catalogue / "lum.gldf") + "#road", str(catalogue / "lum.gldf") + "#bat"]
    assert photosolid.load_all(road)[0].id is None and len(photosolid.load_all(road)) == 1
    np.testing.assert_array_equal(both[0].candela, photosolid.load(DATA / "roadway.ldt").candela)


def test_percents_are_spelled_as_the_cli_spells_them():
    """compare's tolerance and solid_tolerance and fit's tolerance and guard are percents written with their sign,
    as the CLI's flags; a bare number is refused with the CLI's own hint; the same values give the CLI's JSON."""
    path = DATA / "cosine_p5.ies"
    lum = photosolid.load(path)
    for call in (lambda: lum.compare(recons="bilinear", tolerance=1e-3),
                 lambda: lum.compare(recons="bilinear", tolerance="0.001")):
        with pytest.raises((ValueError, TypeError)):
            call()
    with pytest.raises(ValueError) as e:
        lum.compare(recons="bilinear", tolerance="0.1")
    assert "did you mean 0.1%" in str(e.value) and "tolerance" in str(e.value)
    with pytest.raises(ValueError) as e:
        lum.fit(guard="0.02")
    assert "2%" in str(e.value)
    with pytest.raises(ValueError):
        lum.compare(recons="bilinear", factor=2, solid_tolerance="0.05%")
    ours = lum.compare(recons="bilinear", directions="dense:2000", tolerance="0.5%", solid_tolerance="0.1%")
    theirs = cli_json("compare", str(path), "--recon", "bilinear", "--directions", "dense:2000",
                      "--tolerance", "0.5%", "--solid-tolerance", "0.1%", "--json")
    for key in ("tolerance_pct", "solid_tolerance_pct", "tolerance_cd", "solid_tolerance_cd", "reference"):
        assert ours[key] == theirs[key], key
    assert ours["results"][0]["radial_max_cd"] == theirs["results"][0]["radial_max_cd"]
    fit_ours = lum.fit(tolerance="5%", guard="1%")
    fit_cli = cli_json("fit", str(path), "--tolerance", "5%", "--guard", "1%", "--json")
    assert fit_ours == fit_cli


def test_the_readme_tour_runs(catalogue, tmp_path, monkeypatch):
    """The code of python/README.md's tour runs as written, on the repository's data and the catalogue fixture
    in place of its example paths."""
    import re

    text = (ROOT / "python" / "README.md").read_text()
    code = re.search(r"```python\n(.*?)```", text, re.S).group(1)
    dup = tmp_path / "odd.ies"
    dup.write_text(DUPLICATED_GAMMA)
    code = (code.replace('"odd.ies"', repr(str(dup)))
                .replace('"product.gldf"', repr(str(catalogue / "lum.gldf")))
                .replace('"catalogue/"', repr(str(catalogue)))
                .replace('"/tmp/', '"' + str(tmp_path) + "/"))
    monkeypatch.chdir(ROOT)
    exec(compile(code, "python/README.md", "exec"), {})
