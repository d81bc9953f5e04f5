//! The `info` report of one luminaire: the JSON wire format of `photosolid info --json`
//! and of each ok line of `photosolid validate --json`.
//!
//! Keys (stable; other tools rely on them): `format` (`ies`|`ldt`|`tm33`), `version`,
//! `photometric_type` (`A`|`B`|`C`), `symmetry` (`none`, `rotational`, `c0-c180`,
//! `c90-c270`, `quadrant`), `n_c` (stored C-planes), `n_c_full` (planes on
//! the full circle), `n_gamma`, `gamma_range`, `max_cd`, `max_direction_deg`
//! ([C, γ]), `flux_lm`, `downward_flux_lm`, `upward_flux_lm`,
//! `declared_flux_lm`, `lamp_flux_lm` (declared bare-lamp flux; `null` when absolute), `flux_ratio`, `lor`, `dlor`, `ulor`, `dff` (fractions,
//! not percent), `beam_angle_deg` / `field_angle_deg` (IES definition, of
//! I_max, in the C0-C180 plane; `null` when undefined), `beam_angles` (all
//! four definitions x two planes), `tilt`, `absolute`, `front_c_deg` (the C angle at the middle
//! of the luminaire's forward half, [`crate::model::front`]) and `front_source` (`format` or
//! `flag`), and `warnings`, an
//! array of `{line, code, message}` (reader warnings first, then photometric
//! consistency warnings). `lamp_color` (when the file states a colour
//! temperature): `{cct_k, xy, srgb, srgb8}` (see `report::color`).
//! Derived photometry (see `photometry::derived`): `cie_flux_code`,
//! `zonal_lumens`, `ugr_table`, `bug_rating`, `luminance_table`; the last three
//! only when asked for ([`Tables::Compute`]: `info`, `validate --derived`).
//! `gldf_declared` (a photometry read from a GLDF container, `FILE.gldf#ID`;
//! `null` otherwise): the container's `DescriptivePhotometry`
//! ([`GldfDeclared`](crate::formats::gldf::GldfDeclared): `container`, `id`,
//! `file`, `lor`, `dff`, `dlor`, `ulor` as fractions,
//! `luminous_efficacy_lm_per_w`, `luminaire_luminance_cd_m2`,
//! `cie_flux_code`, `ugr_4h8h_70_50_20` `{crosswise, endwise}`,
//! `bug_rating`, `cut_off_angle_deg`), and `gldf_comparison`, its rows
//! `{quantity, declared, computed, difference}` as text
//! ([`crate::declared`]).
//! `path` (the file as given), `input_watts` (IES input watts, EULUMDAT the sum over lamp sets;
//! `null` when unknown or 0), `efficacy_lm_per_w` (computed `flux_lm` / `input_watts`),
//! `luminous_dimensions_m` `{length_m, width_m, height_m, shape}` (as declared; `shape` a word of
//! [`crate::scene::opening::Opening`]), and for Type B files (`null` otherwise)
//! `beam_spread_deg` / `field_spread_deg` `{horizontal, vertical}` (NEMA FL 11 spreads at 50 % /
//! 10 % of I_max in the Type B planes through the peak, [`crate::photometry::floodlight()`]) and
//! `nema_type` (e.g. `"6H x 5V"`, of the field spreads).

use serde::Serialize;

use crate::error::Warning;
use crate::model::{GammaRange, Luminaire, PhotometricType, Symmetry};
use crate::photometry::{self, BeamAngles};

/// Whether a report computes the UGR, BUG and luminance tables (the costly
/// part of a report: `validate` leaves them out unless `--derived` is given).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Tables {
    /// Compute them (`info`).
    #[default]
    Compute,
    /// Leave them out (`None` in [`photometry::Derived`], absent from the JSON).
    Skip,
}

