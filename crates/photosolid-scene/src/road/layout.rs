//! The `[road]` table of a scene file and the installation it describes:
//! luminaire rows, the calculation field, its grids (EN 13201-3 §7) and the
//! observers.
//!
//! Geometry (metres, degrees; world frame of [`crate`]):
//! - carriageway 0 ≤ y ≤ `lanes · lane_width_m`, road surface z = 0,
//!   traffic along +x;
//! - a pole stands `setback_m` outside a kerb, its arm reaches `overhang_m`
//!   towards the road: a near-side luminaire hangs at y = −setback + overhang,
//!   a far-side one at y = width + setback − overhang;
//! - each luminaire's street side, the file's C angle `street_side_c_deg`
//!   (default: the luminaire's front, [`crate::model::front`]: C90 for
//!   EULUMDAT, C0 for IES and TM-33), points across the road from its pole
//!   (near side towards +y, far side towards −y, twin-central away from the
//!   centre line), so the file's C(street side − 90) runs along the road;
//!   `tilt_deg` swings the nadir towards the street side (a roll, positive
//!   upwards towards the road, as the tilt of a road luminaire's arm);
//! - arrangements: `single-sided` (near row), `opposite` (near and far rows
//!   at the same x), `staggered` (far row shifted by half a spacing),
//!   `twin-central` (one pole on the centre line, y = width/2, two arms
//!   reaching `overhang_m` either way, each luminaire facing its half).

use std::path::{Path, PathBuf};

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::surface::{RInterpolation, RTable};
use super::RoadError;
use crate::aim::{Aim, Pose};
use crate::model::Luminaire;
use crate::opening::Opening;
use crate::plan::Recon;
use crate::representation::parse_representation;
use crate::{Receiver, SceneLuminaire, SourceKind};

/// The `[road]` table (keys are a contract: `docs/road.md`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoadSpec {
    /// Photometric file (.ies or .ldt), relative to the scene file.
    pub file: PathBuf,
    /// Representation of the distribution (as in `[[luminaire]]`); default the reference.
    pub representation: Option<String>,
    /// Maintenance factor in (0, 1]; default 1.
    pub maintenance_factor: Option<f64>,
    /// Number of lanes (≥ 1).
    pub lanes: usize,
    /// Width of one lane, m.
    pub lane_width_m: f64,
    /// `R1`..`R4`, `C1`, `C2`, or a path (relative to the scene file) to a user r-table.
    pub surface: String,
    /// Q0 of the surface (sr⁻¹): scales the table to it; default the table's own.
    pub q0: Option<f64>,
    /// `single-sided`, `opposite`, `staggered` or `twin-central`.
    pub arrangement: String,
    /// Distance between two consecutive luminaires of a row, m.
    pub spacing_m: f64,
    /// Height of the photometric centre over the road, m.
    pub mounting_height_m: f64,
    /// Arm reach from the pole towards the road, m (default 0).
    pub overhang_m: Option<f64>,
    /// Upward tilt of the luminaire towards the road, degrees (default 0).
    pub tilt_deg: Option<f64>,
    /// Distance of the pole outside the kerb, m (default 0).
    pub setback_m: Option<f64>,
    /// The file's C angle (degrees) that points from the pole across its own side of the
    /// carriageway; default the luminaire's front.
    pub street_side_c_deg: Option<f64>,
    /// `quadratic` (default) or `bilinear`: how r is interpolated between the table's nodes.
    pub r_interpolation: Option<String>,
    /// `horizontal` (default) or `line-of-sight`: what the 20° car-roof screening angle is measured from.
    pub ti_screening: Option<String>,
}

/// What the 20° car-roof screening angle of TI is measured from (`[road] ti_screening`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum TiScreening {
    /// Luminaires up to 20° above the horizontal count (the default).
    #[default]
    Horizontal,
    /// Luminaires up to 20° above the 1°-down line of sight (19° above the horizontal) count.
    LineOfSight,
}

