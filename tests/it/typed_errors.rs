//! Issue 10 item 7: GPU, encoding, unknown-extension and caller-parameter
//! failures are their own error variants (there is no catch-all `Unsupported`), each
//! with a stable code in `ErrorRecord`; and the closed sets of CLI values
//! are clap `ValueEnum`s listed by `--help`.

use crate::common;

use std::io::Write;

use common::cli::{fails, ok, run};
use photosolid::error::{ErrorRecord, GpuError, Layered, MeshError};
use photosolid::synth::{GridSpec, Synth};
use photosolid::{Error, ModelError};

fn lambertian() -> photosolid::Luminaire {
    Synth::Lambertian
        .build(&GridSpec::uniform(15.0, 5.0).unwrap(), 1000.0)
        .unwrap()
}

/// An unknown output extension is `Error::UnknownExtension` naming the path
/// and the accepted extensions, for luminaires and meshes alike.
#[test]
fn unknown_extensions_are_typed() {
    let t = tempfile::tempdir().unwrap();
    let lum = lambertian();
    let out = t.path().join("lum.txt");
    let e = photosolid::save(&lum.clone().into(), &out, &Default::default()).unwrap_err();
    match &e {
        Error::UnknownExtension { path, what, accepted } => {
            assert_eq!(path, &out);
            assert_eq!(*what, "output format");
            assert!(accepted.contains(&".ies") && accepted.contains(&".ldt"), "{accepted:?}");
        }
        other => panic!("expected UnknownExtension, got {other:?}"),
    }
    let msg = e.to_string();
    assert!(msg.contains("lum.txt") && msg.contains(".ies, .ldt or .xml"), "{msg}");
    assert_eq!(ErrorRecord::from(&e).code, "unknown-extension");

    let mesh = photosolid::registry::Reconstructions::new(lum.distribution().clone(), &[])
        .unwrap()
        .solid(photosolid::registry::Recon::Measured, 1)
        .unwrap();
    let e = photosolid::solid::export::write(&mesh, &t.path().join("m.txt")).unwrap_err();
    assert!(
        matches!(
            &e,
            Error::UnknownExtension {
                what: "mesh format",
                ..
            }
        ),
        "{e:?}"
    );
    let e = photosolid::solid::export::read(&t.path().join("m.step")).unwrap_err();
    assert!(matches!(&e, Error::UnknownExtension { .. }), "{e:?}");
    assert!(e.to_string().contains(".obj, .ply, .stl or .glb"), "{e}");
}

/// A sample count that does not match the image is the caller's parameter
/// error, not an encoding failure; nothing is written.
#[test]
fn length_mismatches_are_parameter_errors() {
    use photosolid::reconstruct::exr_io::write_layer;
    let t = tempfile::tempdir().unwrap();
    let path = t.path().join("x.exr");
    let e = write_layer(
        &path,
        (4, 3),
        exr::prelude::LayerAttributes::default(),
        "Y",
        exr::prelude::FlatSamples::F32(vec![0.0; 11]),
    )
    .unwrap_err();
    assert!(
        matches!(&e, Error::Model(ModelError::Parameter { name: "samples", .. })),
        "{e:?}"
    );
    assert!(
        e.to_string().contains("11 samples") && e.to_string().contains("12"),
        "{e}"
    );
    assert_eq!(ErrorRecord::from(&e).code, "model");
    assert!(!path.exists());
}