/// Everything `info` reports about a luminaire.
#[derive(Debug, Clone, Serialize)]
pub struct InfoReport {
    /// `ies`, `ldt` or `tm33`.
    pub format: crate::model::Format,
    /// Format version, e.g. `LM-63-2002`.
    pub version: String,
    /// A, B or C.
    pub photometric_type: PhotometricType,
    /// Symmetry the stored planes rely on.
    pub symmetry: Symmetry,
    /// Stored C-planes.
    pub n_c: usize,
    /// C-planes on the full circle after symmetry expansion.
    pub n_c_full: usize,
    /// γ angles.
    pub n_gamma: usize,
    /// Measured γ range.
    pub gamma_range: GammaRange,
    /// Largest intensity, cd.
    pub max_cd: f64,
    /// Its direction [C, γ], degrees.
    pub max_direction_deg: [f64; 2],
    /// Integrated luminous flux, lm.
    pub flux_lm: f64,
    /// Flux below the horizontal, lm.
    pub downward_flux_lm: f64,
    /// Flux above the horizontal, lm.
    pub upward_flux_lm: f64,
    /// Flux the file declares, lm.
    pub declared_flux_lm: Option<f64>,
    /// Bare-lamp flux the file declares (IES: lamps x lumens per lamp;
    /// EULUMDAT: the lamp sets' flux), lm: the denominator of LOR and of
    /// cd/klm. `null` for absolute photometry.
    pub lamp_flux_lm: Option<f64>,
    /// flux_lm / declared_flux_lm.
    pub flux_ratio: Option<f64>,
    /// Light output ratio (fraction).
    pub lor: Option<f64>,
    /// Downward light output ratio (fraction).
    pub dlor: Option<f64>,
    /// Upward light output ratio (fraction).
    pub ulor: Option<f64>,
    /// Downward flux fraction (fraction).
    pub dff: Option<f64>,
    /// Declared LOR (fraction), when the file states one.
    pub declared_lor: Option<f64>,
    /// IES beam angle (50 % of I_max) in the C0-C180 plane, degrees.
    pub beam_angle_deg: Option<f64>,
    /// IES field angle (10 % of I_max) in the C0-C180 plane, degrees.
    pub field_angle_deg: Option<f64>,
    /// All beam/field angle definitions in both planes.
    pub beam_angles: BeamAngles,
    /// TILT kind: `none`, `include`, `file`.
    pub tilt: &'static str,
    /// Absolute photometry.
    pub absolute: bool,
    /// The luminaire's front: the C angle (degrees, the file's frame, [0, 360)) at the middle of
    /// its forward half ([`crate::model::front`]).
    pub front_c_deg: f64,
    /// Where the front came from: `format` (its format's convention) or `flag` (`--front`).
    pub front_source: &'static str,
    /// Manufacturer.
    pub manufacturer: String,
    /// Catalogue number.
    pub catalogue: String,
    /// Lamp colour temperature stated by the file (lamp set 1), K, and its display colour.
    pub lamp_color: Option<crate::color::LampColor>,
    /// What the GLDF container declares about this photometry (`None` unless read as `FILE.gldf#ID`).
    pub gldf_declared: Option<crate::formats::gldf::GldfDeclared>,
    /// The declared values next to the computed ones, one row per declared quantity.
    pub gldf_comparison: Option<Vec<crate::declared::DeclaredRow>>,
    /// The file's path, as given (set by the caller; empty when not read from a file).
    pub path: String,
    /// Input power, W: IES the input watts field, EULUMDAT the sum over the lamp sets, TM-33
    /// `InputWattage`; `None` when the file gives none (or 0).
    pub input_watts: Option<f64>,
    /// Luminous efficacy: computed luminaire flux / input watts, lm/W; `None` without input watts.
    pub efficacy_lm_per_w: Option<f64>,
    /// The luminous opening as the file declares it, m, with its shape.
    pub luminous_dimensions_m: LuminousDimensions,
    /// Type B (floodlight) files: full angles where I >= 50 % of I_max in the horizontal and
    /// vertical planes through the peak, in the Type B frame (NEMA FL 11); `None` otherwise.
    pub beam_spread_deg: Option<photometry::floodlight::Spread>,
    /// Type B files: the same at 10 % of I_max.
    pub field_spread_deg: Option<photometry::floodlight::Spread>,
    /// Type B files: NEMA floodlight type of the field spreads, e.g. `6H x 5V` (NEMA FL 11-1982).
    pub nema_type: Option<String>,
    /// Reader and consistency warnings.
    pub warnings: Vec<Warning>,
    /// Derived photometry: flux code, zonal lumens, UGR, BUG, luminance (flattened keys).
    #[serde(flatten)]
    pub derived: photometry::Derived,
}

