//! Derived photometry (CIE flux code, zonal lumens, UGR, BUG, luminance) on
//! real files, against the peer eulumdat-rs where it is right, and through
//! the CLI (`info --json` keys, `compare --vs` side by side).

use crate::common;

use std::path::Path;

use common::cli::{ok, run};
use common::{corpus, manifest, snapshot};
use photosolid::photometry::bug::bug_zones;
use photosolid::photometry::derived::{Derivation, Derived};

/// N1..N4 (%) that eulumdat 0.7.1 (PyPI build of holg/eulumdat-rs; Python
/// `Eulumdat.cie_flux_codes()`, run on 2026-11-30) prints for the corpus
/// files of holg/eulumdat-rs at c7e8b5d. Its N5 is the file's declared LOR,
/// ours the computed one, so N5 is not compared.
const PEER_CIE: [(&str, [f64; 4]); 10] = [
    (
        "4058075580657_FL_MAX_LUM_900W_757_ASYM_50X110_WAL.ldt",
        [37.76, 80.55, 98.73, 100.0],
    ),
    (
        "4058075580664_FL_MAX_LUM_1200W_757_SYM_10_WAL.ldt",
        [91.39, 97.15, 99.66, 100.0],
    ),
    ("ABSOLUTE_LED.ies", [70.64, 94.58, 99.38, 100.0]),
    ("ITALO 1 5P5 S05 3.140-3M.IES", [30.90, 66.88, 95.90, 100.0]),
    (
        "OutdoorRoadway IES OS 8988-2022 03 AM01 60W 4000K.ies",
        [44.89, 77.73, 98.15, 99.43],
    ),
    ("TILT_TEST_SYNTHETIC.ies", [41.19, 71.18, 89.94, 100.0]),
    ("demo_two_lamp_sets.ldt", [25.32, 57.86, 96.09, 99.10]),
    ("projector.ldt", [42.83, 86.73, 98.96, 100.0]),
    ("wiki-batwing.ldt", [36.89, 75.18, 95.89, 100.0]),
    // Wrong in the peer (docs/photometry.md): Isym 3 planes mis-weighted.
    ("road_luminaire.ldt", [29.74, 62.81, 94.10, 100.0]),
];

/// Agreement with the peer: N1..N4 within 0.7 percentage points on every
/// file but the Isym 3 road luminaire, where the peer is 7.8 points off in
/// N1; there our flux (27934 lm) is 0.3 % from the file's declared luminaire
/// flux, which is the independent check that ours is the right one.
#[test]
fn cie_flux_codes_agree_with_the_peer_where_it_is_right() {
    let Some(root) = corpus() else { return };
    for (name, peer) in PEER_CIE {
        let lum = photosolid::load(root.join("eulumdat-rs").join(name)).unwrap();
        let d = Derived::of(&lum);
        let Derivation::Value(code) = &d.cie_flux_code else {
            panic!("{name}: no code")
        };
        let worst = (0..4).map(|k| (code.n[k] - peer[k]).abs()).fold(0.0, f64::max);
        eprintln!("{name}: ours {:?} peer {peer:?} worst {worst:.2}", code.n);
        if name == "road_luminaire.ldt" {
            assert!(worst > 5.0, "{name}: the peer's known error vanished? {worst}");
            let s = photosolid::photometry::summary(&lum);
            assert_close!(s.flux_ratio.unwrap(), 1.0, abs = 0.005, "{:?}", s.flux_ratio);
        } else {
            assert!(worst < 0.7, "{name}: ours {:?} vs peer {peer:?}", code.n);
        }
    }
}

/// A rotationally symmetric file (wiki-batwing, Isym 1; ABSOLUTE_LED.ies,
/// 37 equal planes) must put as many lumens behind as in front. The peer rates it with BL = BM = BH = BVH = 0
/// (it assigns every stored plane C ≤ 180 to the front).
#[test]
fn symmetric_files_have_equal_front_and_back_zones() {
    let Some(root) = corpus() else { return };
    for name in ["wiki-batwing.ldt", "ABSOLUTE_LED.ies"] {
        let lum = photosolid::load(root.join("eulumdat-rs").join(name)).unwrap();
        let z = bug_zones(lum.distribution(), lum.front());
        let total = z.fl + z.fm + z.fh + z.fvh + z.bl + z.bm + z.bh + z.bvh + z.ul + z.uh;
        let flux = photosolid::photometry::flux(lum.distribution()).total_lm;
        assert_close!(total, flux, rel = 1e-9, "{name}: zones {total} vs flux {flux}");
        for (f, b) in [(z.fl, z.bl), (z.fm, z.bm), (z.fh, z.bh), (z.fvh, z.bvh)] {
            assert_close!(f, b, abs = 1e-9 * flux, "{name}: front {f} back {b}");
        }
    }
}