/// A Parquet writer whose sink fails is `Error::Encode { format: "Parquet" }`.
#[test]
fn encoder_failures_are_encode_errors() {
    struct Full;
    impl Write for Full {
        fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
            Err(std::io::Error::other("device full"))
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    let rows = photosolid::batch::run(&[], &Default::default(), &|_, _, _| {});
    let e = photosolid::batch::table::write_parquet_to(&rows, Full).unwrap_err();
    match &e {
        Error::Encode { format, message } => {
            assert_eq!(*format, "Parquet");
            assert!(message.contains("device full"), "{message}");
        }
        other => panic!("expected Encode, got {other:?}"),
    }
    assert!(e.to_string().starts_with("cannot encode Parquet: "), "{e}");
    assert_eq!(ErrorRecord::from(&e).code, "encode");
}

/// GPU failures are `GpuError`s (photosolid-fields' own type, carried by `Error::Layer`) with
/// a code per kind; a job the device
/// cannot render (factor 0) fails in the plan, before any adapter is needed.
#[test]
fn gpu_errors_are_typed() {
    let e: Error = GpuError::NotBuilt.into();
    assert_eq!(ErrorRecord::from(&e).code, "gpu-not-built");
    assert!(e.to_string().contains("cargo feature `gpu`"), "{e}");
    let e: Error = GpuError::BufferMap("mapping read-back buffer 0: lost".into()).into();
    assert_eq!(ErrorRecord::from(&e).code, "gpu-buffer-map");
    #[cfg(feature = "gpu")]
    {
        use photosolid::reconstruct::{LightTexture, RenderOptions};
        let lum = lambertian();
        let tex = LightTexture::new(lum.distribution()).unwrap();
        let bad = RenderOptions {
            factor: 0,
            ..RenderOptions::default()
        };
        let e: Error = photosolid::gpu::plans(&[(&tex, bad)]).unwrap_err().into();
        assert!(
            matches!(e.downcast_ref(), Some(GpuError::InvalidJob { index: 0, .. })),
            "{e:?}"
        );
        assert_eq!(ErrorRecord::from(&e).code, "gpu-invalid-job");
    }
}

/// `--help` lists the values of every closed set, and a value outside the
/// set is a usage error (exit 2) that lists them.
#[test]
fn help_lists_the_enum_values() {
    let t = tempfile::tempdir().unwrap();
    for (cmd, flag, values) in [
        ("texture", "--backend", &["auto", "gpu", "cpu"][..]),
        ("mesh", "--units", &["cd", "peak", "klm", "flux"][..]),
        ("compare", "--units", &["cd", "peak", "klm", "flux"][..]),
        ("fit", "--error", &["relative", "solid-angle"][..]),
        ("convert", "--ies-version", &["2002", "2019"][..]),
        ("info", "--handedness", &["ccw", "cw"][..]),
        ("info", "--lamp-sets", &["first", "sum"][..]),
    ] {
        let help = ok(&run(&[cmd, "-h"], t.path()));
        let line = help
            .lines()
            .skip_while(|l| !l.contains(flag))
            .take(4)
            .collect::<Vec<_>>()
            .join(" ");
        let listed = format!("[possible values: {}]", values.join(", "));
        assert!(line.contains(&listed), "{cmd} {flag}: {listed} not in\n{help}");
        let e = fails(&run(&[cmd, "x", flag, "nope"], t.path()), 2);
        assert!(e.contains("nope") && e.contains(values[0]), "{cmd} {flag}: {e}");
    }
    // Every spelling that worked before still parses (the file does not exist: exit 1, not 2).
    for args in [
        &["texture", "missing.ies", "--backend", "cpu", "-o", "t.exr"][..],
        &["mesh", "missing.ies", "--measured", "--units", "klm", "-o", "m.ply"][..],
        &["fit", "missing.ies", "--error", "solid-angle"][..],
        &["convert", "missing.ies", "o.ies", "--ies-version", "2019"][..],
        &["info", "missing.ies", "--handedness", "cw", "--lamp-sets", "sum"][..],
        &["compare", "missing.ies", "--normalize", "flux"][..],
    ] {
        let e = fails(&run(args, t.path()), 1);
        assert!(e.contains("missing.ies"), "{args:?}: {e}");
    }
}

/// The CLI reports the typed errors with their paths: an unknown output
/// extension for `convert` and `mesh`, before anything is written.
#[test]
fn cli_names_unknown_extensions() {
    let t = tempfile::tempdir().unwrap();
    ok(&run(&["synth", "isotropic", "-o", "iso.ldt"], t.path()));
    let e = fails(&run(&["convert", "iso.ldt", "iso.txt"], t.path()), 1);
    assert!(
        e.contains("iso.txt") && e.contains("cannot tell the output format"),
        "{e}"
    );
    let e = fails(&run(&["mesh", "iso.ldt", "--measured", "-o", "m.step"], t.path()), 1);
    assert!(e.contains("m.step") && e.contains(".obj, .ply, .stl or .glb"), "{e}");
    assert!(!t.path().join("iso.txt").exists() && !t.path().join("m.step").exists());
}

/// The GPU check in the library: every filter of every file rendered on the
/// GPU and the CPU from the same plans agrees within 1e-5 of I_max, the
/// summary adds the renders up, and no filter is `NothingChecked`.
/// Skipped (with a note) when there is no adapter, unless PHOTOSOLID_REQUIRE_GPU=1.
#[cfg(feature = "gpu")]
#[test]
fn gpu_check_agrees_with_the_cpu_on_the_data_files() {
    use photosolid::gpu::check::{check_file, CheckInputs, CheckOptions, CheckSummary};
    use photosolid::reconstruct::Filter;
    let ctx = match photosolid::gpu::GpuContext::global() {
        Ok(c) => c,
        Err(e) if std::env::var("PHOTOSOLID_REQUIRE_GPU").as_deref() == Ok("1") => {
            panic!("PHOTOSOLID_REQUIRE_GPU=1 but: {e}")
        }
        Err(e) => {
            eprintln!("skipped: no GPU adapter ({e})");
            return;
        }
    };
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let paths = vec![data.join("roadway.ies"), data.join("batwing.ldt")];
    let inputs = CheckInputs::collect(&paths, &Default::default()).unwrap();
    assert_eq!((inputs.textures.len(), inputs.skipped.len()), (2, 0));
    let opts = CheckOptions {
        factor: 2,
        filters: vec![Filter::Bilinear, Filter::CatmullRom, Filter::Pchip],
        tolerance: 1e-5,
    };
    let mut summary = CheckSummary::start();
    for (path, tex) in &inputs.textures {
        let f = check_file(ctx, path, tex, &opts).unwrap();
        assert_eq!((f.renders, f.failed), (3, 0), "{f:?}");
        assert!(f.max_diff <= 1e-5 && f.clamp_mismatches.is_empty(), "{f:?}");
        assert!(f.height > 0 && f.width > 0);
        summary.add(&f);
    }
    assert_eq!(summary.checked, 6);
    assert!(summary.passed().unwrap());
    let none = CheckOptions {
        filters: vec![],
        ..opts
    };
    let (path, tex) = &inputs.textures[0];
    assert!(matches!(
        check_file(ctx, path, tex, &none),
        Err(Error::NothingChecked(_))
    ));
}

/// Mesh files that are not meshes, and empty meshes, are their own variants
/// naming the path (they were `Error::Unsupported(String)` with a code that
/// said nothing).
#[test]
fn mesh_file_failures_are_typed() {
    use photosolid::solid::{export, Mesh};
    let t = tempfile::tempdir().unwrap();
    let bad = t.path().join("bad.ply");
    std::fs::write(&bad, b"ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2\n").unwrap();
    let e = export::read(&bad).unwrap_err();
    match e.downcast_ref() {
        Some(MeshError::File { path, .. }) => assert_eq!(path, &bad),
        other => panic!("expected MeshError::File, got {other:?}"),
    }
    assert!(
        e.to_string()
            .starts_with(&format!("{}: cannot read the mesh: ", bad.display())),
        "{e}"
    );
    assert_eq!(ErrorRecord::from(&e).code, "mesh-file");
    // Issue 28: the mesh error names the format, the line and what was
    // expected (it was "intensities: PLY: ..." in a ModelError).
    let rec = ErrorRecord::from(&e);
    assert_eq!(rec.line, Some(3), "{e}");
    assert!(
        e.to_string().ends_with(
            "cannot read the mesh: PLY line 3: expected at least one `property` per element, found element vertex \
             has no properties"
        ),
        "{e}"
    );
    assert!(!e.to_string().contains("intensities"), "{e}");
    let obj = t.path().join("bad.obj");
    std::fs::write(&obj, b"# a mesh\nv 0 0 0\nv 1 0\n").unwrap();
    let e = export::read(&obj).unwrap_err();
    let Some(MeshError::File { source, .. }) = e.downcast_ref() else {
        panic!("expected a MeshError::File, got {e:?}");
    };
    match source.as_ref() {
        photosolid::error::MeshFileError::Syntax {
            format,
            location,
            expected,
            found,
            ..
        } => {
            assert_eq!((*format, location.line), ("OBJ", 3));
            assert_eq!((expected.as_str(), found.as_str()), ("3 numbers after `v`", "`v 1 0`"));
        }
        other => panic!("expected a MeshFile syntax error, got {other:?}"),
    }
    // A binary file cut short names the byte where data was expected.
    let stl = t.path().join("short.stl");
    std::fs::write(&stl, [0u8; 40]).unwrap();
    let e = export::read(&stl).unwrap_err().to_string();
    assert!(
        e.contains("STL byte 40: expected an 84-byte header") && e.contains("end of file"),
        "{e}"
    );
    // A face that indexes no vertex: the mesh invariant, with the format.
    std::fs::write(&obj, b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n").unwrap();
    let e = export::read(&obj).unwrap_err();
    assert!(
        matches!(
            e.downcast_ref(),
            Some(MeshError::File { source, .. })
                if matches!(**source, photosolid::error::MeshFileError::Mesh { format: "OBJ", .. })
        ),
        "{e:?}"
    );

    let empty = Mesh::from_parts(vec![[0.0; 3]], vec![], None, Default::default()).unwrap();
    let out = t.path().join("empty.stl");
    let e = export::write(&empty, &out).unwrap_err();
    match e.downcast_ref() {
        Some(MeshError::Empty { path }) => assert_eq!(path, &out),
        other => panic!("expected MeshError::Empty, got {other:?}"),
    }
    assert!(e.to_string().contains("no triangles; expected at least one"), "{e}");
    assert_eq!(ErrorRecord::from(&e).code, "empty-mesh");
    assert!(!out.exists(), "nothing is written for a refused mesh");
}

/// `Result<T, String>` (or `&str`) anywhere in `text`: 1-based lines of every
/// `Result<...>` whose last generic argument is `String` or a `&str`, outside
/// `//` comments.
fn string_results(text: &str) -> Vec<(usize, String)> {
    let code: String = text
        .lines()
        .map(|l| if l.trim_start().starts_with("//") { "" } else { l })
        .collect::<Vec<_>>()
        .join("\n");
    let b = code.as_bytes();
    let mut found = Vec::new();
    let mut from = 0;
    while let Some(k) = code[from..].find("Result<") {
        let start = from + k;
        from = start + "Result<".len();
        if start > 0 && (b[start - 1].is_ascii_alphanumeric() || b[start - 1] == b'_') {
            continue; // e.g. `MyResult<`
        }
        // The top-level generic arguments up to the matching `>` (a `->` inside is an arrow).
        let (mut depth, mut i, mut args, mut arg_start) = (1, from, Vec::new(), from);
        while i < b.len() && depth > 0 {
            match b[i] {
                b'<' | b'(' | b'[' => depth += 1,
                b'>' if b[i - 1] == b'-' => {}
                b'>' | b')' | b']' => depth -= 1,
                b',' if depth == 1 => {
                    args.push(code[arg_start..i].trim());
                    arg_start = i + 1;
                }
                _ => {}
            }
            i += 1;
        }
        args.push(code[arg_start..i.saturating_sub(1)].trim());
        args.retain(|a| !a.is_empty());
        let arg = args.last().copied().unwrap_or("");
        if args.len() >= 2 && (arg == "String" || (arg.starts_with('&') && arg.ends_with("str"))) {
            let line = code[..start].matches('\n').count() + 1;
            found.push((line, code[start..i].split_whitespace().collect::<Vec<_>>().join(" ")));
        }
    }
    found
}

/// Issue 28 item 3: no library function returns `Result<_, String>`; every
/// error is a typed [`Error`] variant with a code. The CLI (`src/cli`, clap
/// value parsers) may keep strings.
#[test]
fn no_string_errors_in_the_library() {
    // The finder itself.
    let sample = "fn a() -> Result<(), String> {}\nfn b() -> std::result::Result<Vec<Option<String>>, String>\n\
                  fn c() -> Result<Option<String>, ParseError>\n// fn d() -> Result<(), String>\n\
                  fn e(f: impl Fn(u8) -> u8) -> Result<u8, &'static str>\nfn g() -> Result<\n    u8,\n    String,\n>";
    let lines: Vec<usize> = string_results(sample).iter().map(|(l, _)| *l).collect();
    assert_eq!(lines, vec![1, 2, 5, 6], "{:?}", string_results(sample));

    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut stack = vec![root.join("src"), root.join("crates")];
    let mut offenders = Vec::new();
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            let rel = path.strip_prefix(root).unwrap().to_string_lossy().replace('\\', "/");
            if path.is_dir() {
                if rel != "src/cli" {
                    stack.push(path);
                }
            } else if rel.ends_with(".rs") {
                let text = std::fs::read_to_string(&path).unwrap();
                for (line, what) in string_results(&text) {
                    offenders.push(format!("{rel}:{line}: {what}"));
                }
            }
        }
    }
    offenders.sort();
    assert!(
        offenders.is_empty(),
        "library functions returning string errors (use a typed `Error`/`ModelError` variant with a code):\n{}",
        offenders.join("\n")
    );
}