/// The luminous opening's size as the file declares it (absolute values, m) and its shape.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LuminousDimensions {
    /// Along C0, m.
    pub length_m: f64,
    /// Along C90, m.
    pub width_m: f64,
    /// Height, m.
    pub height_m: f64,
    /// `point`, `rectangle`, `ellipse`, `vertical-ellipse`, `box`, `cylinder`, `ellipsoid` or
    /// `ldt-area` ([`crate::scene::opening::Opening`]; a EULUMDAT area whose luminous sides are
    /// all 0 or all equal is the rectangle, disk, box or cylinder it equals, `ldt-area` only when
    /// they differ); `None` for a sign combination no LM-63 version defines.
    pub shape: Option<&'static str>,
}

impl LuminousDimensions {
    /// The opening `lum` declares.
    pub fn of(lum: &Luminaire) -> Self {
        use crate::scene::opening::Opening;
        let o = lum.luminous_opening();
        let opening = Opening::of_luminaire(lum).ok();
        // Words for the geometry, whatever format declared it: a EULUMDAT area whose sides
        // are all dark or all as tall is the LM-63 rectangle, disk, box or cylinder it
        // equals, so one luminaire reads the same in either format.
        let shape = opening.map(|o| match o {
            Opening::Point => "point",
            Opening::Rectangle { .. } => "rectangle",
            Opening::Ellipse { .. } => "ellipse",
            Opening::VerticalEllipse { .. } => "vertical-ellipse",
            Opening::Box(_) => "box",
            Opening::Cylinder(_) => "cylinder",
            Opening::Ellipsoid(_) => "ellipsoid",
            // `Opening::ldt` already reads an area with no luminous sides as a
            // rectangle or disk; one whose sides are all as tall is a box or cylinder.
            Opening::LdtArea { width_m, heights_m, .. } if heights_m.iter().all(|h| *h == heights_m[0]) => {
                if width_m == 0.0 {
                    "cylinder"
                } else {
                    "box"
                }
            }
            Opening::LdtArea { .. } => "ldt-area",
        });
        // The geometry's extent along x (C0), y (C90) and z, whatever format and
        // version encoded it: a EULUMDAT disk (width 0) and an LM-63-1986 disk (length
        // 0) report their diameter both ways, so one luminaire reads the same in
        // every format. A EULUMDAT area keeps its declared (mean) height.
        let (length_m, width_m, height_m) = match opening {
            Some(Opening::Point) => (0.0, 0.0, 0.0),
            Some(Opening::Rectangle { length_m, width_m } | Opening::Ellipse { length_m, width_m }) => {
                (length_m, width_m, 0.0)
            }
            Some(Opening::VerticalEllipse { width_m, height_m }) => (0.0, width_m, height_m),
            Some(Opening::Box(e) | Opening::Ellipsoid(e)) => (e.length_m, e.width_m, e.height_m),
            Some(Opening::Cylinder(c)) => match c.axis {
                0 => (c.length_m, c.diameter_a_m, c.diameter_b_m),
                1 => (c.diameter_a_m, c.length_m, c.diameter_b_m),
                _ => (c.diameter_a_m, c.diameter_b_m, c.length_m),
            },
            Some(Opening::LdtArea { length_m, width_m, .. }) => (
                length_m,
                if width_m == 0.0 { length_m } else { width_m },
                o.height_m.abs(),
            ),
            None => (o.length_m.abs(), o.width_m.abs(), o.height_m.abs()),
        };
        LuminousDimensions {
            length_m,
            width_m,
            height_m,
            shape,
        }
    }
}

