//! The γ-refinement of an adaptive solid of a C-independent field: its
//! meridian profile ([`Profile`]) refined until the profile's chord error is
//! within the tolerance (the certified profile distance itself is
//! [`crate::metrics::profile::hausdorff()`]).

use glam::DVec2;

use crate::metrics::profile::Profile;
use crate::model::frame::sin_cos_deg;
use crate::model::IntensityField;

/// γ angles (degrees) for the profile of a C-independent `field`: `start`
/// (ascending, from 0 to 180) with intervals halved, down to
/// `opts.min_step_deg`, until the midpoint of every profile segment lies
/// within the tolerance of the field's profile (the smaller of `| |p| − I(γ(p)) |`,
/// the distance to the profile's point at the interval's middle γ, and |p|
/// when the profile touches the origin: each an upper bound of the distance). Returns the
/// angles and the largest deviation tested on them (cd).
pub fn adaptive_gammas(field: &dyn IntensityField, start: &[f64], opts: &super::AdaptiveOptions) -> (Vec<f64>, f64) {
    let mut g = start.to_vec();
    loop {
        let p = Profile::of_field(field, &g);
        let peak = p.points().iter().map(|x| x.length()).fold(0.0, f64::max);
        let tol = opts.tolerance.candela(peak).max(0.0);
        let mids: Vec<DVec2> = p.points().windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
        let dirs: Vec<(f64, f64)> = mids
            .iter()
            .zip(g.windows(2))
            .map(|(m, w)| {
                // γ of the point (ρ, z) = r (sin γ, −cos γ); the interval's middle at the origin.
                let gm = if m.length() > 0.0 {
                    m.x.atan2(-m.y).to_degrees()
                } else {
                    0.5 * (w[0] + w[1])
                };
                (0.0, gm)
            })
            .collect();
        let values = crate::reconstruct::eval_all(field, &dirs);
        let params: Vec<(f64, f64)> = g.windows(2).map(|w| (0.0, 0.5 * (w[0] + w[1]))).collect();
        let at_params = crate::reconstruct::eval_all(field, &params);
        // With a zero on the profile the origin is a point of the solid: |m| bounds too
        // (the same rule as the grid solids', crate::solid::adaptive).
        let any_zero = p.points().contains(&DVec2::ZERO);
        let dev: Vec<f64> = mids
            .iter()
            .zip(values)
            .zip(&at_params)
            .zip(g.windows(2))
            .map(|(((m, v), &vm), w)| {
                // Also the distance to the profile's point at the interval's middle γ.
                let (sm, cm) = sin_cos_deg(0.5 * (w[0] + w[1]));
                let beside = m.distance(if vm > 0.0 { vm } else { 0.0 } * DVec2::new(sm, -cm));
                let d = (m.length() - if v > 0.0 { v } else { 0.0 }).abs().min(beside);
                if any_zero {
                    d.min(m.length())
                } else {
                    d
                }
            })
            .collect();
        let worst = dev.iter().copied().fold(0.0, f64::max);
        let mut next = Vec::with_capacity(2 * g.len());
        let mut cut = false;
        for (j, w) in g.windows(2).enumerate() {
            next.push(w[0]);
            if dev[j] > tol && w[1] - w[0] >= 2.0 * opts.min_step_deg.max(1e-6) {
                next.push(0.5 * (w[0] + w[1]));
                cut = true;
            }
        }
        next.extend(g.last().copied());
        if !cut || next.len() > opts.max_points {
            return (g, worst);
        }
        g = next;
    }
}