impl TiScreening {
    /// Parse the `ti_screening` key.
    pub fn parse(s: &str) -> Result<TiScreening, RoadError> {
        match s.trim() {
            "horizontal" => Ok(TiScreening::Horizontal),
            "line-of-sight" => Ok(TiScreening::LineOfSight),
            other => Err(RoadError::Invalid {
                key: "ti_screening",
                reason: format!("{other:?}: expected \"horizontal\" or \"line-of-sight\""),
            }),
        }
    }

    /// The name as written in the scene file.
    pub fn as_str(self) -> &'static str {
        match self {
            TiScreening::Horizontal => "horizontal",
            TiScreening::LineOfSight => "line-of-sight",
        }
    }

    /// The largest elevation above the horizontal (degrees) of a luminaire TI counts.
    pub fn max_elevation_deg(self) -> f64 {
        use super::quantities::{TI_SCREEN_DEG, TI_SIGHT_DOWN_DEG};
        match self {
            TiScreening::Horizontal => TI_SCREEN_DEG,
            TiScreening::LineOfSight => TI_SCREEN_DEG - TI_SIGHT_DOWN_DEG,
        }
    }
}

/// A numeric `[road]` key that `road --maximize` and `--grid` may vary.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RoadKey {
    /// `spacing_m`.
    SpacingM,
    /// `mounting_height_m`.
    MountingHeightM,
    /// `overhang_m`.
    OverhangM,
    /// `tilt_deg`.
    TiltDeg,
    /// `setback_m`.
    SetbackM,
    /// `lane_width_m`.
    LaneWidthM,
    /// `maintenance_factor`.
    MaintenanceFactor,
}

impl RoadKey {
    /// Every key, in the order `docs/road.md` lists them.
    pub const ALL: [RoadKey; 7] = [
        RoadKey::SpacingM,
        RoadKey::MountingHeightM,
        RoadKey::OverhangM,
        RoadKey::TiltDeg,
        RoadKey::SetbackM,
        RoadKey::LaneWidthM,
        RoadKey::MaintenanceFactor,
    ];

    /// The key as written in `[road]`.
    pub fn as_str(self) -> &'static str {
        match self {
            RoadKey::SpacingM => "spacing_m",
            RoadKey::MountingHeightM => "mounting_height_m",
            RoadKey::OverhangM => "overhang_m",
            RoadKey::TiltDeg => "tilt_deg",
            RoadKey::SetbackM => "setback_m",
            RoadKey::LaneWidthM => "lane_width_m",
            RoadKey::MaintenanceFactor => "maintenance_factor",
        }
    }

    /// The key named `s`, if it is one of [`RoadKey::ALL`].
    pub fn parse(s: &str) -> Option<RoadKey> {
        RoadKey::ALL.into_iter().find(|k| k.as_str() == s.trim())
    }

    /// The key's unit (`m`, `deg`, or empty for the maintenance factor).
    pub fn unit(self) -> &'static str {
        match self {
            RoadKey::TiltDeg => "deg",
            RoadKey::MaintenanceFactor => "",
            _ => "m",
        }
    }

    /// `v` if it is a valid value of this key (the same checks as reading the
    /// scene file), else the key's error.
    pub fn check(self, v: f64) -> Result<f64, RoadError> {
        let key = self.as_str();
        let invalid = |reason: String| RoadError::Invalid { key, reason };
        let v = finite_key(key, v, self.unit())?;
        match self {
            RoadKey::LaneWidthM if !(v > 0.0 && v <= 50.0) => Err(invalid(format!("{v} m: expected (0, 50] m"))),
            RoadKey::SpacingM if !(v > 0.0 && v <= 1000.0) => Err(invalid(format!(
                "{v} m: expected a spacing in (0, 1000] m between two luminaires of a row"
            ))),
            RoadKey::MountingHeightM if v <= super::quantities::EYE_HEIGHT_M => {
                Err(RoadError::LuminaireBelowRoad { height_m: v })
            }
            RoadKey::TiltDeg if v.abs() >= 90.0 => Err(invalid(format!("{v}: expected |tilt| < 90 degrees"))),
            RoadKey::MaintenanceFactor if !(v > 0.0 && v <= 1.0) => {
                Err(invalid(format!("{v}: expected a number in (0, 1]")))
            }
            _ => Ok(v),
        }
    }

    /// This key's value in `road`.
    pub fn get(self, road: &Road) -> f64 {
        match self {
            RoadKey::SpacingM => road.spacing_m,
            RoadKey::MountingHeightM => road.mounting_height_m,
            RoadKey::OverhangM => road.overhang_m,
            RoadKey::TiltDeg => road.tilt_deg,
            RoadKey::SetbackM => road.setback_m,
            RoadKey::LaneWidthM => road.lane_width_m,
            RoadKey::MaintenanceFactor => road.maintenance_factor,
        }
    }

    /// `road` with this key set to `v`, checked as [`RoadKey::check`].
    pub fn set(self, road: &Road, v: f64) -> Result<Road, RoadError> {
        let v = self.check(v)?;
        let mut r = road.clone();
        match self {
            RoadKey::SpacingM => r.spacing_m = v,
            RoadKey::MountingHeightM => r.mounting_height_m = v,
            RoadKey::OverhangM => r.overhang_m = v,
            RoadKey::TiltDeg => r.tilt_deg = v,
            RoadKey::SetbackM => r.setback_m = v,
            RoadKey::LaneWidthM => r.lane_width_m = v,
            RoadKey::MaintenanceFactor => r.maintenance_factor = v,
        }
        Ok(r)
    }
}

