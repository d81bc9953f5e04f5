//! The distance from a point to a field's solid searched on the surface
//! (`metrics::nearest`, the withheld reference's H since issue 26) against
//! the exact distance to a fine adaptive mesh of the same solid, measured
//! independently: the two differ by at most the mesh's distance from the
//! solid, |d(p, S) − d(p, M)| ≤ H(S, M).

use glam::DVec3;
use photosolid::metrics::hausdorff::distances;
use photosolid::metrics::{distances_to_solid, Bvh, NearestSearch};
use photosolid::model::frame::direction;
use photosolid::model::{Distribution, IntensityField};
use photosolid::reconstruct::{Filter, LightTexture};
use photosolid::solid::{adaptive_grid, grid_solid, surface_distance, AdaptiveOptions, SolidGrid, Tolerance, Units};
use photosolid::synth::{GridSpec, Synth};

use crate::common::corpus;

/// Points around the solid: each measured direction at 0.7, 0.95, 1.05 and
/// 1.4 times its value, and the origin.
fn points(d: &Distribution) -> Vec<DVec3> {
    let mut p = vec![DVec3::ZERO];
    for (ic, &c) in d.c_angles_deg().iter().enumerate() {
        for (ig, &g) in d.gamma_angles_deg().iter().enumerate() {
            let v = d.value_cd(ic, ig);
            for s in [0.7, 0.95, 1.05, 1.4] {
                p.push(s * v * direction(c, g));
            }
        }
    }
    p
}

fn agrees(name: &str, d: &Distribution, field: &dyn IntensityField) {
    assert!(field.is_continuous(), "{name}");
    let i_max = d.max_cd();
    let a = adaptive_grid(
        field,
        &SolidGrid::knots(d).unwrap(),
        &AdaptiveOptions::new(Tolerance::PercentOfPeak(0.01)),
    )
    .unwrap();
    let mesh = grid_solid(field, &a.grid, Units::Candela).unwrap();
    let pos = mesh.positions_f64();
    let h_sm = surface_distance(field, &mesh, 100_000, 3).max(a.tolerance_cd.max(a.tested_deviation_cd));
    let pts = points(d);
    let on_mesh = distances(&pts, &Bvh::build(&pos, mesh.triangles()));
    let polar: Vec<(DVec3, f64)> = pts.iter().map(|p| (p.normalize_or(DVec3::NEG_Z), p.length())).collect();
    let on_surface = distances_to_solid(field, &polar, &NearestSearch::default());
    let bound = 2.0 * h_sm + 1e-9 * i_max;
    let mut worst: f64 = 0.0;
    for (k, (&m, &s)) in on_mesh.iter().zip(&on_surface).enumerate() {
        assert!(s.is_finite(), "{name}: point {k}");
        // Never more than the distance along the point's own direction.
        let own = field.intensity_dir_cd(pts[k]);
        let u = (pts[k].length() - own).abs();
        assert!(
            s <= u + 1e-9 * i_max || pts[k] == DVec3::ZERO,
            "{name}: point {k}: {s} > {u}"
        );
        worst = worst.max((s - m).abs());
        assert!(
            (s - m).abs() <= bound,
            "{name}: point {k} {}: surface {s}, mesh {m}, bound {bound}",
            pts[k]
        );
    }
    eprintln!(
        "{name}: {} points, largest |surface - mesh| {:.3e} % of I_max (bound {:.3e} %)",
        pts.len(),
        100.0 * worst / i_max,
        100.0 * bound / i_max
    );
}

#[test]
fn surface_search_agrees_with_a_fine_mesh_on_synthetic_luminaires() {
    for s in [Synth::Roadway, Synth::CosinePower { p: 5.0 }] {
        let d = s
            .build(&GridSpec::uniform(15.0, 5.0).unwrap(), 5000.0)
            .unwrap()
            .into_distribution();
        let tex = LightTexture::new(&d).unwrap();
        for f in [Filter::CatmullRom, Filter::Bilinear] {
            agrees(&format!("{s:?} {f}"), &d, &tex.sampler(f));
        }
    }
}

#[test]
fn surface_search_agrees_with_a_fine_mesh_on_real_files() {
    let Some(root) = corpus() else { return };
    for name in ["lithonia-iesparser/PMO_2_32_9LS_ASY.ies", "ils20/NDNN74022.ies"] {
        let path = root.join(name);
        let lum = photosolid::formats::load(&path).unwrap();
        let d = lum.distribution();
        let tex = LightTexture::new(d).unwrap();
        agrees(name, d, &tex.sampler(Filter::CatmullRom));
    }
}
