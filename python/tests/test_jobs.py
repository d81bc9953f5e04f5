"""The CLI's jobs from Python: each function returns the document its command prints with ``--json``, equal to
the CLI's (timings removed where a document has them: they are measured anew on each run).

Needs PHOTOSOLID_BIN (the CLI binary) and PHOTOSOLID_ROOT (the repository), as scripts/python.sh sets them.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import photosolid

ROOT = Path(os.environ.get("PHOTOSOLID_ROOT", Path(__file__).resolve().parents[2]))
BIN = os.environ.get("PHOTOSOLID_BIN", str(ROOT / "target" / "debug" / "photosolid"))
DATA = ROOT / "data"


def cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([BIN, *map(str, args)], capture_output=True, text=True)


def cli_json(*args: str):
    r = cli(*args)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def _behaviour_snapshot():
    """scripts/behaviour-snapshot.py as a module: its `scrub` removes the keys that come from timings and orders
    candidate lists (ties in bytes are ordered by time), the one definition of "timings removed"."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("behaviour_snapshot", ROOT / "scripts" / "behaviour-snapshot.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


scrub = _behaviour_snapshot().scrub


def test_road_equals_the_cli_with_class_and_maximize():
    scene = DATA / "road_en13201.toml"
    assert photosolid.road(scene) == cli_json("road", scene, "--json")
    ours = photosolid.road(scene, class_="M5", maximize="spacing_m", range="30:45")
    theirs = cli_json("road", scene, "--class", "M5", "--maximize", "spacing_m", "--range", "30:45", "--json")
    assert ours == theirs
    assert ours["class"] == "M5" and ours["maximize"]["key"] == "spacing_m"
    # A range as a tuple is the same range.
    assert photosolid.road(scene, class_="M5", maximize="spacing_m", range=(30, 45)) == theirs
    grid = photosolid.road(scene, class_="M5", maximize="spacing_m", grid="mounting_height_m=9:10:1")
    assert grid == cli_json("road", scene, "--class", "M5", "--maximize", "spacing_m",
                            "--grid", "mounting_height_m=9:10:1", "--json")
    assert [g["grid"]["value"] for g in grid["maximize"]] == [9.0, 10.0]


def test_road_options_are_value_errors_naming_the_option():
    scene = DATA / "road_en13201.toml"
    with pytest.raises(ValueError, match="--class"):
        photosolid.road(scene, class_="M9")
    with pytest.raises(ValueError, match="--maximize"):
        photosolid.road(scene, maximize="spacing_m")
    with pytest.raises(ValueError, match="only spacing_m has a default"):
        photosolid.road(scene, class_="M5", maximize="tilt_deg")
    with pytest.raises(ValueError, match="START < END"):
        photosolid.road(scene, class_="M5", maximize="spacing_m", range="40:30")
    # The CLI says the same, as a usage error.
    r = cli("road", scene, "--class", "M5", "--maximize", "tilt_deg")
    assert r.returncode == 2 and "only spacing_m has a default" in r.stderr


def test_road_errors_carry_code_path_line_and_column(tmp_path):
    scene = DATA / "road_en13201.toml"
    with pytest.raises(photosolid.PhotosolidValueError) as caught:
        photosolid.road(scene, class_="M9")
    assert caught.value.code == "option" and caught.value.path is None
    bad = tmp_path / "road.toml"
    text = scene.read_text().replace("lane_width_m = 3.5", "lane_width_m = -3.5")
    bad.write_text(text)
    line = text.splitlines().index("lane_width_m = -3.5") + 1
    with pytest.raises(ValueError) as caught:
        photosolid.road(bad)
    e = caught.value
    assert (e.code, e.path, e.line, e.column) == ("road-invalid", str(bad), line, 1), (e.code, e.path, e.line, e.column)
    assert str(e) == e.message and "lane_width_m" in e.message
    # The CLI names the same place.
    assert f"{bad}:{line}:1" in cli("road", bad).stderr


@pytest.mark.parametrize("name", ["office_scene.toml", "office_panels.toml", "road_scene.toml"])
def test_scene_equals_the_cli(name):
    scene = DATA / name
    assert photosolid.scene(scene) == cli_json("scene", scene, "--json")