/// Scene errors are part of the crate error with stable codes, and a scene
/// file that cannot be read is `Error::Io` with the path and the I/O error
/// as its source (it was `SceneError::Io { message }`).
#[test]
fn scene_errors_have_codes_and_io_sources() {
    use photosolid::scene::Scene;
    use std::error::Error as _;
    let t = tempfile::tempdir().unwrap();
    let missing = t.path().join("missing.toml");
    let e = Scene::load(&missing).unwrap_err();
    match &e {
        Error::Io { path, source } => {
            assert_eq!(path, &missing);
            assert_eq!(source.kind(), std::io::ErrorKind::NotFound);
        }
        other => panic!("expected Io, got {other:?}"),
    }
    assert!(e.source().is_some(), "the io::Error is the source");
    assert_eq!(ErrorRecord::from(&e).code, "io");
    let bad = t.path().join("bad.toml");
    std::fs::write(&bad, "[[luminaire]]\nfile = \"x.ldt\"\nposition = [0, 0]\n").unwrap();
    let e = Scene::load(&bad).unwrap_err();
    let rec = ErrorRecord::from(&e);
    assert_eq!((rec.code, rec.line), ("scene-invalid", Some(3)), "{e}");
    assert!(rec.message.starts_with(&format!("{}:3: ", bad.display())), "{e}");
    // An occluder without area is the caller's parameter, named.
    let flat = photosolid::scene::Occluder::new(vec![glam::DVec3::ZERO; 3]).unwrap_err();
    assert!(
        flat.to_string()
            .starts_with("vertices = 3 points: the polygon has no area"),
        "{flat}"
    );
}

