//! The open extension point (`photosolid::registry::Registry`): a
//! representation defined here, added to a registry value, and found where
//! the built-in ones are by the jobs given that registry: `--recon` names,
//! `compare`'s rows, `tradeoff`'s table, `plan`'s candidates and `batch
//! --compact`'s candidates. Jobs given the built-in registry (every other
//! test, the CLI) list none of it.

use std::path::Path;
use std::sync::{Arc, OnceLock};

use photosolid::error::ModelError;
use photosolid::formats::Document;
use photosolid::jobs::{self, CompareSettings, Named, TradeoffSettings};
use photosolid::model::{Distribution, IntensityField};
use photosolid::registry::{Job, Recon, Registry, Representation};
use photosolid::synth::{GridSpec, Synth};

/// `nadir-cos:P`: I_max cos^P(γ) in the lower hemisphere, 12 bytes (the peak
/// as f64 and P as u32). Exact for a cosine-power luminaire of exponent P.
struct NadirCosine;

/// One instance of [`NadirCosine`].
struct NadirCosineField {
    peak_cd: f64,
    p: u32,
}

impl IntensityField for NadirCosineField {
    fn intensity_cd(&self, _c_deg: f64, gamma_deg: f64) -> f64 {
        if gamma_deg.is_finite() && gamma_deg < 90.0 {
            self.peak_cd * gamma_deg.to_radians().cos().powi(self.p as i32)
        } else {
            0.0
        }
    }
    fn name(&self) -> String {
        format!("nadir-cos:{}", self.p)
    }
    fn bytes(&self) -> usize {
        12
    }
}

impl Representation for NadirCosine {
    fn parse(&self, name: &str) -> Option<u32> {
        name.strip_prefix("nadir-cos:")?.parse().ok().filter(|p| *p <= 128)
    }
    fn name(&self, p: u32) -> String {
        format!("nadir-cos:{p}")
    }
    fn build(&self, dist: &Distribution, p: u32) -> Result<Box<dyn IntensityField + Send>, ModelError> {
        Ok(Box::new(NadirCosineField {
            peak_cd: dist.max_cd(),
            p,
        }))
    }
    fn defaults(&self) -> Vec<u32> {
        vec![5]
    }
}

/// The built-in representations and `nadir-cos:P` (one registry for the
/// tests: registering defines the representation for the process).
fn registered() -> Registry {
    static REGISTRY: OnceLock<Registry> = OnceLock::new();
    REGISTRY
        .get_or_init(|| Registry::builtin().with(Arc::new(NadirCosine)).unwrap())
        .clone()
}

/// A cosine-power luminaire of exponent 5 that records its closed form.
fn cosine_p5() -> Document {
    let grid = GridSpec::uniform(15.0, 5.0).unwrap();
    Synth::CosinePower { p: 5.0 }.build(&grid, 1000.0).unwrap().into()
}

fn named(doc: &Document) -> Named<'_> {
    Named {
        name: "cosine_p5",
        document: doc,
        handedness: Default::default(),
    }
}

#[test]
fn its_names_parse_and_print_as_a_reconstruction() {
    let registry = registered();
    let r: Recon = "nadir-cos:7".parse().unwrap();
    assert_eq!(registry.parse("nadir-cos:7").unwrap(), r);
    // The built-in registry reads only the built-in names.
    assert!(Registry::builtin().parse("nadir-cos:7").is_err());
    assert_eq!(Registry::builtin().parse("bilinear").unwrap().to_string(), "bilinear");
    assert!(matches!(r, Recon::Extension { param: 7, .. }));
    assert_eq!(r.to_string(), "nadir-cos:7");
    // The built-in names still parse as before; a name no one spells is still an error.
    assert_eq!("bilinear".parse::<Recon>().unwrap().to_string(), "bilinear");
    assert!("nadir-cos:999".parse::<Recon>().is_err());
    // A representation whose default names a built-in is refused.
    struct Squatter;
    impl Representation for Squatter {
        fn parse(&self, _: &str) -> Option<u32> {
            None
        }
        fn name(&self, _: u32) -> String {
            "bilinear".into()
        }
        fn build(&self, _: &Distribution, _: u32) -> Result<Box<dyn IntensityField + Send>, ModelError> {
            Err(ModelError::Internal("never built".into()))
        }
        fn defaults(&self) -> Vec<u32> {
            vec![0]
        }
    }
    assert!(Registry::builtin().register(Arc::new(Squatter)).is_err());
    // Another registry may hold the same representation; one registry holds it once.
    let mut other = Registry::builtin().with(Arc::new(NadirCosine)).unwrap();
    let listed = |r: &Registry| r.candidates(&Job::Compare).len();
    assert_eq!(listed(&other), listed(&Registry::builtin()) + 1);
    assert!(other.register(Arc::new(NadirCosine)).is_err());
    assert_eq!(other.parse("nadir-cos:7").unwrap().to_string(), "nadir-cos:7");
}

