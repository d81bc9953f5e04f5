//! The job of `info`: a file's photometric summary, as installed at a tilt
//! angle and with the UGR table at a spacing when asked.

use crate::error::Result;
use crate::photometry::derived::DerivedOptions;
use crate::photometry::ugr::{check_spacing_h, CATALOGUE_SPACING_H};
use crate::report::info::Tables;
use crate::report::InfoReport;

use super::Named;

/// The options of `info` (the CLI's flags; defaults are the CLI's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InfoSettings {
    /// `--tilt`: the installed tilt angle, degrees, applied through the file's
    /// tilt table (an error when the file has none).
    pub tilt_deg: Option<f64>,
    /// `--ugr-spacing`: the UGR table's luminaire spacing in H. Default 0.25.
    pub ugr_spacing_h: f64,
}

impl Default for InfoSettings {
    fn default() -> Self {
        Self {
            tilt_deg: None,
            ugr_spacing_h: CATALOGUE_SPACING_H,
        }
    }
}

/// `photosolid info FILE --json` for one photometry: the summary with every table.
pub fn info(file: Named<'_>, settings: &InfoSettings) -> Result<InfoReport> {
    check_spacing_h(settings.ugr_spacing_h)?;
    let tilted;
    let document = match settings.tilt_deg {
        Some(t) => {
            let mut doc = file.document.clone();
            let distribution = doc.tilted_distribution(t)?;
            doc.luminaire.set_distribution(distribution);
            tilted = doc;
            &tilted
        }
        None => file.document,
    };
    let options = DerivedOptions {
        ugr_spacing_h: settings.ugr_spacing_h,
    };
    let mut report = InfoReport::of_document_with(document, Tables::Compute, &options);
    report.path = file.name.to_string();
    Ok(report)
}