/// Input watts as `info` and `batch` report them, W ([`photometry::input_watts`]).
pub fn input_watts(lum: &Luminaire) -> Option<f64> {
    photometry::input_watts(lum).map(|w| w.watts)
}

impl InfoReport {
    /// Build the report of `lum` (no container declarations), every table included.
    pub fn of(lum: &Luminaire) -> Self {
        Self::of_parts(
            lum,
            None,
            Tables::Compute,
            &photometry::derived::DerivedOptions::default(),
        )
    }

    /// Build the report of a read document: with a GLDF container's
    /// declarations (`gldf_declared`) beside our values (`gldf_comparison`),
    /// every table included.
    pub fn of_document(doc: &crate::formats::Document) -> Self {
        Self::of_document_with(doc, Tables::Compute, &photometry::derived::DerivedOptions::default())
    }

    /// [`InfoReport::of_document`], with or without the UGR, BUG and luminance
    /// tables, computed as `options` say. A GLDF container's comparison rows
    /// are the same either way (the tables they need are computed for them,
    /// then dropped).
    pub fn of_document_with(
        doc: &crate::formats::Document,
        tables: Tables,
        options: &photometry::derived::DerivedOptions,
    ) -> Self {
        Self::of_parts(&doc.luminaire, doc.gldf.as_ref(), tables, options)
    }

    fn of_parts(
        lum: &Luminaire,
        gldf: Option<&crate::formats::gldf::GldfDeclared>,
        tables: Tables,
        options: &photometry::derived::DerivedOptions,
    ) -> Self {
        let d = lum.distribution();
        let s = photometry::summary(lum);
        let mut warnings = lum.warnings().to_vec();
        warnings.extend(s.warnings.iter().cloned());
        let flood = lum.source_grid().and_then(photometry::floodlight);
        let mut report = InfoReport {
            format: lum.format(),
            version: lum.version().to_string(),
            photometric_type: lum.photometric_type(),
            symmetry: d.symmetry(),
            n_c: d.n_c(),
            n_c_full: d.full_planes().len(),
            n_gamma: d.n_gamma(),
            gamma_range: d.gamma_range(),
            max_cd: s.max_cd,
            max_direction_deg: [s.max_direction_deg.0, s.max_direction_deg.1],
            flux_lm: s.flux.total_lm,
            downward_flux_lm: s.flux.downward_lm,
            upward_flux_lm: s.flux.upward_lm,
            declared_flux_lm: s.declared_flux_lm,
            lamp_flux_lm: lum.declared().lamp_flux_lm,
            flux_ratio: s.flux_ratio,
            lor: s.lor,
            dlor: s.dlor,
            ulor: s.ulor,
            dff: s.dff,
            declared_lor: lum.declared().lor,
            beam_angle_deg: s.beams.ies_beam_deg[0],
            field_angle_deg: s.beams.ies_field_deg[0],
            beam_angles: s.beams,
            tilt: match lum.tilt() {
                crate::model::Tilt::None => "none",
                crate::model::Tilt::Include { .. } => "include",
                crate::model::Tilt::File { .. } => "file",
            },
            absolute: lum.declared().absolute,
            front_c_deg: lum.front().c_deg,
            front_source: lum.front().source.as_str(),
            manufacturer: lum.metadata().manufacturer.clone(),
            catalogue: lum.metadata().catalogue.clone(),
            lamp_color: lum
                .lamp_sets()
                .first()
                .and_then(|l| crate::color::parse_cct(&l.color))
                .map(crate::color::lamp_color),
            gldf_declared: gldf.cloned(),
            gldf_comparison: None,
            path: lum.path().map(|p| p.display().to_string()).unwrap_or_default(),
            input_watts: input_watts(lum),
            efficacy_lm_per_w: input_watts(lum).map(|w| s.flux.total_lm / w),
            luminous_dimensions_m: LuminousDimensions::of(lum),
            beam_spread_deg: flood.as_ref().map(|f| f.beam_spread_deg),
            field_spread_deg: flood.as_ref().map(|f| f.field_spread_deg),
            nema_type: flood.as_ref().and_then(|f| f.nema_type()),
            warnings,
            derived: photometry::Derived::without_tables(lum),
        };
        let compare_tables = gldf.is_some_and(|g| g.ugr_4h8h_70_50_20.is_some() || g.bug_rating.is_some());
        if tables == Tables::Compute || compare_tables {
            report.derived.add_tables(lum, options);
        }
        if tables == Tables::Compute {
            // BUG's forward half is the front: say when the light goes elsewhere.
            report
                .warnings
                .extend(photometry::throw::front_mismatch(lum.distribution(), lum.front()));
        }
        report.gldf_comparison =
            gldf.map(|g| crate::declared::declared_vs_computed(g, &report, lum.declared().input_watts));
        if tables == Tables::Skip {
            report.derived.drop_tables();
        }
        report
    }