#[test]
fn compare_measures_it_against_the_truth() {
    let doc = cosine_p5();
    // Not a row of a job given the built-in registry.
    let builtin = jobs::compare(named(&doc), None, &CompareSettings::default(), &jobs::no_progress).unwrap();
    assert!(builtin.results.iter().all(|r| !r.name.starts_with("nadir-cos")));
    // By default, with the built-in rows.
    let with = CompareSettings {
        registry: registered(),
        ..Default::default()
    };
    let c = jobs::compare(named(&doc), None, &with, &jobs::no_progress).unwrap();
    assert_eq!(c.results.len(), builtin.results.len() + 1);
    let row = c
        .results
        .iter()
        .find(|r| r.name == "nadir-cos:5")
        .expect("a nadir-cos:5 row");
    assert_eq!(row.bytes, 12);
    // The closed form itself: errors at rounding level, far below catmull-rom's.
    let cr = c.results.iter().find(|r| r.name == "catmull-rom").unwrap();
    assert!(row.radial_max_pct < 1e-9, "{}", row.radial_max_pct);
    assert!(cr.radial_max_pct > 1e-4, "{}", cr.radial_max_pct);
    // Named on its own, as --recon names it.
    let only = CompareSettings {
        recons: Some(vec![registered().parse("nadir-cos:2").unwrap()]),
        ..Default::default()
    };
    let c = jobs::compare(named(&doc), None, &only, &jobs::no_progress).unwrap();
    assert_eq!(c.results.len(), 1);
    assert!(
        c.results[0].radial_max_pct > 1.0,
        "p = 2 is not the luminaire's exponent"
    );
}

#[test]
fn tradeoff_lists_it_and_it_is_the_smallest_within_one_percent() {
    let doc = cosine_p5();
    let settings = TradeoffSettings {
        factors: vec![1],
        repeats: 1,
        registry: registered(),
        ..Default::default()
    };
    let t = jobs::tradeoff(named(&doc), None, &settings, &jobs::no_progress).unwrap();
    let row = t
        .rows
        .iter()
        .find(|r| r.representation == "nadir-cos:5")
        .expect("a nadir-cos:5 row");
    assert_eq!(row.bytes, 12);
    assert_eq!(t.smallest_within_1pct.as_deref(), Some("nadir-cos:5"));
}

#[test]
fn plan_and_batch_take_it_as_a_candidate() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/office_scene.toml");
    let settings = jobs::PlanSettings {
        registry: registered(),
        ..Default::default()
    };
    let answer = jobs::plan(&scene, &settings, None).unwrap();
    let json = serde_json::to_string(&answer).unwrap();
    assert!(json.contains("nadir-cos:5"), "plan's candidates");

    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/cosine_p5.ldt");
    let options = photosolid::batch::BatchOptions {
        compact: true,
        registry: registered(),
        ..Default::default()
    };
    let rows = photosolid::batch::run(&[file], &options, &|_, _, _| {});
    assert_eq!(rows.len(), 1);
    assert_eq!(
        rows[0].smallest_within_1pct.as_deref(),
        Some("nadir-cos:5"),
        "{:?}",
        rows[0].errors
    );
}