@pytest.mark.parametrize("name", ["office_scene.toml", "road_en13201.toml"])
def test_plan_equals_the_cli(name):
    scene = DATA / name
    assert scrub(photosolid.plan(scene, tolerance="2%")) == scrub(cli_json("plan", scene, "--tolerance", "2%", "--json"))


def test_plan_class_on_a_scene_without_a_road_is_refused_as_the_cli_refuses_it():
    with pytest.raises(ValueError, match="no \\[road\\] table"):
        photosolid.plan(DATA / "office_scene.toml", class_="M3")
    assert cli("plan", DATA / "office_scene.toml", "--class", "M3").returncode == 2


def test_validate_equals_the_cli(catalogue):
    ours = photosolid.validate([catalogue], derived=True)
    out = cli("validate", catalogue, "--derived", "--json").stdout
    theirs = [json.loads(line) for line in out.splitlines()]
    assert ours == theirs
    assert len(ours) == 6 and all(line["ok"] for line in ours)  # a.ies, b.ldt, no_extension, c.xml, 2 in lum.gldf


def test_synth_convert_and_export_write_what_the_cli_writes(tmp_path):
    ours = photosolid.synth("spot", tmp_path / "a.ldt", p=8, cutoff=40, intensity=500, gamma_step=2.5)
    theirs = cli_json("synth", "spot", "--p", "8", "--cutoff", "40", "--intensity", "500", "--gamma-step", "2.5",
                      "-o", tmp_path / "b.ldt", "--json")
    assert ours["output"] == str(tmp_path / "a.ldt") and theirs["output"] == str(tmp_path / "b.ldt")
    assert ours["exact_flux_lm"] == theirs["exact_flux_lm"] > 0
    assert (tmp_path / "a.ldt").read_bytes() == (tmp_path / "b.ldt").read_bytes()

    road = photosolid.load(DATA / "roadway.ies")
    conv = photosolid.convert(road, tmp_path / "r.ldt", rotate_c=90)
    conv_cli = cli_json("convert", DATA / "roadway.ies", tmp_path / "r2.ldt", "--rotate-c", "90", "--json")
    assert conv["warnings"] == conv_cli["warnings"]
    assert (tmp_path / "r.ldt").read_bytes() == (tmp_path / "r2.ldt").read_bytes()
    assert photosolid.convert(DATA / "roadway.ies", tmp_path / "r3.ies", ies_version="2019")["output"].endswith("r3.ies")

    exp = photosolid.export(road, tmp_path / "r.exr", engine="pbrt", resolution=64)
    exp_cli = cli_json("export", DATA / "roadway.ies", "--engine", "pbrt", "--resolution", "64",
                       "-o", tmp_path / "r2.exr", "--json")
    assert {k: v for k, v in exp.items() if k != "output"} == {k: v for k, v in exp_cli.items() if k != "output"}
    assert len(exp["size"]) == 2 and exp["engine"] == "pbrt"
    with pytest.raises(ValueError, match="kind"):
        photosolid.synth("cosine", tmp_path / "x.ldt")
    with pytest.raises(ValueError, match="written as .exr"):
        photosolid.export(road, tmp_path / "r.png", engine="pbrt")


def test_engines_and_tradeoff_equal_the_cli():
    path = DATA / "cosine_p5.ldt"
    ours = photosolid.engines(path, engines="pbrt,godot", resolution=64)
    theirs = cli_json("engines", path, "--engines", "pbrt,godot", "--resolution", "64", "--json")
    assert scrub(ours) == scrub(theirs)
    assert [r["name"] for r in ours["rows"]] == [r["name"] for r in theirs["rows"]]
    lum = photosolid.load(path)
    ours = photosolid.tradeoff(lum, factors=[1, 2], repeats=1)
    theirs = cli_json("tradeoff", path, "--factors", "1,2", "--repeats", "1", "--json")
    assert scrub(ours) == scrub(theirs)
    assert ours["file"] == str(path)