/// BUG ratings printed by manufacturers in the `[DISTRIBUTION]` keyword of
/// their LM-63 files (computed by their photometric labs with TM-15-11
/// Addendum A), against ours. Files: LuxCore's ASA_15M_R2.ies (Type II, MH
/// 150 W, "BUG RATING: B2 - U0 - G2") and appleseed's test_iesparser_3.ies
/// (American Electric Lighting GRSL, Type II, "B2 - U3 - G2"). Both are
/// symmetric about the C0-C180 plane and throw toward C0: with TM-15's
/// forward = horizontal 270-90 they match; with forward = C 0-180 (our
/// earlier convention) both rated B3. The zones also pin glare rows: on
/// test_iesparser_3 FH = 1883 lm must fall in G2 (1800 < FH <= 5000).
#[test]
fn declared_bug_ratings_of_manufacturer_files() {
    let Some(root) = corpus() else { return };
    // Every corpus file that prints its rating (`BUG RATING: B2 - U0 - G2`), found by
    // content, so a file added to the corpus is checked too.
    let mut checked = Vec::new();
    for e in manifest(&root).iter().filter(|e| e.photometric() && !e.malformed()) {
        let Ok(bytes) = std::fs::read(&e.path) else { continue };
        let text = String::from_utf8_lossy(&bytes);
        let Some(line) = text.lines().find(|l| l.contains("BUG RATING")) else {
            continue;
        };
        let printed: String = line.split("BUG RATING:").nth(1).unwrap().replace(" - ", " ");
        let declared = printed.trim().to_string();
        let lum = photosolid::load(&e.path).unwrap();
        let r = photosolid::photometry::bug::bug_rating(lum.distribution(), lum.front());
        eprintln!("{}: ours {} declared {declared} zones {:?}", e.rel, r.rating, r.zones);
        assert_eq!(r.rating, declared, "{}: zones {:?}", e.rel, r.zones);
        checked.push(e.rel.clone());
    }
    checked.sort();
    assert_eq!(
        checked,
        ["appleseed/test_iesparser_3.ies", "luxcore/ASA_15M_R2.ies"],
        "the corpus files that load and declare a BUG rating (test_iesparser_4.ies, a damaged copy of _3, does not load)"
    );
}

/// Golden table of the derived scalars of every eulumdat-rs corpus file
/// (regressions show as a diff; values explained in docs/photometry.md).
#[test]
fn corpus_derived_photometry_snapshot() {
    let Some(root) = corpus() else { return };
    let mut table = String::from("file\tcie_flux_code\tbug\tugr_4x8_705020_cross\tugr_4x8_705020_end\tlum_max_cd_m2\n");
    let mut entries: Vec<_> = manifest(&root)
        .into_iter()
        .filter(|e| e.rel.starts_with("eulumdat-rs/") && e.photometric() && !e.malformed())
        .collect();
    entries.sort_by(|a, b| a.rel.cmp(&b.rel));
    for e in entries {
        let lum = photosolid::load(&e.path).unwrap();
        let d = Derived::of(&lum);
        let code = d.cie_flux_code.value().map_or("-".into(), |c| c.code.clone());
        let r = d.scalars();
        let get = |q: &str| {
            r.iter()
                .find(|x| x.0 == q)
                .and_then(|x| x.2)
                .map_or("-".into(), |v| format!("{v:.1}"))
        };
        let json = serde_json::to_string(&d).unwrap();
        assert!(!json.contains("NaN") && !json.contains("null,null,null"), "{}", e.rel);
        table.push_str(&format!(
            "{}\t{}\t{}\t{}\t{}\t{}\n",
            e.rel,
            code,
            d.bug_rating.as_ref().map_or("-", |b| b.rating.as_str()),
            get("UGR 4Hx8H 70/50/20 crosswise"),
            get("UGR 4Hx8H 70/50/20 endwise"),
            get("luminance table max")
        ));
    }
    snapshot("photometry_corpus.tsv", &table);
}