/// A representation that needs the GPU keeps the GPU error as its source
/// (it was flattened into a `Parameter` message); the code stays `model`.
#[test]
fn gpu_representation_errors_keep_the_gpu_error() {
    use photosolid::registry::{Recon, Reconstructions};
    use std::error::Error as _;
    let lum = lambertian();
    let r: Recon = "catmull-rom@x5/bilinear+gpu".parse().unwrap();
    let recs = Reconstructions::new(lum.distribution().clone(), &[r]).unwrap();
    let Err(e) = recs.field(r) else {
        eprintln!("skipped: a GPU adapter is present, the GPU field was built");
        return;
    };
    match &e {
        ModelError::Gpu { recon, source } => {
            assert_eq!(recon, &r.to_string());
            assert!(e.to_string().contains(&source.to_string()), "{e}");
            assert!(source.downcast_ref::<GpuError>().is_some(), "{source:?}");
        }
        other => panic!("expected ModelError::Gpu, got {other:?}"),
    }
    // The source chain meets the GPU's own type: through the carrier, `Layered`.
    assert!(
        e.source()
            .and_then(|s| s.downcast_ref::<Layered>())
            .is_some_and(|l| l.downcast_ref::<GpuError>().is_some()),
        "{e:?}"
    );
    assert_eq!(ErrorRecord::from(&Error::from(e)).code, "model");
}

