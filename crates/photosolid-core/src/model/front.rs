//! The luminaire's front: the C angle its forward half is centred on.
//!
//! A photometric file stores intensities on C-planes in its own frame; which
//! C angle faces "forward" (the street side of a road luminaire, TM-15's
//! forward half of a BUG rating, the side an aimed luminaire tilts towards)
//! is a convention of its format, not something the grid says. This module
//! is the one place that convention lives (`docs/photometry.md`, "The
//! luminaire's front", cites the sources):
//!
//! | format | front | source |
//! |---|---|---|
//! | IES LM-63 | C0 | LM-63-2019 §5 (0° horizontal is the luminaire's reference direction) and IES TM-15-11 (forward = horizontal angles 270°-90°, centred on 0°) |
//! | EULUMDAT | C90 | CIE 140-2019 / EN 13201-3:2015 §5 (C90 half-plane across the carriageway, the street side) and the EULUMDAT format description (C0 along the luminaire's length) |
//! | TM-33 | C0 | ANSI/IES TM-33-23 (the LM-63 angle conventions) |
//!
//! `--front DEG` overrides the convention for one file
//! ([`FrontSource::Flag`]). BUG ([`crate::photometry::bug`]), `road`
//! (`street_side_c_deg`'s default), `scene`'s `aim_at` and `convert` read
//! the front from here; LM-72 aim angles are absolute and do not.

use serde::Serialize;

use crate::error::{Warning, WarningCode};
use crate::model::distribution::wrap360;
use crate::model::Format;

/// Where a luminaire's [`Front`] came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FrontSource {
    /// The convention of the file's format ([`Front::convention`]).
    Format,
    /// Given by the user (`--front DEG`).
    Flag,
}

impl FrontSource {
    /// `format` or `flag`, as `info --json` writes it.
    pub fn as_str(self) -> &'static str {
        match self {
            FrontSource::Format => "format",
            FrontSource::Flag => "flag",
        }
    }
}

/// The luminaire's front: the C angle (degrees, in the file's own frame,
/// [0, 360)) at the middle of TM-15's forward half; the forward half is
/// front ± 90°.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Front {
    /// C angle of the front, degrees, [0, 360).
    pub c_deg: f64,
    /// Where it came from.
    pub source: FrontSource,
}

impl Front {
    /// The front a file of `format` has by its format's convention (module docs).
    pub fn convention(format: Format) -> Front {
        Front {
            c_deg: Self::convention_c_deg(format),
            source: FrontSource::Format,
        }
    }

    /// The C angle, degrees, that `format`'s convention puts the front at.
    pub fn convention_c_deg(format: Format) -> f64 {
        match format {
            Format::Ies | Format::Tm33 => 0.0,
            Format::Ldt => 90.0,
        }
    }

    /// A front given by the user, `c_deg` wrapped into [0, 360); `None`
    /// when `c_deg` is not finite.
    pub fn flag(c_deg: f64) -> Option<Front> {
        c_deg.is_finite().then(|| Front {
            c_deg: wrap360(c_deg),
            source: FrontSource::Flag,
        })
    }

    /// This front after the C angles are changed as `convert --mirror --rotate-c` does
    /// (each C to (mirror ? −C : C) + rotate), keeping its source.
    pub fn reoriented(&self, rotate_deg: f64, mirror: bool) -> Front {
        let c = if mirror { -self.c_deg } else { self.c_deg };
        Front {
            c_deg: wrap360(c + rotate_deg),
            source: self.source,
        }
    }

    /// `front-differs` when a file of `target` format, read by its convention,
    /// would put this luminaire's front elsewhere: the warning names the
    /// `--front` and `street_side_c_deg` to use with the converted file.
    pub fn differs_in(&self, target: Format) -> Option<Warning> {
        let theirs = Self::convention_c_deg(target);
        (c_separation_deg(self.c_deg, theirs) > 1e-9).then(|| {
            let c = crate::error::Num(self.c_deg);
            Warning::new(
                WarningCode::FrontDiffers,
                format!(
                    "this luminaire's front is C{c} but {} readers take C{} as the front: read the converted \
                     file with --front {c} (info, validate, batch, convert) and set street_side_c_deg = {c} in a \
                     [road] table that uses it",
                    match target {
                        Format::Ies => "IES",
                        Format::Ldt => "EULUMDAT",
                        Format::Tm33 => "TM-33",
                    },
                    crate::error::Num(theirs)
                ),
            )
        })
    }

    /// The forward half of C, degrees: `(front − 90, front + 90)`.
    pub fn forward_c_deg(&self) -> (f64, f64) {
        (self.c_deg - 90.0, self.c_deg + 90.0)
    }

    /// The back half of C, degrees: `(front + 90, front + 270)`.
    pub fn back_c_deg(&self) -> (f64, f64) {
        (self.c_deg + 90.0, self.c_deg + 270.0)
    }
}

/// The smallest angle between two C angles, degrees, [0, 180].
pub fn c_separation_deg(a: f64, b: f64) -> f64 {
    let d = wrap360(a - b);
    d.min(360.0 - d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conventions_and_flags() {
        assert_eq!(Front::convention(Format::Ies).c_deg, 0.0);
        assert_eq!(Front::convention(Format::Tm33).c_deg, 0.0);
        assert_eq!(Front::convention(Format::Ldt).c_deg, 90.0);
        let f = Front::flag(-90.0).unwrap();
        assert_eq!((f.c_deg, f.source), (270.0, FrontSource::Flag));
        assert_eq!(Front::flag(720.0).unwrap().c_deg, 0.0);
        assert!(Front::flag(f64::NAN).is_none());
        assert_eq!(f.forward_c_deg(), (180.0, 360.0));
        assert_eq!(f.back_c_deg(), (360.0, 540.0));
    }

    #[test]
    fn conversions_say_when_the_target_puts_the_front_elsewhere() {
        let ies = Front::convention(Format::Ies);
        assert!(ies.differs_in(Format::Ies).is_none());
        assert!(ies.differs_in(Format::Tm33).is_none());
        let w = ies.differs_in(Format::Ldt).unwrap();
        assert_eq!(w.code, WarningCode::FrontDiffers);
        assert!(
            w.message.contains("--front 0") && w.message.contains("street_side_c_deg = 0"),
            "{}",
            w.message
        );
        // Turned by 90 degrees, the IES front lands on EULUMDAT's.
        assert!(ies.reoriented(90.0, false).differs_in(Format::Ldt).is_none());
        assert_eq!(ies.reoriented(-90.0, true).c_deg, 270.0);
    }

    #[test]
    fn separation_is_the_short_way_round() {
        assert_eq!(c_separation_deg(350.0, 10.0), 20.0);
        assert_eq!(c_separation_deg(0.0, 180.0), 180.0);
        assert_eq!(c_separation_deg(90.0, 45.0), 45.0);
    }
}
