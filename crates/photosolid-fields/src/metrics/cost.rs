//! What a representation costs a renderer: time per lookup and Pareto fronts.
//!
//! A shader looks a luminaire up from a unit direction vector, one sample at
//! a time; [`time_per_sample_ns`] measures exactly that on one thread: the
//! median over repeats of the wall time of evaluating
//! [`IntensityField::intensity_dir_cd`] at every direction of a fixed,
//! shuffled set of unit vectors ([`random_directions`]), divided by their
//! number. Dynamic dispatch adds the same ~1 ns to every representation.

use glam::{DVec3, Vec3};

use crate::model::IntensityField;

/// `n` unit directions, uniform on the sphere, in a fixed pseudo-random
/// order (SplitMix64 seeded by `seed`): the same set in every run.
pub fn random_directions(n: usize, seed: u64) -> Vec<DVec3> {
    let mut state = seed;
    let mut next = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| {
            let z = 2.0 * next() - 1.0;
            let phi = 2.0 * std::f64::consts::PI * next();
            let r = (1.0 - z * z).max(0.0).sqrt();
            DVec3::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect()
}

/// Median wall time (ns) per sample of evaluating `field` at every direction
/// of `dirs` on the calling thread, over `repeats` runs (at least 1). 0 for
/// an empty set. A field that answers batches is timed as one batch
/// ([`IntensityField::batch_time_per_sample_ns`]).
pub fn time_per_sample_ns(field: &dyn IntensityField, dirs: &[DVec3], repeats: usize) -> f64 {
    if dirs.is_empty() {
        return 0.0;
    }
    if let Some(t) = field.batch_time_per_sample_ns(dirs, repeats.max(1)) {
        return t;
    }
    median_ns_per_item(repeats, dirs.len(), || {
        let mut acc = 0.0;
        for &d in dirs {
            acc += field.intensity_dir_cd(std::hint::black_box(d));
        }
        std::hint::black_box(acc);
    })
}

/// [`time_per_sample_ns`] for a lookup that computes in f32 from f32 unit
/// vectors (as a shader does), e.g. [`StoredTexture::cd_dir_f32`](crate::reconstruct::StoredTexture::cd_dir_f32).
pub fn time_per_sample_ns_f32(lookup: impl Fn(Vec3) -> f32, dirs: &[Vec3], repeats: usize) -> f64 {
    if dirs.is_empty() {
        return 0.0;
    }
    median_ns_per_item(repeats, dirs.len(), || {
        let mut acc = 0.0f32;
        for &d in dirs {
            acc += lookup(std::hint::black_box(d));
        }
        std::hint::black_box(acc);
    })
}

/// Median over `repeats` runs (at least 1) of the wall time of `run`, in ns per item of `n`.
fn median_ns_per_item(repeats: usize, n: usize, mut run: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..repeats.max(1))
        .map(|_| {
            let t0 = std::time::Instant::now();
            run();
            t0.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    1e9 * times[times.len() / 2] / n as f64
}

/// Which points are on the Pareto front when every coordinate is a cost to
/// minimise: a point is on it when no other point is at most as costly in
/// every coordinate and cheaper in one. Points with a NaN coordinate are
/// never on it (and dominate nothing).
pub fn pareto_front(points: &[Vec<f64>]) -> Vec<bool> {
    let valid = |p: &Vec<f64>| p.iter().all(|x| !x.is_nan());
    let dominates =
        |a: &Vec<f64>, b: &Vec<f64>| a.iter().zip(b).all(|(x, y)| x <= y) && a.iter().zip(b).any(|(x, y)| x < y);
    points
        .iter()
        .map(|p| valid(p) && !points.iter().any(|o| valid(o) && dominates(o, p)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_are_unit_and_spread() {
        let d = random_directions(10_000, 7);
        assert!(d.iter().all(|v| (v.length() - 1.0).abs() < 1e-12));
        let mean = d.iter().copied().sum::<DVec3>() / d.len() as f64;
        assert!(mean.length() < 0.03, "{mean}");
        assert_eq!(d, random_directions(10_000, 7));
    }

    #[test]
    fn pareto_front_of_costs() {
        let p = vec![
            vec![1.0, 5.0],
            vec![2.0, 2.0],
            vec![3.0, 3.0],
            vec![5.0, 1.0],
            vec![f64::NAN, 0.0],
            vec![2.0, 2.0],
        ];
        assert_eq!(pareto_front(&p), vec![true, true, false, true, false, true]);
    }

    #[test]
    fn timing_is_positive() {
        let f = |_c: f64, g: f64| g;
        let t = time_per_sample_ns(&f, &random_directions(1000, 1), 3);
        assert!(t > 0.0 && t.is_finite());
        assert_eq!(time_per_sample_ns(&f, &[], 3), 0.0);
    }
}