/// How the luminaires stand.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Arrangement {
    /// One row on the near side (y < 0).
    SingleSided,
    /// Two rows facing each other at the same x.
    Opposite,
    /// Two rows facing each other, the far one shifted by half a spacing.
    Staggered,
    /// Twin arms on poles on the centre line.
    TwinCentral,
}

impl Arrangement {
    /// Parse the `arrangement` key.
    pub fn parse(s: &str) -> Result<Arrangement, RoadError> {
        Ok(match s.trim() {
            "single-sided" => Arrangement::SingleSided,
            "opposite" => Arrangement::Opposite,
            "staggered" => Arrangement::Staggered,
            "twin-central" => Arrangement::TwinCentral,
            other => {
                return Err(RoadError::Invalid {
                    key: "arrangement",
                    reason: format!(
                        "{other:?}: expected \"single-sided\", \"opposite\", \"staggered\" or \"twin-central\""
                    ),
                })
            }
        })
    }

    /// The name as written in the scene file.
    pub fn as_str(self) -> &'static str {
        match self {
            Arrangement::SingleSided => "single-sided",
            Arrangement::Opposite => "opposite",
            Arrangement::Staggered => "staggered",
            Arrangement::TwinCentral => "twin-central",
        }
    }
}

/// One row of luminaires: y, C0 direction (orient) and x offset.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// y of the photometric centres, m.
    pub y_m: f64,
    /// Orient (about z), degrees: 0 faces +y, 180 faces −y.
    pub orient_deg: f64,
    /// x of the row's first luminaire at or after the field start, m.
    pub x0_m: f64,
}

/// One generated luminaire.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placed {
    /// Index of its row in [`Road::rows`].
    pub row: usize,
    /// Where it hangs and how it is aimed.
    pub pose: Pose,
}

/// A checked road installation.
#[derive(Debug, Clone)]
pub struct Road {
    /// The scene file, when read from one.
    pub path: Option<PathBuf>,
    /// The photometric file as resolved.
    pub file: PathBuf,
    /// The loaded luminaire.
    pub luminaire: Luminaire,
    /// Representation asked for (`None`: the reference).
    pub representation: Option<Recon>,
    /// Maintenance factor.
    pub maintenance_factor: f64,
    /// Number of lanes.
    pub lanes: usize,
    /// Lane width, m.
    pub lane_width_m: f64,
    /// The surface's r-table (scaled to `q0` when given).
    pub surface: RTable,
    /// Arrangement.
    pub arrangement: Arrangement,
    /// Spacing within a row, m.
    pub spacing_m: f64,
    /// Mounting height, m.
    pub mounting_height_m: f64,
    /// Overhang, m.
    pub overhang_m: f64,
    /// Tilt, degrees.
    pub tilt_deg: f64,
    /// Setback, m.
    pub setback_m: f64,
    /// The file's C angle that points across the road from the pole, degrees, [0, 360).
    pub street_side_c_deg: f64,
    /// How r is interpolated between the r-table's nodes.
    pub r_interpolation: RInterpolation,
    /// What TI's screening angle is measured from.
    pub ti_screening: TiScreening,
}

