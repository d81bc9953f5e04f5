"""The interactive 3D view of the HTML reports in a real browser (headless Chromium driven by Playwright).

Run by scripts/browser-tests.sh (which installs tests/browser/requirements.txt into .venv-browser/):
  PHOTOSOLID_BIN=target/debug/photosolid CHROMIUM=/usr/bin/chromium pytest tests/browser
Playwright drives the system Chromium (executable_path): `playwright install` needs a network. WebGL runs on
SwiftShader (software), so no GPU is needed. Screenshots go to $BROWSER_TEST_OUT (default target/browser-tests).
$PHOTOSOLID_DEMO_DIR, when it holds a demo report (test-all.sh sets it), is opened instead of running the demo.
"""

import io
import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from PIL import Image, ImageChops, ImageStat
from playwright.sync_api import sync_playwright

ROOT = Path(__file__).resolve().parents[2]
OUT = Path(os.environ.get("BROWSER_TEST_OUT", ROOT / "target" / "browser-tests"))
# Software WebGL: ANGLE on SwiftShader (Chromium refuses SwiftShader WebGL without the "unsafe" opt-in).
WEBGL_ARGS = ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist", "--no-sandbox"]


def chromium() -> str:
    exe = os.environ.get("CHROMIUM") or next(
        (shutil.which(e) for e in ("chromium", "chromium-browser", "google-chrome") if shutil.which(e)), None
    )
    assert exe, "no chromium on PATH (set CHROMIUM)"
    return exe


def run(*args: str) -> None:
    bin_ = os.environ.get("PHOTOSOLID_BIN", str(ROOT / "target" / "debug" / "photosolid"))
    r = subprocess.run([bin_, *args], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


@pytest.fixture(scope="session")
def reports(tmp_path_factory):
    """Two reports: against the closed-form truth (synth file) and against withheld measurements."""
    d = tmp_path_factory.mktemp("reports")
    run("synth", "roadway", "--c-step", "10", "--gamma-step", "5", "-o", str(d / "road.ldt"))
    run("compare", str(d / "road.ldt"), "--directions", "dense:2000", "--report", str(d / "truth"))
    run("compare", str(d / "road.ldt"), "--against", "withheld", "--directions", "dense:2000",
        "--report", str(d / "withheld"))
    run("scene", str(ROOT / "data" / "road_scene.toml"), "--report", str(d / "scene"))
    # A denser measurement of the same luminaire: `--vs` measures against it.
    run("synth", "roadway", "--c-step", "2.5", "--gamma-step", "1", "-o", str(d / "dense.ldt"))
    # The legend test compares with the table's radial max: these two use the default 20,000 directions,
    # the max refined locally around the largest.
    run("compare", str(d / "road.ldt"), "--vs", str(d / "dense.ldt"), "--report", str(d / "vs"))
    run("compare", str(d / "road.ldt"), "--report", str(d / "truth-dense"))
    # test-all.sh's CLI smoke has just run the same binary's demo: open its report
    # (PHOTOSOLID_DEMO_DIR) rather than spend another demo run on it.
    demo = Path(os.environ.get("PHOTOSOLID_DEMO_DIR") or d / "demo")
    if not (demo / "index.html").is_file():
        demo = d / "demo"
        run("demo", "--output", str(demo))
    return {
        "truth": d / "truth" / "index.html",
        "withheld": d / "withheld" / "index.html",
        "scene": d / "scene" / "index.html",
        "vs": d / "vs" / "index.html",
        "truth-dense": d / "truth-dense" / "index.html",
        "demo": demo / "index.html",
    }


@pytest.fixture(scope="session")
def pw():
    """One Playwright driver for the session (the sync API allows one at a time)."""
    with sync_playwright() as p:
        yield p


@pytest.fixture(scope="session")
def browser(pw):
    b = pw.chromium.launch(executable_path=chromium(), args=WEBGL_ARGS)
    yield b
    b.close()


def open_page(browser, index: Path):
    """The report offline, every non-file request aborted and recorded; console errors recorded."""
    ctx = browser.new_context(offline=True, viewport={"width": 1280, "height": 1000})
    page = ctx.new_page()
    errors, outside = [], []
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(str(e)))

    def route(r):
        if r.request.url.startswith(("file:", "data:")):
            r.continue_()
        else:
            outside.append(r.request.url)
            r.abort()

    page.route("**/*", route)
    page.goto(index.as_uri())
    return ctx, page, errors, outside