    /// A human-readable table.
    pub fn to_text(&self) -> String {
        use std::fmt::Write;
        let mut o = String::new();
        let rows = [self.file_rows(), self.flux_rows(), self.beam_rows(), self.lamp_rows()];
        for (k, v) in rows.into_iter().flatten() {
            let _ = writeln!(o, "{k:<34} {v}");
        }
        self.write_spreads(&mut o);
        if let (Some(g), Some(rows)) = (&self.gldf_declared, &self.gldf_comparison) {
            o.push_str(&crate::declared::to_text(g, rows));
        }
        if !self.warnings.is_empty() {
            let _ = writeln!(o, "warnings:");
            for w in &self.warnings {
                let _ = writeln!(o, "  {w}");
            }
        }
        o.push_str(&self.derived.to_text());
        o
    }

    /// The text table's rows on the file and its grid.
    fn file_rows(&self) -> Vec<(&'static str, String)> {
        let range = match self.gamma_range {
            GammaRange::Full => "0-180 (full sphere)".to_string(),
            GammaRange::Lower => "0-90 (lower hemisphere)".to_string(),
            GammaRange::Upper => "90-180 (upper hemisphere)".to_string(),
            GammaRange::Partial { from, to } => format!("{from}-{to} (partial)"),
        };
        vec![
            ("format", format!("{:?} {}", self.format, self.version).to_uppercase()),
            ("manufacturer", self.manufacturer.clone()),
            ("catalogue", self.catalogue.clone()),
            ("photometric type", format!("{:?}", self.photometric_type)),
            ("symmetry", self.symmetry.describe().to_string()),
            (
                "front (forward half's middle)",
                format!(
                    "C{} ({})",
                    crate::error::Num(self.front_c_deg),
                    if self.front_source == "flag" {
                        "--front"
                    } else {
                        "the format's convention"
                    }
                ),
            ),
            (
                "grid",
                format!(
                    "{} C-planes stored ({} on the full circle) x {} gamma angles",
                    self.n_c, self.n_c_full, self.n_gamma
                ),
            ),
            ("gamma range", range),
        ]
    }

    /// The text table's rows on intensity, flux and light output ratios.
    fn flux_rows(&self) -> Vec<(&'static str, String)> {
        vec![
            (
                "max intensity",
                format!(
                    "{:.2} cd at C {:.1}°, gamma {:.1}°",
                    self.max_cd, self.max_direction_deg[0], self.max_direction_deg[1]
                ),
            ),
            (
                "flux",
                format!(
                    "{:.2} lm (down {:.2}, up {:.2})",
                    self.flux_lm, self.downward_flux_lm, self.upward_flux_lm
                ),
            ),
            (
                "declared flux",
                match (self.declared_flux_lm, self.flux_ratio) {
                    (Some(d), Some(r)) => format!("{d:.2} lm (computed / declared = {:.3})", r),
                    _ => "-".into(),
                },
            ),
            (
                "lamp flux",
                match self.lamp_flux_lm {
                    Some(l) => format!("{l:.2} lm (declared; LOR = flux / lamp flux, cd/klm per 1000 lm of it)"),
                    None => "- (absolute photometry: no lamp flux, no LOR)".into(),
                },
            ),
            (
                "LOR / DLOR / ULOR",
                format!(
                    "{} / {} / {}",
                    opt_text(self.lor, 100.0, " %"),
                    opt_text(self.dlor, 100.0, " %"),
                    opt_text(self.ulor, 100.0, " %")
                ),
            ),
            ("declared LOR", opt_text(self.declared_lor, 100.0, " %")),
            ("DFF", opt_text(self.dff, 100.0, " %")),
        ]
    }

