//! Blender Cycles: no texture; the kernel interpolates the IES table itself.
//!
//! Source (blender/blender):
//! - `intern/cycles/util/ies.cpp`, `IESFile::parse`: `TILT=INCLUDE` is
//!   skipped (angles and factors read and dropped), Type A is refused;
//!   `process_type_c`: a first horizontal angle of 90 is shifted by −90
//!   (90-270 files are turned by 90°), a single plane gets a copy at 360,
//!   a last angle of 90 is mirrored to 180 and a last angle of 180 to 360,
//!   a missing 360 plane is added when the spacing allows; the vertical
//!   angles must start at 0 or 90.
//! - `intern/cycles/kernel/svm/ies.h`, `kernel_ies_interp`: 0 at and beyond
//!   the last vertical angle; the fractional position of each angle in its
//!   interval (`inverse_lerp`), then uniform Catmull–Rom (`cubic_interp`)
//!   vertically (at v = 0 the row v = 1 stands in for v = −1, i.e. symmetry
//!   across the pole is assumed; the last row is repeated) and horizontally
//!   (wrapping over the duplicate 360 plane), clamped at 0. The IES node
//!   reads v = acos(−z), h = atan2(x, y) + π in the light's frame (C0 on
//!   −Y, C90 on −X): the emulation works in the file's own (C, γ).

use super::table::IesTable;
use crate::error::ModelError;
use crate::model::IntensityField;

/// Cycles' `cubic_interp` (uniform Catmull–Rom) at fraction `x` between `b` and `c`.
#[inline]
pub fn cubic_interp(a: f64, b: f64, c: f64, d: f64, x: f64) -> f64 {
    ((-0.5 * a + 1.5 * b - 1.5 * c + 0.5 * d) * x + (a - 2.5 * b + 2.0 * c - 0.5 * d)) * x * x
        + (-0.5 * a + 0.5 * c) * x
        + b
}

/// The table after Cycles' `process_type_c`: horizontal angles 0..360 with
/// the closing 360 plane. `rotate_90_270`: apply the −90° shift Cycles gives
/// tables starting at 90 (the defect); otherwise such a table is first
/// expanded to the full circle correctly.
///
/// # Errors
/// [`ModelError::Angles`] for tables Cycles refuses (a first horizontal angle
/// other than 0 or 90, vertical angles not starting at 0 or 90, a missing
/// 360 plane it cannot add).
pub fn process(t: &IesTable, rotate_90_270: bool) -> Result<IesTable, ModelError> {
    let nv = t.v.len();
    let bad = |reason: String| ModelError::Angles {
        axis: "horizontal",
        reason,
    };
    let mut h = t.h.clone();
    let mut planes: Vec<Vec<f64>> = (0..h.len()).map(|i| t.cd[i * nv..(i + 1) * nv].to_vec()).collect();
    if h[0] == 90.0 {
        if rotate_90_270 {
            h.iter_mut().for_each(|a| *a -= 90.0);
        } else {
            // A 90..270 table mirrored about the 90-270 plane, I(C) = I(180 − C):
            // [0, 90) are the images of (90, 180], (270, 360) those of (180, 270).
            let n = h.len();
            let mut all: Vec<(f64, Vec<f64>)> = Vec::with_capacity(2 * n + 1);
            for i in 0..n {
                if h[i] > 90.0 && h[i] <= 180.0 {
                    all.push((180.0 - h[i], planes[i].clone()));
                }
                all.push((h[i], planes[i].clone()));
                if h[i] > 180.0 && h[i] < 270.0 {
                    all.push((540.0 - h[i], planes[i].clone()));
                }
            }
            all.sort_by(|a, b| a.0.total_cmp(&b.0));
            if all[0].0 == 0.0 {
                let p0 = all[0].1.clone();
                all.push((360.0, p0));
            }
            h = all.iter().map(|p| p.0).collect();
            planes = all.into_iter().map(|p| p.1).collect();
        }
    }
    if h[0] != 0.0 {
        return Err(bad(format!("Cycles refuses a first horizontal angle of {}", t.h[0])));
    }
    if h.len() == 1 {
        h.push(360.0);
        planes.push(planes[0].clone());
    }
    if h[h.len() - 1] == 90.0 {
        let n = h.len();
        for i in (0..n - 1).rev() {
            h.push(180.0 - h[i]);
            planes.push(planes[i].clone());
        }
    }
    if h[h.len() - 1] == 180.0 {
        let n = h.len();
        for i in (0..n - 1).rev() {
            h.push(360.0 - h[i]);
            planes.push(planes[i].clone());
        }
    }
    if h[h.len() - 1] != 360.0 {
        let n = h.len();
        let (last_step, first_step, gap) = (h[n - 1] - h[n - 2], h[1] - h[0], 360.0 - h[n - 1]);
        if last_step == gap || first_step == gap {
            h.push(360.0);
            planes.push(planes[0].clone());
        } else {
            return Err(bad(
                "Cycles cannot close the circle: no 360 plane and irregular spacing".into(),
            ));
        }
    }
    if !(t.v[0] == 0.0 || t.v[0] == 90.0) {
        return Err(ModelError::Angles {
            axis: "vertical",
            reason: format!("Cycles needs vertical angles starting at 0 or 90, not {}", t.v[0]),
        });
    }
    Ok(IesTable {
        h,
        v: t.v.clone(),
        cd: planes.concat(),
    })
}

