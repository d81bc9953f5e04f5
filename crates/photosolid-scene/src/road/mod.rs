//! Road lighting: a straight road lit by rows of one luminaire at a regular
//! spacing, computed the EN 13201-3 / CIE 140 way (sources and what was and
//! was not verified: `docs/road.md`).
//!
//! - [`surface`]: road-surface r-tables (CIE R1–R4, C1, C2 or a user table)
//!   and their interpolation, Q0 / S1 / S2;
//! - [`layout`]: the `[road]` table of the scene file, the luminaires it
//!   generates, the calculation field, its grids and the observers;
//! - [`quantities`]: luminance, illuminance, hemispherical illuminance,
//!   U_o, U_l, TI, R_EI per observer lane and overall;
//! - [`classes`]: the lighting classes of EN 13201-2 (M, C, P) and a
//!   road's verdict against one;
//! - [`design`]: the verdict of a layout, and the largest value of a key
//!   (the spacing) that meets a class;
//! - [`plan`]: the cheapest representation that keeps those quantities
//!   within their limits of the reference.
//!
//! World frame as in [`crate`]: the road runs along +x (the traffic
//! direction of every observer), the carriageway spans 0 ≤ y ≤ width,
//! z is up and the road surface is z = 0. The calculation field is
//! 0 ≤ x ≤ spacing: between two consecutive luminaires of the first row.
//!
//! ```no_run
//! use photosolid_scene::road::{layout::Road, quantities::{evaluate, RoadOptions}};
//! let road = Road::load(std::path::Path::new("data/road_en13201.toml")).unwrap();
//! let result = evaluate(&road, &RoadOptions::default()).unwrap();
//! println!("L_av {} cd/m², TI {} %", result.overall.l_av_cd_m2, result.overall.ti_pct);
//! ```

pub mod classes;
pub mod design;
pub mod layout;
pub mod plan;
pub mod quantities;
pub mod surface;
pub mod tables;

use std::path::PathBuf;

/// Everything that can go wrong with a road; each variant has a stable
/// [`RoadError::code`].
#[derive(Debug, thiserror::Error)]
pub enum RoadError {
    /// The scene file could not be read or parsed, or its `[road]` table is
    /// missing or mixed with `[[luminaire]]` tables.
    #[error("{path}: {message}", path = .path.display())]
    File {
        /// The scene file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A `[road]` value is outside its domain.
    #[error("[road] {key}: {reason}")]
    Invalid {
        /// The key.
        key: &'static str,
        /// What was expected and what was found.
        reason: String,
    },
    /// `surface` names no standard class and no readable table file.
    #[error("[road] surface = {surface:?}: not a standard class (R1, R2, R3, R4, C1, C2) and no such table file")]
    UnknownSurface {
        /// What was given.
        surface: String,
    },
    /// A user r-table is malformed.
    #[error("road-surface table {table}: {reason}")]
    BadTable {
        /// The table (file name or class).
        table: String,
        /// What is wrong.
        reason: String,
    },
    /// The luminaires hang at or below the observers' eye height (1.5 m,
    /// [`quantities::EYE_HEIGHT_M`]), where luminance and TI are undefined.
    #[error(
        "[road] mounting_height_m = {height_m} m: the luminaires must hang above the observers' eyes \
         ({} m, EN 13201-3) for luminance and TI to be defined",
        quantities::EYE_HEIGHT_M
    )]
    LuminaireBelowRoad {
        /// The mounting height given.
        height_m: f64,
    },
    /// An observer stands inside the calculation field.
    #[error(
        "the luminance observer at x = {x_m} m stands inside the calculation field (0 to {length_m} m); \
         it must be before it (negative x)"
    )]
    ObserverInField {
        /// Observer x, m.
        x_m: f64,
        /// Field length, m.
        length_m: f64,
    },
    /// No luminaire puts light on the field: the uniformities and TI are undefined.
    #[error(
        "no luminaire puts light on the calculation field (L_av = 0 cd/m² and E_av = 0 lx): check the luminaire's \
         file, its aiming (tilt_deg) and that it emits downwards"
    )]
    NothingInView,
    /// An error of one `[road]` key, at the key's line and column (1-based) in the scene file.
    #[error("{path}:{line}:{column}: {source}", path = .path.display())]
    AtKey {
        /// The scene file.
        path: PathBuf,
        /// Line of the key, 1-based.
        line: usize,
        /// Column of the key, 1-based.
        column: usize,
        /// The key's error.
        source: Box<RoadError>,
    },
    /// A figure the lighting class needs is undefined for this road.
    #[error("class {class} needs {criterion}, which this road cannot compute: {reason}")]
    CannotJudge {
        /// The class.
        class: &'static str,
        /// The criterion (an `overall` key).
        criterion: &'static str,
        /// Why.
        reason: String,
    },
    /// An option of the road job that cannot be used as given (`--range`
    /// outside its key's values, `--grid` on the key being maximised).
    #[error("{option}: {message}")]
    Option {
        /// The option, as the command line spells it.
        option: String,
        /// What is wrong and what was expected.
        message: String,
    },
    /// The luminaire file could not be read or its representation built.
    #[error("luminaire {file}: {message}", file = .file.display())]
    Luminaire {
        /// The photometric file.
        file: PathBuf,
        /// The reader's or model's message.
        message: String,
    },
}