/// A 600 x 600 mm Lambertian panel of 1 lamp x 3600 lm, 1000/π cd·cos γ per klm.
fn write_panel(dir: &Path, name: &str, scale: f64) {
    let g: Vec<f64> = (0..=18).map(|k| 5.0 * f64::from(k)).collect();
    let cd: Vec<String> = g
        .iter()
        .map(|x| {
            format!(
                "{:.6}",
                scale * 3600.0 / std::f64::consts::PI * x.to_radians().cos().max(0.0)
            )
        })
        .collect();
    let gs: Vec<String> = g.iter().map(|x| x.to_string()).collect();
    let text = format!(
        "IESNA:LM-63-2002\n[TEST] panel\nTILT=NONE\n1 3600 1 {} 1 1 2 0.6 0.6 0\n1 1 0\n{}\n0\n{}\n",
        g.len(),
        gs.join(" "),
        cd.join(" ")
    );
    std::fs::write(dir.join(name), text).unwrap();
}

#[test]
fn info_json_carries_the_derived_keys() {
    let dir = tempfile::tempdir().unwrap();
    write_panel(dir.path(), "panel.ies", 1.0);
    let out = ok(&run(&["info", "panel.ies", "--json"], dir.path()));
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for k in [
        "cie_flux_code",
        "zonal_lumens",
        "ugr_table",
        "bug_rating",
        "luminance_table",
        "flux_lm",
    ] {
        assert!(v.get(k).is_some(), "missing {k}: {out}");
    }
    // Lambertian: L = I/A_p = (3600/π)/0.36 cd/m² at every angle.
    let l = v["luminance_table"]["c0_cd_m2"][4].as_f64().unwrap();
    let want = 3600.0 / std::f64::consts::PI / 0.36;
    assert_close!(l, want, rel = 1e-3, "{l} vs {want}");
    // Isotropic-in-cosine: N1 = 43.75 % within the 5° grid's interpolation error.
    let n1 = v["cie_flux_code"]["n"][0].as_f64().unwrap();
    assert_close!(n1, 43.75, abs = 0.3, "{n1}");
    let text = ok(&run(&["info", "panel.ies"], dir.path()));
    assert!(
        text.contains("UGR table") && text.contains("CIE flux code") && text.contains("BUG rating"),
        "{text}"
    );
    assert!(!text.contains("NaN"));
}

/// `compare --vs`: the scalars side by side above the metrics, in text, JSON
/// and the Markdown/HTML report. Twice the intensities: flux doubles, the
/// flux code stays, UGR rises by 8 log10 2 = 2.41.
#[test]
fn compare_vs_prints_photometry_side_by_side() {
    let dir = tempfile::tempdir().unwrap();
    write_panel(dir.path(), "a.ies", 1.0);
    write_panel(dir.path(), "b.ies", 2.0);
    let args = [
        "compare",
        "a.ies",
        "--vs",
        "b.ies",
        "--recon",
        "bilinear",
        "--directions",
        "dense:500",
    ];
    let text = ok(&run(&args, dir.path()));
    let side = text.find("photometry (unit)").expect(&text);
    let metrics = text.find("bilinear").expect(&text);
    assert!(side < metrics, "{text}");
    let mut j = args.to_vec();
    j.push("--json");
    let v: serde_json::Value = serde_json::from_str(&ok(&run(&j, dir.path()))).unwrap();
    let rows = v["photometry_side_by_side"].as_array().unwrap();
    let row = |q: &str| rows.iter().find(|r| r["quantity"] == q).unwrap().clone();
    let flux = row("flux");
    let (a, d) = (flux["file"].as_f64().unwrap(), flux["difference"].as_f64().unwrap());
    assert_close!(d, a, rel = 1e-6, "{flux}");
    assert_close!(row("CIE flux code N1")["difference"].as_f64().unwrap(), 0.0, abs = 1e-9);
    let du = row("UGR 4Hx8H 70/50/20 crosswise")["difference"].as_f64().unwrap();
    assert_close!(du, 8.0 * 2f64.log10(), abs = 1e-6, "{du}");
    let mut r = args.to_vec();
    r.extend(["--report", "rep"]);
    ok(&run(&r, dir.path()));
    let md = std::fs::read_to_string(dir.path().join("rep/report.md")).unwrap();
    assert!(md.find("## Photometry side by side").unwrap() < md.find("## Metrics").unwrap());
    let html = std::fs::read_to_string(dir.path().join("rep/index.html")).unwrap();
    assert!(html.contains("Photometry side by side"));
    // Without --vs there is no side-by-side key.
    let solo: serde_json::Value = serde_json::from_str(&ok(&run(
        &[
            "compare",
            "a.ies",
            "--recon",
            "bilinear",
            "--directions",
            "dense:200",
            "--json",
        ],
        dir.path(),
    )))
    .unwrap();
    assert!(solo.get("photometry_side_by_side").is_none());
}