def test_tradeoff_on_the_gpu_equals_the_cli():
    """The wheel installs the GPU at import as the CLI's main does: `gpu=True` gives `--gpu`'s rows (the `+gpu`
    ones on the adapter WGPU_BACKEND picks), or, with no adapter, the CLI's error code."""
    path = DATA / "cosine_p5.ldt"
    r = cli("tradeoff", path, "--factors", "1", "--repeats", "1", "--gpu", "--json")
    if r.returncode != 0:
        with pytest.raises(photosolid.PhotosolidError) as caught:
            photosolid.tradeoff(path, factors=[1], repeats=1, gpu=True)
        assert caught.value.code in r.stderr, (caught.value.code, r.stderr)
        return
    theirs = json.loads(r.stdout)
    ours = photosolid.tradeoff(path, factors=[1], repeats=1, gpu=True)
    gpu_rows = [row["representation"] for row in ours["rows"] if row["representation"].endswith("+gpu")]
    assert gpu_rows, [row["representation"] for row in ours["rows"]]
    assert scrub(ours) == scrub(theirs)


def test_compare_takes_units_and_align_as_the_cli():
    a, b = DATA / "roadway.ldt", DATA / "roadway.ies"
    ours = photosolid.load(a).compare(recons="bilinear", vs=photosolid.load(b), units="peak", align=True,
                                      directions="dense:2000")
    theirs = cli_json("compare", a, "--vs", b, "--recon", "bilinear", "--units", "peak", "--align",
                      "--directions", "dense:2000", "--json")
    assert scrub(ours) == scrub(theirs)
    assert ours["photometry_side_by_side"] == theirs["photometry_side_by_side"]
    with pytest.raises(ValueError, match="align needs vs"):
        photosolid.load(a).compare(align=True)


def test_ugr_table_is_the_info_table_as_arrays():
    ugr_file = ROOT.parent / "shared" / "ugr-reference" / "sample_09.ldt"
    if not ugr_file.is_file():
        pytest.skip(f"no {ugr_file} (the shared UGR references)")
    lum = photosolid.load(ugr_file)
    t = lum.ugr_table()
    info = lum.photometry()["ugr_table"]
    assert t["crosswise"].shape == (19, 5) and t["rooms_h"].shape == (19, 2)
    assert t["reflectances"].shape == (5, 3) and t["crosswise"].dtype == np.float64
    np.testing.assert_array_equal(t["endwise"], np.array(info["endwise"]))
    assert t["max"] == info["max"]


def test_grid_frame_and_an_undefined_ugr_table():
    with pytest.raises(ValueError, match="point source"):
        photosolid.load(DATA / "batwing.ldt").ugr_table()
    import pandas as pd  # pinned in notebooks/requirements.txt: grid_frame is tested, never skipped
    lum = photosolid.load(DATA / "batwing.ies")
    frame = lum.grid_frame()
    assert isinstance(frame, pd.DataFrame)
    assert frame.index.name == "gamma_deg" and frame.columns.name == "c_deg"
    assert frame.shape == (len(lum.gamma_deg), len(lum.c_deg))
    np.testing.assert_array_equal(frame.to_numpy(), lum.candela.T)
    np.testing.assert_array_equal(frame.columns.to_numpy(), lum.c_deg)


def test_photometry_takes_the_info_options_as_the_cli():
    corpus = ROOT.parent / "shared" / "corpus"
    tilted = corpus / "luxera" / "tilt_include_variant.ies"
    ugr_file = ROOT.parent / "shared" / "ugr-reference" / "sample_09.ldt"
    if not (tilted.is_file() and ugr_file.is_file()):
        pytest.skip(f"no {tilted} or {ugr_file} (the shared corpus and UGR references)")
    lum = photosolid.load(tilted)
    assert lum.photometry(tilt=30) == cli_json("info", tilted, "--tilt", "30", "--json")
    assert lum.photometry(tilt=30)["flux_lm"] != lum.photometry()["flux_lm"]
    ugr = photosolid.load(ugr_file)
    assert ugr.photometry(ugr_spacing=1.0) == cli_json("info", ugr_file, "--ugr-spacing", "1", "--json")
    assert ugr.ugr_table(ugr_spacing=1.0)["spacing_h"] == 1.0
    with pytest.raises(ValueError):
        ugr.photometry(ugr_spacing=0.3)
    with pytest.raises(ValueError):
        photosolid.load(DATA / "batwing.ies").photometry(tilt=10)  # no tilt table