/// A built-in representation on the open trait (`c-mean`, one file and one
/// line in `registry::builtin`) is in every registry: `--recon` parses it
/// with and without `+gpu`, `tradeoff` and `plan` list it for data that
/// stores more than one plane, `compare`'s defaults do not. On data the same in every plane it is the Catmull-Rom
/// filter on one column; where the planes differ its error is that asymmetry.
#[test]
fn a_builtin_on_the_open_trait_is_in_every_registry() {
    let builtin = Registry::builtin();
    assert_eq!(builtin.parse("c-mean").unwrap().to_string(), "c-mean");
    assert_eq!(builtin.parse("c-mean+gpu").unwrap().to_string(), "c-mean+gpu");
    assert!(builtin.parse("c-mean+gpu").unwrap().on_gpu());
    assert!(builtin.parse("c-mean:2").is_err());
    // An added representation cannot take its name.
    struct Squatter;
    impl Representation for Squatter {
        fn parse(&self, name: &str) -> Option<u32> {
            (name == "c-mean").then_some(0)
        }
        fn name(&self, _: u32) -> String {
            "c-mean".into()
        }
        fn build(&self, _: &Distribution, _: u32) -> Result<Box<dyn IntensityField + Send>, ModelError> {
            Err(ModelError::Internal("never built".into()))
        }
        fn defaults(&self) -> Vec<u32> {
            vec![0]
        }
    }
    assert!(Registry::builtin().register(Arc::new(Squatter)).is_err());
    assert!(!builtin
        .candidates(&Job::Compare)
        .iter()
        .any(|r| r.to_string() == "c-mean"));

    let settings = TradeoffSettings {
        factors: vec![1],
        repeats: 1,
        ..Default::default()
    };
    let row = |t: &photosolid::compare::trade::TradeTable, name: &str| {
        t.rows.iter().find(|r| r.representation == name).cloned().expect(name)
    };
    // The cosine-power luminaire stored in all of its 24 planes, the same in each.
    let grid = GridSpec::uniform(15.0, 5.0).unwrap();
    let mut lum = Synth::CosinePower { p: 5.0 }.build(&grid, 1000.0).unwrap();
    lum.set_distribution(lum.distribution().expand(24));
    let doc = Document::from(lum);
    assert_eq!(doc.distribution().n_c(), 24);
    let t = jobs::tradeoff(named(&doc), None, &settings, &jobs::no_progress).unwrap();
    let (mean, cr) = (row(&t, "c-mean"), row(&t, "catmull-rom"));
    assert!(mean.bytes < cr.bytes / 4, "{} vs {} bytes", mean.bytes, cr.bytes);
    assert!(
        (mean.radial_max_pct - cr.radial_max_pct).abs() < 1e-6,
        "{mean:?} vs {cr:?}"
    );
    // Planes that differ: the roadway luminaire's mean profile is far from it.
    let road =
        photosolid::formats::load_document(Path::new(env!("CARGO_MANIFEST_DIR")).join("data/roadway.ldt")).unwrap();
    let road_named = Named {
        name: "roadway",
        document: &road,
        handedness: Default::default(),
    };
    let two = CompareSettings {
        recons: Some(["c-mean", "catmull-rom"].map(|n| builtin.parse(n).unwrap()).to_vec()),
        ..Default::default()
    };
    let c = jobs::compare(road_named, None, &two, &jobs::no_progress).unwrap();
    let (mean, cr) = (&c.results[0], &c.results[1]);
    assert_eq!((mean.name.as_str(), cr.name.as_str()), ("c-mean", "catmull-rom"));
    assert!(mean.radial_max_pct > 10.0 * cr.radial_max_pct, "{mean:?} vs {cr:?}");

    // The road scene's luminaire stores its planes (the office's are rotational: no c-mean there).
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/road_en13201.toml");
    let answer = jobs::plan(&scene, &jobs::PlanSettings::default(), None).unwrap();
    assert!(
        serde_json::to_string(&answer).unwrap().contains("\"c-mean\""),
        "plan's candidates"
    );
}