fn finite_key(key: &'static str, v: f64, unit: &str) -> Result<f64, RoadError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(RoadError::Invalid {
            key,
            reason: format!("{v}: expected a finite number ({unit})"),
        })
    }
}

/// The checked dimensions of a `[road]` table (metres, degrees).
struct RoadDimensions {
    lane_width_m: f64,
    spacing_m: f64,
    mounting_height_m: f64,
    overhang_m: f64,
    setback_m: f64,
    tilt_deg: f64,
}

impl RoadDimensions {
    /// The lanes and dimensions of `spec`, each checked in turn.
    fn check(spec: &RoadSpec) -> Result<Self, RoadError> {
        if spec.lanes == 0 || spec.lanes > 64 {
            return Err(RoadError::Invalid {
                key: "lanes",
                reason: format!("{}: expected 1 to 64 lanes", spec.lanes),
            });
        }
        Ok(Self {
            lane_width_m: RoadKey::LaneWidthM.check(spec.lane_width_m)?,
            spacing_m: RoadKey::SpacingM.check(spec.spacing_m)?,
            mounting_height_m: RoadKey::MountingHeightM.check(spec.mounting_height_m)?,
            overhang_m: RoadKey::OverhangM.check(spec.overhang_m.unwrap_or(0.0))?,
            setback_m: RoadKey::SetbackM.check(spec.setback_m.unwrap_or(0.0))?,
            tilt_deg: RoadKey::TiltDeg.check(spec.tilt_deg.unwrap_or(0.0))?,
        })
    }
}

/// The surface's r-table: a standard one by name, else a user table read
/// from `base` (the scene file's directory); scaled to the `q0` given.
fn road_surface(spec: &RoadSpec, base: &Path) -> Result<RTable, RoadError> {
    let mut surface = match RTable::standard(&spec.surface) {
        Ok(t) => t,
        Err(RoadError::UnknownSurface { .. }) => {
            let p = base.join(&spec.surface);
            if p.is_file() {
                RTable::load(&p)?
            } else {
                return Err(RoadError::UnknownSurface {
                    surface: spec.surface.clone(),
                });
            }
        }
        Err(e) => return Err(e),
    };
    if let Some(q0) = spec.q0 {
        surface = surface.with_q0(q0)?;
    }
    Ok(surface)
}