@pytest.mark.parametrize("args,kwargs", [
    (["--filter", "catmull-rom"], {}),  # the CLI's default grid: adaptive within 0.1 %
    (["--filter", "bilinear", "--tolerance", "0.5%", "--units", "peak"], {"filter": "bilinear", "tolerance": "0.5%",
                                                                        "units": "peak"}),
    (["--measured"], {"filter": "measured"}),
    (["--filter", "pchip", "--texture", "--factor", "2"], {"filter": "pchip", "texture": True, "factor": 2}),
])
def test_mesh_takes_the_clis_options_and_defaults(tmp_path, args, kwargs):
    import trimesh

    path = DATA / "spot_p8_c40.ies"
    v, f = photosolid.load(path).mesh(**kwargs)
    cli_doc = cli_json("mesh", path, *args, "-o", tmp_path / "s.ply", "--json")
    m = trimesh.Trimesh(v, f, process=False)
    assert len(f) == cli_doc["triangles"]
    assert m.volume == pytest.approx(cli_doc["volume"], rel=1e-5)
    assert m.area == pytest.approx(cli_doc["area"], rel=1e-5)


def test_mesh_options_that_exclude_each_other_are_refused():
    lum = photosolid.load(DATA / "spot_p8_c40.ies")
    with pytest.raises(ValueError, match="--tolerance"):
        lum.mesh(factor=3, tolerance="0.1%")
    with pytest.raises(ValueError, match="--texture"):
        lum.mesh("measured", texture=True)
    with pytest.raises(ValueError, match="units"):
        lum.mesh(units="lm")


def test_an_ignored_option_is_a_warning_in_both_ways_in():
    path = DATA / "roadway.ldt"
    lum = photosolid.load(path)
    with pytest.warns(UserWarning, match="--directions dense:2000: the withheld reference"):
        ours = lum.compare(recons="bilinear", against="withheld", directions="dense:2000")
    theirs = cli_json("compare", path, "--recon", "bilinear", "--against", "withheld", "--directions", "dense:2000",
                      "--json")
    assert [w for w in ours["warnings"] if w["code"] == "ignored-option"] == \
        [w for w in theirs["warnings"] if w["code"] == "ignored-option"] != []
    # Not given: no warning.
    assert not [w for w in lum.compare(recons="bilinear", against="withheld")["warnings"]
                if w["code"] == "ignored-option"]


def test_load_from_bytes_and_file_objects_and_the_cheap_properties(catalogue):
    import io

    path = DATA / "roadway.ldt"
    from_path = photosolid.load(path)
    data = path.read_bytes()
    from_bytes = photosolid.load(data, name="roadway.ldt")
    assert from_bytes.path == "roadway.ldt"
    np.testing.assert_array_equal(from_bytes.candela, from_path.candela)
    assert from_bytes.photometry()["flux_lm"] == from_path.photometry()["flux_lm"]
    # No name: the content decides (EULUMDAT has no TILT= line), as for batch's extension-less files.
    np.testing.assert_array_equal(photosolid.load(io.BytesIO(data)).candela, from_path.candela)
    with open(path, "rb") as f:
        assert photosolid.load(f).path == str(path)
    gldf = (catalogue / "lum.gldf").read_bytes()
    bat = photosolid.load(gldf, name="lum.gldf#bat")
    np.testing.assert_array_equal(bat.candela, photosolid.load(DATA / "batwing.ies").candela)
    with pytest.raises(TypeError, match="binary mode"):
        photosolid.load(io.StringIO("x"))
    with pytest.raises(ValueError):
        photosolid.load(b"not photometric at all", name="x.ies")
    meta = from_path.metadata
    info = from_path.photometry()
    assert meta["declared"]["lamp_flux_lm"] == info["lamp_flux_lm"]
    assert meta["format"] == info["format"]
    assert from_path.warnings == info["warnings"]


def test_folds_with_another_reference_is_an_ignored_option():
    path = DATA / "cosine_p5.ldt"  # written by `photosolid synth`: it records its closed form, the default reference
    lum = photosolid.load(path)
    with pytest.warns(UserWarning, match="--folds 3: folds are the withheld reference's, and the reference is truth"):
        ours = lum.compare(recons="bilinear", folds=3, directions="dense:2000")
    theirs = cli_json("compare", path, "--recon", "bilinear", "--folds", "3", "--directions", "dense:2000", "--json")
    ignored = [w for w in theirs["warnings"] if w["code"] == "ignored-option"]
    assert ignored and ignored == [w for w in ours["warnings"] if w["code"] == "ignored-option"]
    assert theirs["reference"].startswith("truth")