/// Cycles' `kernel_ies_interp` on a processed table, in cd.
#[derive(Debug, Clone)]
pub struct BlenderField {
    /// The processed table (0..360 with the closing plane).
    pub table: IesTable,
}

impl BlenderField {
    fn vertical(&self, v: usize, frac: f64, h: usize) -> f64 {
        let t = &self.table;
        let n = t.v.len();
        let at = |i: usize| t.at(h, i.min(n - 1));
        let a = at(if v == 0 { 1 } else { v - 1 });
        cubic_interp(a, at(v), at(v + 1), at((v + 2).min(n - 1)), frac)
    }
}

impl IntensityField for BlenderField {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        let t = &self.table;
        let (nh, nv) = (t.h.len(), t.v.len());
        let (h, v) = (crate::model::wrap360(c_deg), gamma_deg.clamp(0.0, 180.0));
        if nv < 2 || v >= t.v[nv - 1] || v < t.v[0] {
            return 0.0;
        }
        let mut hi = 0;
        while hi + 2 < nh && t.h[hi + 1] < h {
            hi += 1;
        }
        let mut vi = 0;
        while vi + 2 < nv && t.v[vi + 1] < v {
            vi += 1;
        }
        let inv = |a: f64, b: f64, x: f64| if b > a { (x - a) / (b - a) } else { 0.0 };
        let hf = inv(t.h[hi], t.h[hi + 1], h);
        let vf = inv(t.v[vi], t.v[vi + 1], v);
        let a = self.vertical(vi, vf, if hi == 0 { nh - 2 } else { hi - 1 });
        let b = self.vertical(vi, vf, hi);
        let c = self.vertical(vi, vf, hi + 1);
        let d = self.vertical(vi, vf, if hi + 2 == nh { 1 } else { hi + 2 });
        cubic_interp(a, b, c, d, hf).max(0.0)
    }
    fn name(&self) -> String {
        "blender cycles catmull-rom".into()
    }
    fn bytes(&self) -> usize {
        (2 + self.table.h.len() + self.table.v.len() + self.table.cd.len()) * 4
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn processes_symmetries() {
        let quad = IesTable {
            h: vec![0.0, 45.0, 90.0],
            v: vec![0.0, 90.0],
            cd: vec![1.0, 1.0, 2.0, 2.0, 3.0, 3.0],
        };
        let p = process(&quad, false).unwrap();
        assert_eq!(p.h, vec![0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0, 360.0]);
        let f = BlenderField { table: p };
        assert!((f.intensity_cd(90.0, 10.0) - 3.0).abs() < 1e-12);
        assert!((f.intensity_cd(270.0, 10.0) - 3.0).abs() < 1e-12);
        assert_eq!(f.intensity_cd(0.0, 90.0), 0.0, "0 at the last vertical angle");
        let side = IesTable {
            h: vec![90.0, 180.0, 270.0],
            v: vec![0.0, 90.0],
            cd: vec![1.0, 1.0, 2.0, 2.0, 3.0, 3.0],
        };
        let right = process(&side, false).unwrap();
        assert_eq!(right.h, vec![0.0, 90.0, 180.0, 270.0, 360.0]);
        assert_eq!(right.at(0, 0), 2.0, "C0 is the image of C180");
        let turned = process(&side, true).unwrap();
        assert_eq!(turned.at(0, 0), 1.0, "Cycles puts the file's C90 at C0");
    }
}
