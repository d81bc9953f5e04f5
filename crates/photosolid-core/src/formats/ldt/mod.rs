//! EULUMDAT (.ldt): reader and writer.
//!
//! # Reading
//! The header (lines 1-26 and the lamp sets) is read line by line: text
//! fields are whole lines, numeric lines give their first number (junk after
//! it is warned about). From the direct ratios (line 27) on, the file is read
//! as a stream of numbers, because real files sometimes put several values on
//! one line. Counts (Mc, Ng, lamp sets) are checked against what the file
//! holds before anything is allocated.
//!
//! Intensities are converted to candela with
//! `I[cd] = I[cd/klm] × CFLI × Φ_ref / 1000`, where Φ_ref is the flux of lamp
//! set 1 or the sum of all sets ([`crate::formats::LampSetFlux`]); for
//! absolute photometry (lamp count < 0) the flux field is the luminaire flux.
//! CFLI (line 24) is applied as the format defines it; every corpus file holds
//! 1, and a value other than 1 is applied with a `cfli` warning (a missing,
//! zero or negative CFLI is taken as 1, also warned). The factor used is kept
//! in [`LdtHeader::cd_per_cdklm`] so the writer reproduces the raw cd/klm.
//!
//! # Stored planes
//! Line 28 always lists all Mc C-angles. The planes stored in the intensity
//! block are chosen by angle value, not by the Mc1/Mc2 index formulas (which
//! fail when Mc is not divisible as the symmetry needs): Isym 0 all, Isym 1
//! the first, Isym 2 those in [0, 180], Isym 3 those in [270, 360) then
//! [0, 90] (file order), Isym 4 those in [0, 90]. Isym 3 planes are relabelled
//! into the model's C90-C270 half through the mirror I(C) = I(180 − C): file
//! C0 becomes model C180, C270 stays C270, C90 stays C90.
//!
//! # Writing
//! See [`write()`]: CRLF line ends, lamp sets in the field-group layout, numbers
//! with at most [`SIGNIFICANT_DIGITS`] significant digits.

mod read;
mod write;

pub use read::read;
pub use write::write;

use serde::Serialize;

use crate::model::{Symmetry, ANGLE_EPS};

/// Significant digits the writer keeps for intensities, fluxes and
/// dimensions (trailing zeros trimmed): a written value is within a relative
/// 0.5 × 10^-(SIGNIFICANT_DIGITS − 1) of the model's value.
pub const SIGNIFICANT_DIGITS: u32 = 8;

/// How lamp sets (lines 26a-26f) are laid out when there are several.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum LampSetLayout {
    /// n × 26a, then n × 26b, ... (helios32 layout; tinyldt, lidrs). The writer always uses it.
    #[default]
    FieldGroups,
    /// n blocks of six lines, one block per set (eulumdat-rs and many real files).
    Blocks,
}

/// The raw EULUMDAT header, kept so a file is written back losslessly.
///
/// Text fields, dimensions, lamp sets, DFF and LORL live in the
/// [`Luminaire`](crate::model::Luminaire) itself; this holds what the model
/// has no place for.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct LdtHeader {
    /// Line 2, Ityp: 1 point source rotationally symmetric, 2 linear, 3 point source other symmetry (0 occurs).
    pub ityp: i64,
    /// Line 3, Isym 0-4.
    pub isym: u8,
    /// Line 4, Mc: number of C-planes on the full circle (the length of [`Self::c_angles`]).
    pub mc: usize,
    /// Line 5, Dc: C-plane step, degrees (0 = non-equidistant).
    pub dc: f64,
    /// Line 6, Ng: number of γ angles per plane.
    pub ng: usize,
    /// Line 7, Dg: γ step, degrees (0 = non-equidistant).
    pub dg: f64,
    /// Line 11, file name as written.
    pub file_name: String,
    /// Lines 18-21: height of the luminous area in the C0, C90, C180, C270 planes, mm.
    pub luminous_heights_mm: [f64; 4],
    /// Line 22, DFF (downward flux fraction), percent, as written.
    pub dff_percent: f64,
    /// Line 23, LORL (light output ratio), percent, as written.
    pub lorl_percent: f64,
    /// Line 24, CFLI (conversion factor for intensities) as applied (1 when the file's was unusable).
    pub cfli: f64,
    /// Line 25, tilt of the luminaire during measurement, degrees.
    pub tilt_deg: f64,
    /// Layout the lamp sets were read in (the writer always writes field groups).
    pub lamp_set_layout: LampSetLayout,
    /// Line 27: direct ratios for room indices k = 0.6, 0.8, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0.
    pub direct_ratios: [f64; 10],
    /// Line 28: all Mc C-angles as written, degrees.
    pub c_angles: Vec<f64>,
    /// Line 29: all Ng γ angles as written, degrees.
    pub gamma_angles: Vec<f64>,
    /// Candela per file unit: `I[cd] = I[file] × cd_per_cdklm` (= CFLI × Φ_ref / 1000).
    pub cd_per_cdklm: f64,
}

/// Indices into the full C-angle list (line 28) of the planes stored in the
/// intensity block, in file order, chosen by angle value (see the module docs).
pub(crate) fn stored_plane_indices(sym: Symmetry, c: &[f64]) -> Vec<usize> {
    let e = ANGLE_EPS;
    let inside =
        |lo: f64, hi: f64| -> Vec<usize> { (0..c.len()).filter(|&i| c[i] >= lo - e && c[i] <= hi + e).collect() };
    match sym {
        Symmetry::None => (0..c.len()).collect(),
        Symmetry::Rotational => vec![0],
        Symmetry::C0C180 => inside(0.0, 180.0),
        Symmetry::Quadrant => inside(0.0, 90.0),
        Symmetry::C90C270 => {
            let mut v: Vec<usize> = (0..c.len())
                .filter(|&i| c[i] >= 270.0 - e && c[i] < 360.0 - e)
                .collect();
            v.extend((0..c.len()).filter(|&i| c[i] >= -e && c[i] <= 90.0 + e));
            v
        }
    }
}

/// Number of stored planes by the format's Mc1/Mc2 formulas, when Mc allows them.
pub(crate) fn formula_plane_count(sym: Symmetry, mc: usize) -> Option<usize> {
    match sym {
        Symmetry::None => Some(mc),
        Symmetry::Rotational => Some(1),
        Symmetry::C0C180 => mc.is_multiple_of(2).then_some(mc / 2 + 1),
        Symmetry::C90C270 => mc.is_multiple_of(4).then_some(mc / 2 + 1),
        Symmetry::Quadrant => mc.is_multiple_of(4).then_some(mc / 4 + 1),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn isym3_stores_c270_to_c90_wrapping() {
        let c: Vec<f64> = (0..24).map(|i| i as f64 * 15.0).collect();
        let idx = stored_plane_indices(Symmetry::C90C270, &c);
        let angles: Vec<f64> = idx.iter().map(|&i| c[i]).collect();
        assert_eq!(angles.len(), 13);
        assert_eq!(angles[0], 270.0);
        assert_eq!(angles[5], 345.0);
        assert_eq!(angles[6], 0.0);
        assert_eq!(angles[12], 90.0);
        assert_eq!(formula_plane_count(Symmetry::C90C270, 24), Some(13));
        assert_eq!(stored_plane_indices(Symmetry::Quadrant, &c).len(), 7);
        assert_eq!(stored_plane_indices(Symmetry::C0C180, &c).len(), 13);
    }
}