def shot(locator, name: str) -> Image.Image:
    OUT.mkdir(parents=True, exist_ok=True)
    png = locator.screenshot()
    (OUT / f"{name}.png").write_bytes(png)
    return Image.open(io.BytesIO(png)).convert("RGB")


def changed_fraction(a: Image.Image, b: Image.Image) -> float:
    diff = ImageChops.difference(a, b).convert("L").point(lambda v: 255 if v > 8 else 0)
    return ImageStat.Stat(diff).mean[0] / 255


def not_blank(img: Image.Image, name: str, min_colours: int) -> None:
    """A picture, not an empty canvas: grey-level spread and distinct colours above what a blank
    (1 colour, stddev 0) or a frame-only canvas (a few colours) gives."""
    std = sum(ImageStat.Stat(img).stddev) / 3
    colours = len(img.getcolors(maxcolors=1 << 20) or [])
    assert std > 8 and colours > min_colours, f"{name} looks blank: stddev {std:.1f}, {colours} colours"


@pytest.mark.parametrize("kind", ["truth", "withheld"])
def test_viewer_renders_offline_and_reacts(browser, reports, kind):
    ctx, page, errors, outside = open_page(browser, reports[kind])
    root = page.locator("section.psv")
    page.wait_for_selector("section.psv[data-psv-state=ready]", timeout=30_000)
    caption = root.locator(".psv-caption").inner_text()
    assert ("Reference: truth" if kind == "truth" else "Reference: the measured solid") in caption, caption
    stage, polar = root.locator(".psv-stage"), root.locator(".psv-polar")
    first = shot(stage, f"{kind}-3d")
    # The same view drawn again is the same picture (the comparisons below rely on it).
    root.locator(".psv-c").evaluate("e => e.dispatchEvent(new Event('input'))")
    assert changed_fraction(first, shot(stage, f"{kind}-3d-redrawn")) == 0
    # The shaded, colour-mapped solid has hundreds of colours; the line drawings (antialiased) dozens.
    not_blank(first, "3D view", 300)
    not_blank(shot(polar, f"{kind}-polar"), "polar panel", 40)
    not_blank(shot(root.locator(".psv-scale"), f"{kind}-scale"), "colour scale", 40)

    # Toggling a reconstruction changes the picture; toggling it back restores it.
    boxes = root.locator(".psv-toggles input")
    assert boxes.count() >= 3
    recon = boxes.nth(1)
    assert recon.is_checked()
    recon.uncheck()
    without = shot(stage, f"{kind}-3d-without")
    assert changed_fraction(first, without) > 0.02, "unchecking a reconstruction left the 3D view unchanged"
    boxes.nth(2).check()
    other = shot(stage, f"{kind}-3d-other")
    assert changed_fraction(without, other) > 0.02
    boxes.nth(2).uncheck()
    recon.check()
    assert changed_fraction(first, shot(stage, f"{kind}-3d-again")) < 0.002

    # The C-plane slider redraws the polar panel (C0-C180 to C90-C270 of a road luminaire differ).
    before = shot(polar, f"{kind}-polar-c0")
    root.locator(".psv-c").evaluate("e => { e.value = 90; e.dispatchEvent(new Event('input')); }")
    assert root.locator(".psv-cval").inner_text() == "C90 \u2013 C270"
    after = shot(polar, f"{kind}-polar-c90")
    assert changed_fraction(before, after) > 0.01, "moving the C-plane slider left the polar panel unchanged"

    # Mouse orbit and touch pinch (pointer events) change the view.
    box = stage.bounding_box()
    cx, cy = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    base = shot(stage, f"{kind}-3d-c90")
    page.mouse.move(cx, cy)
    page.mouse.down()
    page.mouse.move(cx + 120, cy + 40, steps=5)
    page.mouse.up()
    orbited = shot(stage, f"{kind}-3d-orbit")
    assert changed_fraction(base, orbited) > 0.02, "dragging did not orbit"
    page.locator(".psv-gl").evaluate(
        """c => {
          const ev = (type, id, x, y) => c.dispatchEvent(new PointerEvent(type,
            {pointerId: id, pointerType: 'touch', clientX: x, clientY: y, bubbles: true, isPrimary: id === 1}));
          const r = c.getBoundingClientRect(), x = r.left + r.width / 2, y = r.top + r.height / 2;
          ev('pointerdown', 1, x - 20, y); ev('pointerdown', 2, x + 20, y);
          for (let k = 1; k <= 5; k++) { ev('pointermove', 1, x - 20 - 15 * k, y); ev('pointermove', 2, x + 20 + 15 * k, y); }
          ev('pointerup', 1, x, y); ev('pointerup', 2, x, y);
        }"""
    )
    pinched = shot(stage, f"{kind}-3d-pinch")
    assert changed_fraction(orbited, pinched) > 0.02, "a two-finger pinch did not zoom"

    # The static figures stay.
    assert page.locator("figure img").count() >= 3
    assert errors == [], errors
    assert outside == [], outside
    shot(page.locator("body"), f"{kind}-page")
    ctx.close()