/// The writers' round-trip check gives a typed difference, with its own code.
#[test]
fn round_trip_differences_are_typed() {
    use photosolid::error::Difference;
    use photosolid::formats::roundtrip::same_distribution;
    use photosolid::{Distribution, Symmetry};
    let g: Vec<f64> = (0..=18).map(|k| 10.0 * k as f64).collect();
    let a = Distribution::new(vec![0.0], g.clone(), vec![100.0; 19], Symmetry::Rotational).unwrap();
    let mut cd = vec![100.0; 19];
    cd[3] = 101.0;
    let b = Distribution::new(vec![0.0], g, cd, Symmetry::Rotational).unwrap();
    let d = same_distribution(&a, &b, 1e-6).unwrap_err();
    assert!(
        matches!(d, Difference::Value { gamma, want, got, .. } if gamma == 30.0 && want == 100.0 && got == 101.0),
        "{d:?}"
    );
    let e = Error::RoundTrip {
        format: "EULUMDAT",
        difference: d,
    };
    assert_eq!(ErrorRecord::from(&e).code, "round-trip");
    assert!(
        e.to_string()
            .starts_with("EULUMDAT: I(C = 0, gamma = 30) = 100 cd came back as 101 cd"),
        "{e}"
    );
}

/// `reference_kind` is an enum and serialises to the strings of before.
#[test]
fn reference_kinds_serialise_as_before() {
    use photosolid::compare::ReferenceKind;
    for (k, s) in [
        (ReferenceKind::Truth, "truth"),
        (ReferenceKind::Withheld, "withheld"),
        (ReferenceKind::Dense, "dense"),
        (ReferenceKind::Reconstruction, "reconstruction"),
    ] {
        assert_eq!(serde_json::to_value(k).unwrap(), serde_json::json!(s));
        assert_eq!(k.to_string(), s);
        assert_eq!(k, s);
    }
}

