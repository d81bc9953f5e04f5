use super::*;
use crate::model::{Distribution, Symmetry};
use crate::reconstruct::{Filter, LightTexture};

/// A quadrant-symmetric distribution that varies with C and γ.
fn quadrant() -> Distribution {
    let c: Vec<f64> = (0..=6).map(|k| 15.0 * k as f64).collect();
    let g: Vec<f64> = (0..=18).map(|k| 10.0 * k as f64).collect();
    let cd = c
        .iter()
        .flat_map(|&c| {
            g.iter().map(move |&g: &f64| {
                let (c, g) = (c.to_radians(), g.to_radians());
                100.0 + 80.0 * (2.0 * c).cos() * g.sin() + 60.0 * g.cos().max(0.0).powi(3)
            })
        })
        .collect();
    Distribution::new(c, g, cd, Symmetry::Quadrant).unwrap()
}

/// A filter row searches once per stored sample and gives every image
/// its sample's distance; searching every image on its own gives the
/// same distances (to the search's accuracy, 1e-6 of I_max).
#[test]
fn images_of_a_withheld_sample_share_its_distance() {
    let a = quadrant();
    let opts = CompareOptions::default();
    let i_max = a.max_cd();
    let planes = a.full_planes();
    let mut shared = 0;
    for fold in kfold(&a, 2).unwrap() {
        let points = FoldPoints::of(&a, &fold, &planes);
        let (first, _) = first_images(&points.stored);
        assert!(2 * first.len() < points.stored.len(), "quadrant images: {first:?}");
        shared += points.stored.len() - first.len();
        let mut row = RowDistances::default();
        let r = Recon::Filter(Filter::CatmullRom);
        row.add_fold(r, &fold, &points, false, &opts.refinement(i_max), &|_, _, _| {})
            .unwrap();
        assert_eq!(row.methods, ["surface"]);
        let tex = LightTexture::new(&fold.kept).unwrap();
        let polar = points.polar();
        let sampler = tex.sampler(Filter::CatmullRom);
        let tol = SYMMETRY_TOLERANCE * fold.kept.max_cd();
        let values: Vec<f64> = polar.iter().map(|&(w, _)| sampler.intensity_dir_cd(w)).collect();
        let images = shared_images(&sampler, Symmetry::Quadrant, &values, &points.stored, tol)
            .expect("a filter keeps the symmetry");
        assert_eq!(images.first.len(), first.len());
        assert_eq!(row.searched, first.len(), "the row shared its images' searches");
        // A field that breaks the symmetry searches every point.
        let tilted: Vec<f64> = polar.iter().map(|&(w, _)| Tilted.intensity_dir_cd(w)).collect();
        assert!(shared_images(&Tilted, Symmetry::Quadrant, &tilted, &points.stored, tol).is_none());
        // A field that equals the filter at every withheld point but breaks
        // the symmetry between them is found out by the probes.
        let between = Between(&sampler);
        assert!(shared_images(&between, Symmetry::Quadrant, &values, &points.stored, tol).is_none());
        let each = distances_to_solid(&sampler, &polar, &NearestSearch::default());
        assert_eq!(row.dist.len(), each.len());
        for (k, (x, y)) in row.dist.iter().zip(&each).enumerate() {
            assert!((x - y).abs() <= 1e-6 * i_max, "point {k} {:?}: {x} vs {y}", polar[k]);
        }
    }
    assert!(shared > 0);
}