def test_scene_report_draws_every_luminaire(browser, reports):
    ctx, page, errors, outside = open_page(browser, reports["scene"])
    roots = page.locator("section.psv")
    assert roots.count() >= 2
    for k in range(roots.count()):
        page.wait_for_selector(f"section.psv:nth-of-type({k + 1})", timeout=30_000)
    page.wait_for_function("[...document.querySelectorAll('section.psv')].every(s => s.dataset.psvState === 'ready')")
    for k in range(roots.count()):
        # Only the reference: a shaded grey surface under its wire mesh.
        not_blank(shot(roots.nth(k).locator(".psv-stage"), f"scene-3d-{k}"), f"luminaire {k}", 100)
    assert errors == [] and outside == [], (errors, outside)
    ctx.close()


def test_without_webgl_the_static_figures_remain(pw, reports):
    b = pw.chromium.launch(executable_path=chromium(), args=["--disable-webgl", "--disable-3d-apis", "--no-sandbox"])
    ctx, page, errors, outside = open_page(b, reports["truth"])
    page.wait_for_selector("section.psv[data-psv-state=nogl]", timeout=30_000)
    msg = page.locator(".psv-nogl")
    assert msg.is_visible() and "WebGL is not available" in msg.inner_text()
    assert not page.locator(".psv-main").is_visible()
    imgs = page.locator("figure img")
    assert imgs.count() >= 3
    for k in range(imgs.count()):
        assert imgs.nth(k).evaluate("i => i.complete && i.naturalWidth > 0"), f"figure {k} not shown"
    shot(page.locator("body"), "nogl-page")
    assert errors == [] and outside == [], (errors, outside)
    ctx.close()
    b.close()


def legend(page) -> dict:
    """Each reconstruction's legend entry of the 3D view: name -> (quantity, value in %)."""
    page.wait_for_selector("section.psv[data-psv-state=ready]", timeout=30_000)
    out = {}
    for text in page.locator("section.psv .psv-toggles label").all_inner_texts():
        m = re.fullmatch(r"(.+) \((max \|[^|]+\|) ([0-9.eE+-]+) %\)", text.strip())
        if m:
            out[m.group(1)] = (m.group(2), float(m.group(3)))
    return out


@pytest.mark.parametrize("kind", ["truth-dense", "vs", "demo"])
def test_legend_max_agrees_with_the_table(browser, reports, kind):
    """Against the truth (a compare report and the demo's) and against a denser file (`--vs`), the legend's max |err| of each
    reconstruction agrees with the table's radial max within 10 %: the view samples the error between
    the measured directions, where it is (it showed 0.00 % for interpolating filters)."""
    ctx, page, errors, _ = open_page(browser, reports[kind])
    shown = legend(page)
    rows = json.loads((reports[kind].parent / "report.json").read_text())["results"]
    assert len(shown) >= 3, shown
    for r in rows:
        quantity, value = shown[r["name"]]
        assert quantity == "max |err|", (r["name"], quantity)
        table = r["radial_max_pct"]
        # The table's radial max is over 20,000 Fibonacci directions, refined locally around the largest
        # (`radial_max_method`); the view's is over nine points around each vertex of its grid.
        assert value >= 0.9 * table - 0.0015, (kind, r["name"], value, table)
        assert value <= 1.1 * table + 0.0015, (kind, r["name"], value, table)
    assert not errors, errors
    ctx.close()


def test_withheld_legend_says_what_it_shows(browser, reports):
    """Against withheld measurements the colours show the difference from the measured solid, and the
    legend says so instead of calling it an error."""
    ctx, page, errors, _ = open_page(browser, reports["withheld"])
    shown = legend(page)
    assert shown and all(q == "max |diff from the measured solid|" for q, _ in shown.values()), shown
    assert not errors, errors
    ctx.close()