impl RoadError {
    /// Stable machine-readable code (kebab-case).
    pub fn code(&self) -> &'static str {
        match self {
            RoadError::File { .. } => "road-file",
            RoadError::Invalid { .. } => "road-invalid",
            RoadError::UnknownSurface { .. } => "road-unknown-surface",
            RoadError::BadTable { .. } => "road-bad-table",
            RoadError::LuminaireBelowRoad { .. } => "road-luminaire-below-road",
            RoadError::ObserverInField { .. } => "road-observer-in-field",
            RoadError::NothingInView => "road-nothing-in-view",
            RoadError::Luminaire { .. } => "road-luminaire",
            RoadError::CannotJudge { .. } => "road-class-not-computable",
            RoadError::Option { .. } => "option",
            RoadError::AtKey { source, .. } => source.code(),
        }
    }

    /// The `[road]` key this error is about, if it is about one.
    pub fn key(&self) -> Option<&'static str> {
        match self {
            RoadError::Invalid { key, .. } => Some(key),
            RoadError::LuminaireBelowRoad { .. } => Some("mounting_height_m"),
            RoadError::UnknownSurface { .. } => Some("surface"),
            RoadError::Luminaire { .. } => Some("file"),
            _ => None,
        }
    }

    /// This error at its key's line and column in the scene file `text` read
    /// from `path` ([`RoadError::AtKey`]); unchanged when it names no key or
    /// the key is not written in the `[road]` table (a default).
    pub fn at_key(self, path: &std::path::Path, text: &str) -> RoadError {
        let Some((line, column)) = self.key().and_then(|k| key_position(text, "road", k)) else {
            return self;
        };
        RoadError::AtKey {
            path: path.to_path_buf(),
            line,
            column,
            source: Box::new(self),
        }
    }
}

/// The 1-based line and column of `key` in the TOML table `[table]` of `text`
/// (the first `key =` line after the table's header and before the next header).
pub(crate) fn key_position(text: &str, table: &str, key: &str) -> Option<(usize, usize)> {
    let header = format!("[{table}]");
    let mut inside = false;
    for (i, line) in text.lines().enumerate() {
        let t = line.trim_start();
        if t.starts_with('[') {
            inside = t.split('#').next().is_some_and(|h| h.trim() == header);
            continue;
        }
        if inside {
            if let Some(rest) = t.strip_prefix(key) {
                if rest.trim_start().starts_with('=') {
                    return Some((i + 1, line.len() - t.len() + 1));
                }
            }
        }
    }
    None
}