/// The folds of a row run side by side; merged in fold order they give
/// the row of the folds one after the other, value for value, with the
/// largest mesh, deviation and the methods in order of first use, and
/// the same H when only H is measured. The
/// rows cover the three ways a fold is measured: searched on the solid
/// (a filter), in cells (nearest) and on a mesh (the measured solid).
#[test]
fn folds_side_by_side_give_the_sequential_row() {
    let a = quadrant();
    for hausdorff_only in [false, true] {
        let opts = CompareOptions {
            hausdorff_only,
            ..CompareOptions::default()
        };
        let h = HoldOut::new(&a, 1.0, &opts).unwrap();
        assert!(h.folds.len() > 1, "one fold shows no merge");
        for r in [
            Recon::Filter(Filter::CatmullRom),
            Recon::Filter(Filter::Nearest),
            Recon::Measured,
        ] {
            let side_by_side = h.row_distances(r, &|_, _, _| {}).unwrap();
            let mut sequential = RowDistances {
                hausdorff_only,
                ..RowDistances::default()
            };
            for (fold, points) in h.folds.iter().zip(&h.sets) {
                sequential
                    .add_fold(r, fold, points, h.rotational, &h.refinement, &|_, _, _| {})
                    .unwrap();
            }
            let what = format!("{r}, H only: {hausdorff_only}");
            assert_eq!(side_by_side.recon, sequential.recon, "{what}");
            assert_eq!(side_by_side.dist, sequential.dist, "{what}");
            assert_eq!(side_by_side.h(), sequential.h(), "{what}");
            assert!(side_by_side.h() > 0.0, "{what}");
            assert_eq!(side_by_side.methods, sequential.methods, "{what}");
            assert_eq!(side_by_side.triangles, sequential.triangles, "{what}");
            assert_eq!(side_by_side.deviation, sequential.deviation, "{what}");
            if !hausdorff_only {
                // With H alone a fold prunes with its own largest distance only: more searches.
                assert_eq!(side_by_side.searched, sequential.searched, "{what}");
            }
        }
    }
}

/// Merging keeps the first fold's values first and takes the larger of
/// the per-fold maxima; a method used by both is listed once.
#[test]
fn merge_keeps_fold_order_and_maxima() {
    let first = RowDistances {
        recon: vec![1.0, 2.0],
        dist: vec![0.5, 0.25],
        triangles: 10,
        deviation: Some(0.3),
        segments: None,
        methods: vec!["surface"],
        searched: 2,
        hausdorff_only: false,
        largest: 0.0,
    };
    let second = RowDistances {
        recon: vec![3.0],
        dist: vec![0.75],
        triangles: 4,
        deviation: Some(0.1),
        segments: Some(7),
        methods: vec!["mesh", "surface"],
        searched: 1,
        hausdorff_only: false,
        largest: 2.0,
    };
    let m = first.merge(second);
    assert_eq!(m.recon, [1.0, 2.0, 3.0]);
    assert_eq!(m.dist, [0.5, 0.25, 0.75]);
    assert_eq!(
        (m.triangles, m.deviation, m.segments, m.searched),
        (10, Some(0.3), Some(7), 3)
    );
    assert_eq!(m.methods, ["surface", "mesh"]);
    assert_eq!(m.largest, 2.0);
}

/// 100 cd plus a term in sin C: not quadrant-symmetric (C and 180 + C differ).
struct Tilted;

/// A field plus a bump in sin(3C) that vanishes at every multiple of 15°
/// (the test's planes) and on the γ rows at multiples of 10°: equal to the
/// field at every withheld direction, not symmetric between them.
struct Between<'a>(&'a dyn IntensityField);
impl IntensityField for Between<'_> {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        let bump = (12.0 * c_deg.to_radians()).sin() * (18.0 * gamma_deg.to_radians()).sin();
        self.0.intensity_cd(c_deg, gamma_deg) + 5.0 * bump.abs() * (3.0 * c_deg.to_radians()).sin()
    }
    fn name(&self) -> String {
        "between".into()
    }
    fn bytes(&self) -> usize {
        0
    }
}
impl IntensityField for Tilted {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        100.0 + 50.0 * c_deg.to_radians().sin() * gamma_deg.to_radians().sin()
    }
    fn name(&self) -> String {
        "tilted".into()
    }
    fn bytes(&self) -> usize {
        0
    }
}

#[test]
fn first_images_index_each_sample_once() {
    let (first, of) = first_images(&[(0, 1), (2, 1), (0, 1), (0, 3), (2, 1)]);
    assert_eq!(first, [0, 1, 3]);
    assert_eq!(of, [0, 1, 0, 2, 1]);
}