    /// The text table's rows on the beam and field angles of both plane pairs.
    fn beam_rows(&self) -> Vec<(&'static str, String)> {
        let pair = |a: [Option<f64>; 2]| {
            format!(
                "{} in C0-C180, {} in C90-C270",
                opt_text(a[0], 1.0, "°"),
                opt_text(a[1], 1.0, "°")
            )
        };
        vec![
            ("beam angle IES, 50 % of I_max", pair(self.beam_angles.ies_beam_deg)),
            ("field angle IES, 10 % of I_max", pair(self.beam_angles.ies_field_deg)),
            ("beam angle CIE, 50 % of centre I", pair(self.beam_angles.cie_beam_deg)),
            (
                "field angle CIE, 10 % of centre I",
                pair(self.beam_angles.cie_field_deg),
            ),
        ]
    }

    /// The text table's rows on the lamp, the power and the luminous opening.
    fn lamp_rows(&self) -> Vec<(&'static str, String)> {
        vec![
            ("tilt", self.tilt.to_string()),
            (
                "lamp colour",
                match &self.lamp_color {
                    Some(c) => format!(
                        "{:.0} K, sRGB #{:02x}{:02x}{:02x}",
                        c.cct_k, c.srgb8[0], c.srgb8[1], c.srgb8[2]
                    ),
                    None => "-".into(),
                },
            ),
            ("absolute photometry", self.absolute.to_string()),
            ("input watts", opt_text(self.input_watts, 1.0, " W")),
            ("efficacy", opt_text(self.efficacy_lm_per_w, 1.0, " lm/W")),
            (
                "luminous opening",
                format!(
                    "{:.3} x {:.3} x {:.3} m (length x width x height), {}",
                    self.luminous_dimensions_m.length_m,
                    self.luminous_dimensions_m.width_m,
                    self.luminous_dimensions_m.height_m,
                    self.luminous_dimensions_m.shape.unwrap_or("shape undefined")
                ),
            ),
        ]
    }

    /// The floodlight lines (Type B spreads and NEMA type), when there are spreads.
    fn write_spreads(&self, o: &mut String) {
        use std::fmt::Write;
        let spread = |s: &Option<photometry::floodlight::Spread>| match s {
            Some(s) => format!("{:.1}° H x {:.1}° V", s.horizontal, s.vertical),
            None => "-".into(),
        };
        if self.beam_spread_deg.is_some() {
            let _ = writeln!(
                o,
                "{:<34} {}",
                "beam spread (Type B, 50 %)",
                spread(&self.beam_spread_deg)
            );
            let _ = writeln!(
                o,
                "{:<34} {}",
                "field spread (Type B, 10 %)",
                spread(&self.field_spread_deg)
            );
            let _ = writeln!(
                o,
                "{:<34} {}",
                "NEMA type (of the 10 % spreads)",
                self.nema_type.as_deref().unwrap_or("- (a spread under 10°)")
            );
        }
    }
}

/// `v` × `scale` with two decimals and `unit`, or "-" when absent.
fn opt_text(v: Option<f64>, scale: f64, unit: &str) -> String {
    match v {
        Some(x) => format!("{:.2}{unit}", x * scale),
        None => "-".to_string(),
    }
}