impl Road {
    /// Read the `[road]` table of a scene file when it has one (`None`: a
    /// scene file without `[road]`).
    ///
    /// # Errors
    /// As [`Road::load`], except that a missing `[road]` table is `Ok(None)`.
    pub fn load_if_road(path: &Path) -> Result<Option<Road>, RoadError> {
        let text = std::fs::read_to_string(path).map_err(|e| RoadError::File {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        let has_road = toml::from_str::<crate::file::SceneSpec>(&text).is_ok_and(|spec| spec.road.is_some());
        if has_road {
            Road::load(path).map(Some)
        } else {
            Ok(None)
        }
    }

    /// Read the `[road]` table of a scene file.
    pub fn load(path: &Path) -> Result<Road, RoadError> {
        let text = std::fs::read_to_string(path).map_err(|e| RoadError::File {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        let spec: crate::file::SceneSpec = toml::from_str(&text).map_err(|e| RoadError::File {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        let road = spec.road.as_ref().ok_or_else(|| RoadError::File {
            path: path.to_path_buf(),
            message: "no [road] table: `photosolid road` needs one (docs/road.md)".into(),
        })?;
        if !spec.luminaires.is_empty() {
            return Err(RoadError::File {
                path: path.to_path_buf(),
                message: "a scene with [road] holds no [[luminaire]] tables: the road generates its luminaires".into(),
            });
        }
        Road::from_spec(road, path).map_err(|e| e.at_key(path, &text))
    }

    /// Check a parsed `[road]` table; files resolve relative to `scene_path`'s directory.
    pub fn from_spec(spec: &RoadSpec, scene_path: &Path) -> Result<Road, RoadError> {
        let base = scene_path.parent().map(Path::to_path_buf).unwrap_or_default();
        let invalid = |key: &'static str, reason: String| RoadError::Invalid { key, reason };
        let dims = RoadDimensions::check(spec)?;
        let mf = RoadKey::MaintenanceFactor.check(spec.maintenance_factor.unwrap_or(1.0))?;
        let r_interpolation = spec
            .r_interpolation
            .as_deref()
            .map_or(Ok(RInterpolation::default()), RInterpolation::parse)?;
        let ti_screening = spec
            .ti_screening
            .as_deref()
            .map_or(Ok(TiScreening::default()), TiScreening::parse)?;
        let arrangement = Arrangement::parse(&spec.arrangement)?;
        if arrangement == Arrangement::TwinCentral && !spec.lanes.is_multiple_of(2) {
            return Err(invalid(
                "lanes",
                format!(
                    "{}: twin-central needs an even number of lanes (a pole on the centre line)",
                    spec.lanes
                ),
            ));
        }
        let surface = road_surface(spec, &base)?;
        let representation = match &spec.representation {
            None => None,
            Some(r) => Some(
                parse_representation(r)
                    .map_err(|e| invalid("representation", e.to_string()))?
                    .0,
            ),
        };
        let file = base.join(&spec.file);
        let luminaire = crate::load(&file).map_err(|e| RoadError::Luminaire {
            file: file.clone(),
            message: e.to_string(),
        })?;
        let street_side_c_deg = match spec.street_side_c_deg {
            Some(c) => crate::model::wrap360(finite_key("street_side_c_deg", c, "degrees")?),
            None => luminaire.front().c_deg,
        };
        Ok(Road {
            path: Some(scene_path.to_path_buf()),
            file,
            luminaire,
            representation,
            maintenance_factor: mf,
            lanes: spec.lanes,
            lane_width_m: dims.lane_width_m,
            surface,
            arrangement,
            spacing_m: dims.spacing_m,
            mounting_height_m: dims.mounting_height_m,
            overhang_m: dims.overhang_m,
            tilt_deg: dims.tilt_deg,
            setback_m: dims.setback_m,
            street_side_c_deg,
            r_interpolation,
            ti_screening,
        })
    }

    /// Carriageway width, m.
    pub fn width_m(&self) -> f64 {
        self.lanes as f64 * self.lane_width_m
    }

    /// The rows of luminaires.
    pub fn rows(&self) -> Vec<Row> {
        let w = self.width_m();
        let near = Row {
            y_m: -self.setback_m + self.overhang_m,
            orient_deg: 0.0,
            x0_m: 0.0,
        };
        let far = |x0_m| Row {
            y_m: w + self.setback_m - self.overhang_m,
            orient_deg: 180.0,
            x0_m,
        };
        match self.arrangement {
            Arrangement::SingleSided => vec![near],
            Arrangement::Opposite => vec![near, far(0.0)],
            Arrangement::Staggered => vec![near, far(self.spacing_m / 2.0)],
            Arrangement::TwinCentral => vec![
                Row {
                    y_m: w / 2.0 - self.overhang_m,
                    orient_deg: 180.0,
                    x0_m: 0.0,
                },
                Row {
                    y_m: w / 2.0 + self.overhang_m,
                    orient_deg: 0.0,
                    x0_m: 0.0,
                },
            ],
        }
    }

    /// Every luminaire with x in [`x_from`, `x_to`] (m).
    pub fn luminaires(&self, x_from: f64, x_to: f64) -> Vec<Placed> {
        let s = self.spacing_m;
        let mut out = Vec::new();
        for (k, row) in self.rows().iter().enumerate() {
            let first = ((x_from - row.x0_m) / s).ceil() as i64;
            let last = ((x_to - row.x0_m) / s).floor() as i64;
            for i in first..=last {
                let x = row.x0_m + i as f64 * s;
                // Spin first turns the street side onto the local +y the roll tilts towards.
                let aim = Aim {
                    orient: row.orient_deg,
                    roll: self.tilt_deg,
                    spin: 90.0 - self.street_side_c_deg,
                    ..Default::default()
                };
                out.push(Placed {
                    row: k,
                    pose: Pose::new(DVec3::new(x, row.y_m, self.mounting_height_m), aim),
                });
            }
        }
        out
    }

    /// Number of grid points along the field: 10 for S ≤ 30 m, else the
    /// smallest N with S/N ≤ 3 m (EN 13201-3 §7.1.3 as implemented by
    /// others; `docs/road.md`).
    pub fn n_along(&self) -> usize {
        if self.spacing_m <= 30.0 + 1e-9 {
            10
        } else {
            (self.spacing_m / 3.0 - 1e-9).ceil() as usize
        }
    }

    /// Number of illuminance grid points across a strip of width `w` m:
    /// spacing ≤ 1.5 m, at least 3.
    pub fn n_across(w: f64) -> usize {
        ((w / 1.5 - 1e-9).ceil() as usize).max(3)
    }

    /// The template luminaire of the generated ones (point source: the
    /// standard treats road luminaires as points).
    pub fn scene_luminaire(&self, name: &str, pose: Pose) -> SceneLuminaire {
        SceneLuminaire {
            name: name.to_string(),
            luminaire: self.luminaire.clone(),
            pose,
            maintenance_factor: self.maintenance_factor,
            opening: Opening::Point,
            representation: self.representation,
            source: Some(SourceKind::Point),
        }
    }

    /// The scene `photosolid scene` computes on a road file: the luminaires
    /// within 5 mounting heights of the field and the field as a plane
    /// receiver with the EN 13201-3 illuminance grid.
    pub fn scene_parts(&self) -> (Vec<SceneLuminaire>, Receiver) {
        let reach = 5.0 * self.mounting_height_m;
        let lums = self
            .luminaires(-reach, self.spacing_m + reach)
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let name = format!("row {} #{} (x = {} m)", p.row + 1, i + 1, p.pose.position.x);
                self.scene_luminaire(&name, p.pose)
            })
            .collect();
        let w = self.width_m();
        let field = Receiver::plane(
            "road field",
            DVec3::ZERO,
            DVec3::new(self.spacing_m, 0.0, 0.0),
            DVec3::new(0.0, w, 0.0),
            self.n_along(),
            Road::n_across(w),
        );
        (lums, field)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_counts_follow_the_standard() {
        let mut r = test_road();
        r.spacing_m = 30.0;
        assert_eq!(r.n_along(), 10);
        r.spacing_m = 36.0;
        assert_eq!(r.n_along(), 12);
        r.spacing_m = 37.0;
        assert_eq!(r.n_along(), 13);
        assert_eq!(Road::n_across(7.0), 5);
        assert_eq!(Road::n_across(2.0), 3);
    }

    #[test]
    fn rows_of_each_arrangement() {
        let mut r = test_road();
        r.setback_m = 1.0;
        r.overhang_m = 2.0;
        assert_eq!(r.rows().len(), 1);
        assert_eq!(r.rows()[0].y_m, 1.0);
        r.arrangement = Arrangement::Opposite;
        assert_eq!(r.rows()[1].y_m, 7.0 + 1.0 - 2.0);
        r.arrangement = Arrangement::Staggered;
        assert_eq!(r.rows()[1].x0_m, 15.0);
        let lums = r.luminaires(0.0, 30.0);
        assert_eq!(lums.len(), 2 + 1);
    }

    pub(crate) fn test_road() -> Road {
        let lum = crate::synth::Synth::Roadway
            .build(&crate::synth::GridSpec::uniform(5.0, 2.5).unwrap(), 10_000.0)
            .unwrap();
        Road {
            path: None,
            file: PathBuf::from("synthetic"),
            luminaire: lum,
            representation: None,
            maintenance_factor: 1.0,
            lanes: 2,
            lane_width_m: 3.5,
            surface: RTable::standard("R3").unwrap(),
            arrangement: Arrangement::SingleSided,
            spacing_m: 30.0,
            mounting_height_m: 10.0,
            overhang_m: 0.0,
            tilt_deg: 0.0,
            setback_m: 0.0,
            street_side_c_deg: 90.0,
            r_interpolation: RInterpolation::Quadratic,
            ti_screening: TiScreening::Horizontal,
        }
    }
}