/// The uncorrected UGR table CIE 190:2010 publishes for its example
/// luminaire (rooms 2H×2H … 12H×8H as in `ROOMS_H`; columns crosswise
/// 70/50/20, 70/30/20, 50/50/20, 50/30/20, 30/30/20, then endwise in the same
/// order), as transcribed in 123VincentB/eulumdat-ugr
/// (`data/reference/ugr_table_11_cie190.csv`, via mariusgrote/eulumdat-core
/// `tests/fixtures/ugr/reference/ugr_table_11_cie190.csv` at 8b0c3fa). Its
/// 2H×4H 70/50/20 cell, 11.0 crosswise and 13.1 endwise, is also the result of
/// the standard's worked example as quoted in a second, independent reading
/// of CIE 190 (an "iesUgr" verification note found by exact-string search).
const CIE_190_EXAMPLE_TABLE: [[f64; 10]; 19] = [
    [8.9, 10.5, 9.3, 10.8, 11.1, 10.7, 12.2, 11.0, 12.5, 12.9],
    [10.5, 11.9, 10.8, 12.2, 12.6, 12.4, 13.8, 12.8, 14.2, 14.5],
    [11.0, 12.3, 11.4, 12.6, 13.0, 13.1, 14.5, 13.5, 14.8, 15.2],
    [11.5, 12.7, 11.9, 13.1, 13.5, 13.6, 14.8, 14.0, 15.2, 15.6],
    [11.7, 12.9, 12.2, 13.3, 13.7, 13.8, 14.9, 14.2, 15.3, 15.7],
    [12.0, 13.2, 12.5, 13.5, 14.0, 13.8, 15.0, 14.3, 15.3, 15.8],
    [9.6, 11.0, 10.0, 11.3, 11.7, 11.0, 12.4, 11.4, 12.7, 13.1],
    [11.4, 12.5, 11.8, 12.9, 13.3, 13.0, 14.1, 13.4, 14.5, 14.9],
    [12.0, 13.0, 12.4, 13.4, 13.9, 13.9, 14.9, 14.3, 15.3, 15.7],
    [12.7, 13.5, 13.1, 14.0, 14.4, 14.5, 15.4, 15.0, 15.8, 16.3],
    [13.0, 13.8, 13.5, 14.2, 14.7, 14.7, 15.5, 15.2, 16.0, 16.4],
    [13.4, 14.1, 13.8, 14.6, 15.0, 14.8, 15.6, 15.3, 16.0, 16.5],
    [12.4, 13.2, 12.8, 13.6, 14.1, 14.0, 14.8, 14.5, 15.3, 15.8],
    [13.2, 13.8, 13.7, 14.3, 14.8, 14.8, 15.4, 15.3, 15.9, 16.4],
    [13.6, 14.2, 14.1, 14.7, 15.2, 15.0, 15.6, 15.5, 16.1, 16.6],
    [14.1, 14.7, 14.6, 15.1, 15.7, 15.2, 15.7, 15.7, 16.2, 16.8],
    [12.4, 13.1, 12.9, 13.6, 14.1, 14.0, 14.8, 14.5, 15.2, 15.7],
    [13.2, 13.8, 13.8, 14.3, 14.8, 14.8, 15.4, 15.3, 15.9, 16.4],
    [13.7, 14.3, 14.3, 14.8, 15.3, 15.1, 15.6, 15.6, 16.1, 16.7],
];