/// The one table of codes, `ERROR_CODES`, against the errors of every crate: each code there is
/// given by some error (the core's own, `photosolid-fields`' `GpuError` and `MeshError`,
/// `photosolid-scene`'s `SceneError`, each converted into `Error` with `From`), and each code
/// an error gives is there. The core's unit test checks its own variants exhaustively.
#[test]
fn every_error_code_is_given_by_some_crate() {
    use photosolid::error::{Difference, ErrorKind, Location, MeshFileError, ParseError, SceneError, ERROR_CODES};
    use std::collections::BTreeSet;
    let parse = |kind| {
        Error::Parse(ParseError {
            path: "f.ies".into(),
            location: Location::at(3, 4),
            kind,
            expected: "a number".into(),
            found: "`x`".into(),
        })
    };
    let model = |reason: &str| ModelError::Parameter {
        name: "factor",
        value: "0".into(),
        reason: reason.into(),
    };
    let mut errors = vec![
        parse(ErrorKind::Invalid),
        parse(ErrorKind::Unsupported),
        Error::io("f.ies", std::io::Error::other("gone")),
        model("expected >= 1").into(),
        ModelError::Undefined {
            quantity: "UGR",
            why: photosolid::error::Undefined::NoLuminousArea,
        }
        .into(),
        ModelError::Opening("signs".into()).into(),
        Error::Encode {
            format: "PNG",
            message: "full".into(),
        },
        Error::UnknownExtension {
            path: "x.txt".into(),
            what: "output format",
            accepted: &[".ies"],
        },
        Error::NothingChecked("no files".into()),
        Error::Option {
            option: "--range".into(),
            message: "empty".into(),
        },
        Error::RoundTrip {
            format: "EULUMDAT",
            difference: Difference::MissingPlane {
                c: 90.0,
                back: vec![0.0],
            },
        },
        MeshError::File {
            path: "m.obj".into(),
            source: Box::new(MeshFileError::at_line("OBJ", 2, "3 numbers", "`v 1`")),
        }
        .into(),
        MeshError::Empty { path: "m.stl".into() }.into(),
        SceneError::Invalid {
            path: "s.toml".into(),
            location: Location::line(2),
            message: "bad".into(),
        }
        .into(),
        SceneError::InsideOpening {
            receiver: "r".into(),
            index: 1,
            position: [0.0; 3],
            luminaire: "l".into(),
            opening: "point".into(),
        }
        .into(),
    ];
    errors.extend(
        [
            GpuError::NoAdapter {
                tried: "vulkan".into(),
                detail: "none".into(),
            },
            GpuError::Device("lost".into()),
            GpuError::Pipeline("bad".into()),
            GpuError::BufferMap("unmapped".into()),
            GpuError::InvalidJob {
                index: 0,
                reason: "factor 0".into(),
            },
            GpuError::TooLarge {
                index: 0,
                reason: "too big".into(),
            },
            GpuError::NotBuilt,
        ]
        .map(Error::from),
    );
    let table: BTreeSet<&str> = ERROR_CODES.iter().map(|(c, _)| *c).collect();
    let given: BTreeSet<&str> = errors.iter().map(|e| ErrorRecord::from(e).code).collect();
    assert_eq!(given, table, "codes given by the crates' errors vs ERROR_CODES");
    // A layer's error keeps its line and its type through Error.
    let by_code = |code: &str| errors.iter().find(|e| e.code() == code).unwrap();
    let mesh = by_code("mesh-file");
    assert_eq!(ErrorRecord::from(mesh).line, Some(2));
    assert!(
        mesh.to_string()
            .starts_with("m.obj: cannot read the mesh: OBJ line 2: expected 3 numbers"),
        "{mesh}"
    );
    let scene = by_code("scene-invalid");
    assert_eq!(
        (ErrorRecord::from(scene).line, scene.to_string().as_str()),
        (Some(2), "s.toml:2: bad")
    );
    assert!(matches!(scene.downcast_ref(), Some(SceneError::Invalid { .. })));
}