/// Every cell of our table for the CIE 190:2010 example luminaire (its
/// Table 7 intensities, 1000 lm, LORL 64.9 %, a flat 0.316 m² luminous area:
/// `r-lighting/0_CIE-2010-Table7.ldt` of the corpus, from Wei-Lim/lighting)
/// against the table the standard publishes for it: every cell within
/// −0.22 … +0.18 (mean −0.001; the published cells are rounded to 0.1).
/// Two fixes of 2026-11-30 brought it there: crosswise and endwise as CIE 117
/// eqs. 4.5/4.6 define them (swapped before: cells off by −1.7 … +2.4), and
/// CIE 117's field, which leaves the first row of the array (H/R = 2, beyond
/// the Guth table) out of the glare sum (without it: +0.12 … +0.94).
#[test]
fn ugr_table_of_the_cie_190_example_luminaire() {
    let Some(root) = corpus() else { return };
    let lum = photosolid::load(root.join("r-lighting/0_CIE-2010-Table7.ldt")).unwrap();
    let t = photosolid::photometry::ugr::ugr_table_at(&lum, photosolid::photometry::ugr::CIE_190_EXAMPLE_SPACING_H)
        .unwrap();
    assert_eq!(t.rooms_h.len(), CIE_190_EXAMPLE_TABLE.len());
    let mut sum = 0.0;
    for (k, published) in CIE_190_EXAMPLE_TABLE.iter().enumerate() {
        let ours: Vec<f64> = t.crosswise[k].iter().chain(&t.endwise[k]).copied().collect();
        for (c, (o, p)) in ours.iter().zip(published).enumerate() {
            let d = o - p;
            sum += d;
            assert!(
                d.abs() <= 0.25,
                "room {:?} column {c}: ours {o:.2}, CIE 190 {p}",
                t.rooms_h[k]
            );
        }
        // The published table rates this luminaire higher endwise in every room; so must ours.
        assert!(t.endwise[k][0] > t.crosswise[k][0], "room {:?}", t.rooms_h[k]);
    }
    let mean = sum / 190.0;
    assert!(mean.abs() <= 0.05, "mean difference {mean:.3}");
}

/// The background of CIE 190:2010's worked example (its example luminaire,
/// 1000 lm, room 2H × 4H, 70/50/20, H = 2 m): E_WID = 27.37 lx (the second
/// reading of the standard quoted above), and the direct flux fractions
/// F_DF = 0.390 onto the reference plane and F_DW = 0.260 onto the walls
/// (the eulumdat-ugr notes, `CONTEXT_eulumdat-ugr.md`, "Validation croisée
/// k=1,33"). Ours, from an exact interreflection instead of CIE 190's preset
/// factors: E_WID 27.42 lx crosswise and 27.18 lx endwise (within 0.7 %),
/// F_DF 0.386 / 0.395, F_DW 0.263 / 0.254 (CIE 190 averages over C, so its
/// values do not depend on the view). So the background is CIE 190's, and
/// what is left of the table's difference lies in the glare sum.
#[test]
fn background_of_the_cie_190_worked_example() {
    use photosolid::photometry::ugr::{background, View, CIE_190_EXAMPLE_SPACING_H};
    let Some(root) = corpus() else { return };
    let lum = photosolid::load(root.join("r-lighting/0_CIE-2010-Table7.ldt")).unwrap();
    assert_eq!(lum.declared().lamp_flux_lm, Some(1000.0));
    for view in [View::Crosswise, View::Endwise] {
        let b = background(&lum, view, (2.0, 4.0), (0.7, 0.5, 0.2), 2.0, CIE_190_EXAMPLE_SPACING_H).unwrap();
        assert_close!(b.e_wid_lx, 27.37, rel = 0.01, "{view:?}");
        assert_close!(b.floor_lm / 1000.0, 0.390, abs = 0.01, "{view:?}");
        assert_close!(b.walls_lm / 1000.0, 0.260, abs = 0.01, "{view:?}");
        assert!(b.ceiling_lm < 1.0, "{view:?}: {b:?}");
    }
}

/// A reference UGR table as DIALux or Relux export it (19 rows × 10
/// columns, `ROOMS_H` order, crosswise then endwise): `None` for a cell the
/// tool writes as `<10.0` (not comparable).
fn reference_ugr_csv(path: &Path) -> Vec<[Option<f64>; 10]> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let rows: Vec<[Option<f64>; 10]> = text
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let cells: Vec<Option<f64>> = l.split(',').map(|c| c.trim().parse::<f64>().ok()).collect();
            assert_eq!(cells.len(), 10, "{}: {l}", path.display());
            let mut row = [None; 10];
            row.copy_from_slice(&cells);
            row
        })
        .collect();
    assert_eq!(rows.len(), 19, "{}", path.display());
    rows
}

/// Every comparable cell of our catalogue table (SHR 0.25, the default) for
/// the 11 luminaires of `../shared/ugr-reference` against the tables DIALux
/// and Relux export for them: within 0.6 of Relux and 1.1 of DIALux in every
/// cell (the tables are rounded to 0.1; Relux writes cells below 10 as
/// `<10.0`, which are skipped). 4,032 cells are compared; the test prints max
/// and mean |difference| per tool and per file (docs/photometry.md, "UGR
/// against DIALux and Relux").
#[test]
fn ugr_tables_agree_with_dialux_and_relux() {
    let Some(root) = common::ugr_reference() else { return };
    let mut total = 0;
    for (tool, limit) in [("Relux", 0.6), ("Dialux", 1.1)] {
        let (mut max, mut sum, mut n, mut worst) = (0.0f64, 0.0, 0usize, String::new());
        for k in 1..=11 {
            let lum = photosolid::load(root.join(format!("sample_{k:02}.ldt"))).unwrap();
            let t = photosolid::photometry::ugr::ugr_table(&lum).unwrap();
            assert_eq!(t.spacing_h, 0.25, "catalogue spacing by default");
            let reference = reference_ugr_csv(&root.join(format!("ugr_table_{k:02}_{tool}.csv")));
            let (mut file_max, mut file_sum, mut file_n) = (0.0f64, 0.0, 0usize);
            for (room, refs) in reference.iter().enumerate() {
                let ours = t.crosswise[room].iter().chain(&t.endwise[room]);
                for (col, (o, r)) in ours.zip(refs).enumerate() {
                    let Some(r) = r else { continue };
                    let d = (o - r).abs();
                    if d > max {
                        worst = format!(
                            "sample_{k:02} room {:?} column {col}: ours {o:.2}, {tool} {r}",
                            t.rooms_h[room]
                        );
                    }
                    max = max.max(d);
                    file_max = file_max.max(d);
                    (sum, file_sum, n, file_n) = (sum + d, file_sum + d, n + 1, file_n + 1);
                }
            }
            println!(
                "{tool:6} sample_{k:02}: {file_n} cells, max |diff| {file_max:.2}, mean {:.2}",
                file_sum / file_n as f64
            );
        }
        println!(
            "{tool:6} all: {n} cells, max |diff| {max:.2} (limit {limit}), mean {:.3}; worst {worst}",
            sum / n as f64
        );
        assert!(max <= limit, "{tool}: max |difference| {max:.2} > {limit}: {worst}");
        total += n;
    }
    assert_eq!(total, 4032, "comparable cells");
}

/// A declared LOR of 112 % (a real catalogue has such files) is flagged
/// `lor-above-100` by `validate --json` and `info --json`, and a luminous
/// area larger than the luminaire `luminous-area-larger-than-luminaire`; a
/// plausible file gets neither.
#[test]
fn impossible_declarations_are_warned_in_validate_and_info() {
    let t = tempfile::tempdir().unwrap();
    // 10 cd/klm everywhere: 4π · 10 = 126 lm per klm, a LOR of 12.6 %.
    let mut fixture = common::fixtures::LdtFile::isym(1);
    fixture.cd_per_klm.iter_mut().for_each(|v| *v = 10.0);
    let text = fixture.text();
    let mut lines: Vec<String> = text.split("\r\n").map(String::from).collect();
    std::fs::write(t.path().join("ok.ldt"), lines.join("\r\n")).unwrap();
    assert_eq!(lines[22], "80", "line 23 is the LORL");
    lines[22] = "112".into();
    std::fs::write(t.path().join("lor.ldt"), lines.join("\r\n")).unwrap();
    lines[22] = "80".into();
    assert_eq!(lines[15], "600", "line 16 is the luminous length");
    lines[15] = "700".into();
    std::fs::write(t.path().join("area.ldt"), lines.join("\r\n")).unwrap();
    let codes = crate::common::cli::warning_codes;
    for (file, code) in [
        ("lor.ldt", Some("lor-above-100")),
        ("area.ldt", Some("luminous-area-larger-than-luminaire")),
        ("ok.ldt", None),
    ] {
        let v: serde_json::Value = serde_json::from_str(&ok(&run(&["validate", file, "--json"], t.path()))).unwrap();
        let i: serde_json::Value = serde_json::from_str(&ok(&run(&["info", file, "--json"], t.path()))).unwrap();
        for (what, c) in [("validate", codes(&v)), ("info", codes(&i))] {
            let impossible: Vec<&String> = c
                .iter()
                .filter(|c| {
                    [
                        "lor-above-100",
                        "flux-above-lamp",
                        "luminous-area-larger-than-luminaire",
                    ]
                    .contains(&c.as_str())
                })
                .collect();
            match code {
                Some(code) => assert_eq!(impossible, [code], "{what} {file}: {c:?}"),
                None => assert!(impossible.is_empty(), "{what} {file}: {c:?}"),
            }
        }
    }
}
