//! The scene file (TOML, metres and degrees; schema in `docs/scene.md`).
//!
//! Parsing is serde into the `*Spec` structs (unknown keys are errors), then
//! [`Scene::from_spec`] checks every value and resolves files relative to the
//! scene file. Every error names the scene file, the line of the offending
//! table and what was expected.

use std::path::{Path, PathBuf};

use glam::DVec3;
use serde::Deserialize;

use super::aim::{Aim, Pose};
use super::opening::Opening;
use super::representation::parse_representation;
use super::road::layout::{Road, RoadSpec};
use super::{Occluder, Receiver, Scene, SceneError, SceneLuminaire, SourceKind};
use crate::error::Location;
use crate::model::Luminaire;

/// Most receiver points a scene may ask for (a typo in a spacing must not
/// allocate gigabytes).
pub const MAX_POINTS: usize = 1_000_000;

/// The whole file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSpec {
    /// `[[luminaire]]` tables.
    #[serde(default, rename = "luminaire")]
    pub luminaires: Vec<LuminaireSpec>,
    /// `[[receiver]]` tables.
    #[serde(default, rename = "receiver")]
    pub receivers: Vec<ReceiverSpec>,
    /// `[[occluder]]` tables.
    #[serde(default, rename = "occluder")]
    pub occluders: Vec<OccluderSpec>,
    /// A `[road]` table: the road generates its luminaires and its field
    /// receiver ([`super::road`], `docs/road.md`).
    #[serde(default)]
    pub road: Option<super::road::layout::RoadSpec>,
}

/// One `[[luminaire]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LuminaireSpec {
    /// Photometric file (.ies or .ldt), relative to the scene file.
    pub file: PathBuf,
    /// A name for reports; default: the file name.
    pub name: Option<String>,
    /// Photometric centre, world metres.
    pub position: [f64; 3],
    /// LM-72 aiming angles, degrees.
    pub aim: Option<AimSpec>,
    /// Point the nadir at this world point (metres) instead of `aim`.
    pub aim_at: Option<[f64; 3]>,
    /// Maintenance factor in (0, 1]; default 1.
    pub maintenance_factor: Option<f64>,
    /// Representation of the distribution; default: the reference (Catmull-Rom on the native grid).
    pub representation: Option<String>,
    /// `point` or `area`; default: `area` when the opening has a size, else `point`.
    pub source: Option<String>,
    /// Overrides the luminous opening the file declares.
    pub opening: Option<Opening>,
}

/// LM-72 aim angles (degrees), each 0 when omitted.
#[derive(Debug, Clone, Copy, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct AimSpec {
    /// About world Z.
    #[serde(default)]
    pub orient: f64,
    /// About local Y (nadir towards C0).
    #[serde(default)]
    pub tilt: f64,
    /// About local X (nadir towards C90).
    #[serde(default)]
    pub roll: f64,
    /// About local Z.
    #[serde(default)]
    pub spin: f64,
}

/// Grid spacing of a plane receiver.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum SpacingSpec {
    /// `"en12464"`.
    Named(String),
    /// `[du, dv]`, metres.
    Metres([f64; 2]),
}

/// One `[[receiver]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum ReceiverSpec {
    /// A rectangle: origin + s u + t v, normal u × v.
    Plane {
        /// Name for reports.
        name: String,
        /// A corner, metres.
        origin: [f64; 3],
        /// First edge, metres.
        u: [f64; 3],
        /// Second edge, metres.
        v: [f64; 3],
        /// `"en12464"` or `[du, dv]` metres.
        spacing: SpacingSpec,
    },
    /// One point with a normal.
    Point {
        /// Name for reports.
        name: String,
        /// Position, metres.
        position: [f64; 3],
        /// Facing direction (any length > 0).
        normal: [f64; 3],
    },
}

/// One `[[occluder]]`: an opaque planar polygon.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OccluderSpec {
    /// At least 3 coplanar vertices, metres.
    pub vertices: Vec<[f64; 3]>,
}

/// EN 12464-1 grid spacing (m) for a side of length `d` (m): `0.2 · 5^log10(d)`, at most 10 m.
pub fn en12464_spacing(d: f64) -> f64 {
    (0.2 * 5f64.powf(d.log10())).min(10.0)
}

/// The 1-based line of the `k`-th (0-based) `[[table]]` header in `text`, 0 when not found.
fn table_line(text: &str, table: &str, k: usize) -> usize {
    let header = format!("[[{table}]]");
    text.lines()
        .enumerate()
        .filter(|(_, l)| l.trim_start().starts_with(&header))
        .nth(k)
        .map_or(0, |(i, _)| i + 1)
}

/// The 1-based line and column of `key = ...` inside the `k`-th (0-based)
/// `[[table]]` of `text` (the table's own lines, up to the next table
/// header); the table's header line when the key is not written there (a
/// default).
fn key_location(text: &str, table: &str, k: usize, key: &str) -> Location {
    let start = table_line(text, table, k);
    if start == 0 {
        return Location::line(0);
    }
    for (i, line) in text.lines().enumerate().skip(start) {
        let l = line.trim_start();
        if l.starts_with('[') {
            break;
        }
        let name = l.split('=').next().unwrap_or("").trim().trim_matches('"');
        if l.contains('=') && name == key {
            return Location::at(i + 1, line.len() - l.len() + 1);
        }
    }
    Location::line(start)
}

fn vec3(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}

/// Whether all three numbers are finite.
fn finite3(a: &[f64; 3]) -> bool {
    a.iter().all(|v| v.is_finite())
}

/// The scene file being checked, to build its errors: its path, and its text
/// to find the line of a table or key.
#[derive(Clone, Copy)]
struct SpecText<'a> {
    path: &'a Path,
    text: &'a str,
}

/// The `k`-th (0-based) `[[table]]` of a scene file, where its errors point.
struct TableAt<'a> {
    file: SpecText<'a>,
    table: &'static str,
    k: usize,
}

impl<'a> SpecText<'a> {
    /// The `k`-th (0-based) `[[table]]` of this file.
    fn table(self, table: &'static str, k: usize) -> TableAt<'a> {
        TableAt { file: self, table, k }
    }

    /// An error about the `[road]` table, at its header line.
    fn road_error(self, message: String) -> SceneError {
        SceneError::Invalid {
            path: self.path.to_path_buf(),
            location: Location::line(
                self.text
                    .lines()
                    .position(|l| l.trim_start().starts_with("[road]"))
                    .map_or(0, |i| i + 1),
            ),
            message,
        }
    }
}

impl TableAt<'_> {
    /// An error in this table as a whole: at its header line, the message
    /// prefixed with `table #n`.
    fn error(&self, message: String) -> SceneError {
        SceneError::Invalid {
            path: self.file.path.to_path_buf(),
            location: Location::line(table_line(self.file.text, self.table, self.k)),
            message: format!("{} #{}: {message}", self.table, self.k + 1),
        }
    }

    /// An error in one key's value: at that key's line.
    fn key_error(&self, key: &str, message: String) -> SceneError {
        SceneError::Invalid {
            path: self.file.path.to_path_buf(),
            location: key_location(self.file.text, self.table, self.k, key),
            message: format!("{} #{}: {message}", self.table, self.k + 1),
        }
    }
}

/// The luminaires and the field receiver a `[road]` table generates.
fn road_parts(
    spec: &SceneSpec,
    road: &RoadSpec,
    file: SpecText<'_>,
) -> Result<(Vec<SceneLuminaire>, Receiver), SceneError> {
    if !spec.luminaires.is_empty() {
        return Err(file.road_error(
            "a scene with [road] holds no [[luminaire]] tables: the road generates its luminaires".into(),
        ));
    }
    let road = Road::from_spec(road, file.path).map_err(|e| {
        // At the key's line and column when the error is about one key.
        match e.key().and_then(|k| crate::road::key_position(file.text, "road", k)) {
            Some((line, column)) => SceneError::Invalid {
                path: file.path.to_path_buf(),
                location: Location {
                    line,
                    column: Some(column),
                },
                message: e.to_string(),
            },
            None => file.road_error(e.to_string()),
        }
    })?;
    Ok(road.scene_parts())
}

/// One `[[luminaire]]` checked, its file loaded (relative to `base`, the
/// scene file's directory); a deprecated representation spelling adds a line
/// to `warnings`.
fn luminaire(
    l: &LuminaireSpec,
    at: &TableAt<'_>,
    base: &Path,
    warnings: &mut Vec<crate::error::Warning>,
) -> Result<SceneLuminaire, SceneError> {
    if !finite3(&l.position) {
        return Err(at.key_error(
            "position",
            format!("position {:?}: expected 3 finite numbers (m)", l.position),
        ));
    }
    let position = vec3(l.position);
    let luminaire = load_luminaire(l, base, at)?;
    let aim = luminaire_aim(l, &luminaire, position, at)?;
    let mf = l.maintenance_factor.unwrap_or(1.0);
    if !(mf.is_finite() && mf > 0.0 && mf <= 1.0) {
        return Err(at.key_error(
            "maintenance_factor",
            format!("maintenance_factor = {mf}: expected a number in (0, 1]"),
        ));
    }
    let representation = match &l.representation {
        None => None,
        Some(r) => {
            let (rep, deprecated) = parse_representation(r)
                .map_err(|e| at.key_error("representation", format!("representation = {r:?}: {e}")))?;
            warnings.extend(deprecated.map(|w| {
                let mut w = crate::error::Warning::new(
                    crate::error::WarningCode::DeprecatedSpelling,
                    format!("[[luminaire]] #{}: {w}", at.k + 1),
                );
                w.line = Some(key_location(at.file.text, at.table, at.k, "representation").line).filter(|l| *l > 0);
                w
            }));
            Some(rep)
        }
    };
    let source = match l.source.as_deref() {
        None => None,
        Some("point") => Some(SourceKind::Point),
        Some("area") => Some(SourceKind::Area),
        Some(s) => return Err(at.key_error("source", format!("source = {s:?}: expected \"point\" or \"area\""))),
    };
    let opening = luminaire_opening(l, &luminaire, at)?;
    let name = l.name.clone().unwrap_or_else(|| l.file.display().to_string());
    Ok(SceneLuminaire {
        name,
        luminaire,
        pose: Pose::new(position, aim),
        maintenance_factor: mf,
        opening,
        representation,
        source,
    })
}

/// The aim of a luminaire at `position` (m): its `aim` angles (degrees),
/// towards its `aim_at` point (the nadir on the point, the luminaire's front
/// in the vertical plane through both, [`crate::model::front`]), or straight
/// down.
fn luminaire_aim(
    l: &LuminaireSpec,
    luminaire: &Luminaire,
    position: DVec3,
    at: &TableAt<'_>,
) -> Result<Aim, SceneError> {
    Ok(match (&l.aim, &l.aim_at) {
        (Some(_), Some(_)) => return Err(at.error("give either aim or aim_at, not both".into())),
        (Some(a), None) => {
            if ![a.orient, a.tilt, a.roll, a.spin].iter().all(|v| v.is_finite()) {
                return Err(at.key_error("aim", format!("aim {a:?}: expected finite degrees")));
            }
            Aim {
                orient: a.orient,
                tilt: a.tilt,
                roll: a.roll,
                spin: a.spin,
            }
        }
        (None, Some(t)) => {
            if !finite3(t) {
                return Err(at.key_error("aim_at", format!("aim_at {t:?}: expected 3 finite numbers (m)")));
            }
            let towards = Aim::at(position, vec3(*t))
                .ok_or_else(|| at.key_error("aim_at", "aim_at is the luminaire's own position: no direction".into()))?;
            // Spin first turns the front onto the local +x the tilt swings the nadir towards.
            Aim {
                spin: -luminaire.front().c_deg,
                ..towards
            }
        }
        (None, None) => Aim::default(),
    })
}

/// The luminaire's photometric file, read from next to the scene file (`base`).
fn load_luminaire(l: &LuminaireSpec, base: &Path, at: &TableAt<'_>) -> Result<Luminaire, SceneError> {
    let file = base.join(&l.file);
    crate::load(&file).map_err(|e| {
        // The path as resolved (relative to the scene file), and the
        // reason once (an I/O error's text already names the path).
        let resolved = std::path::absolute(&file).unwrap_or_else(|_| file.clone());
        let why = match &e {
            crate::Error::Io { source, .. } => source.to_string(),
            other => other.to_string(),
        };
        at.key_error(
            "file",
            format!(
                "file = {:?} (resolved next to the scene file: {}): {why}",
                l.file.display().to_string(),
                resolved.display()
            ),
        )
    })
}

/// The luminous opening: the one the scene gives (checked), else the one
/// the file declares.
fn luminaire_opening(l: &LuminaireSpec, luminaire: &Luminaire, at: &TableAt<'_>) -> Result<Opening, SceneError> {
    Ok(match l.opening {
        Some(o) => {
            Opening::check(&o).map_err(|m| at.key_error("opening", format!("opening: {m}")))?;
            o
        }
        None => Opening::of_luminaire(luminaire).map_err(|m| {
            at.error(format!(
                "{}: {m}; give the opening in the scene (opening = {{ shape = \"point\" }})",
                l.file.display()
            ))
        })?,
    })
}

/// One `[[receiver]]` checked, with its calculation points.
fn receiver(r: &ReceiverSpec, at: &TableAt<'_>) -> Result<Receiver, SceneError> {
    Ok(match r {
        ReceiverSpec::Point { name, position, normal } => {
            if !finite3(position) || !finite3(normal) {
                return Err(at.error("position and normal: expected 3 finite numbers each".into()));
            }
            let n = vec3(*normal)
                .try_normalize()
                .ok_or_else(|| at.key_error("normal", format!("normal {normal:?}: expected a non-zero vector")))?;
            Receiver::point(name, vec3(*position), n)
        }
        ReceiverSpec::Plane {
            name,
            origin,
            u,
            v,
            spacing,
        } => {
            if !finite3(origin) || !finite3(u) || !finite3(v) {
                return Err(at.error("origin, u and v: expected 3 finite numbers each".into()));
            }
            let (o, u, v) = (vec3(*origin), vec3(*u), vec3(*v));
            if u.cross(v).try_normalize().is_none() {
                return Err(at.error("u and v: expected two non-zero, non-parallel edges".into()));
            }
            let (du, dv) = plane_spacing(spacing, u, v, at)?;
            let (nu, nv) = ((u.length() / du).ceil().max(1.0), (v.length() / dv).ceil().max(1.0));
            if nu * nv > MAX_POINTS as f64 {
                return Err(at.error(format!(
                    "{nu} x {nv} points: more than {MAX_POINTS}; use a coarser spacing"
                )));
            }
            Receiver::plane(name, o, u, v, nu as usize, nv as usize)
        }
    })
}

/// The grid spacing (m along `u`, m along `v`) of a plane receiver with edges
/// `u` and `v` (m): EN 12464-1's for the longer edge, or the one given.
fn plane_spacing(spacing: &SpacingSpec, u: DVec3, v: DVec3, at: &TableAt<'_>) -> Result<(f64, f64), SceneError> {
    Ok(match spacing {
        SpacingSpec::Named(s) if s == "en12464" => {
            let p = en12464_spacing(u.length().max(v.length()));
            (p, p)
        }
        SpacingSpec::Named(s) => {
            return Err(at.key_error(
                "spacing",
                format!("spacing = {s:?}: expected \"en12464\" or [du, dv] in metres"),
            ))
        }
        SpacingSpec::Metres([a, b]) => {
            if !(a.is_finite() && b.is_finite() && *a > 0.0 && *b > 0.0) {
                return Err(at.key_error("spacing", format!("spacing [{a}, {b}]: expected two positive metres")));
            }
            (*a, *b)
        }
    })
}

impl Scene {
    /// Read and check a scene file.
    ///
    /// # Errors
    /// [`crate::Error::Io`] (the path and the I/O error) when it cannot be
    /// read; a [`SceneError`] when its content is not a scene.
    pub fn load(path: &Path) -> crate::Result<Scene> {
        let text = std::fs::read_to_string(path).map_err(|e| crate::Error::io(path, e))?;
        Ok(Scene::from_toml(&text, path)?)
    }

    /// Parse scene text; files are resolved relative to `path`'s directory
    /// (which need not exist for scenes without luminaire files to read).
    pub fn from_toml(text: &str, path: &Path) -> Result<Scene, SceneError> {
        let spec: SceneSpec = toml::from_str(text).map_err(|e| {
            let start = e.span().map_or(0, |s| s.start.min(text.len()));
            let line = e.span().map_or(0, |_| text[..start].matches('\n').count() + 1);
            let shown = text
                .lines()
                .nth(line.saturating_sub(1))
                .filter(|_| line > 0)
                .unwrap_or("")
                .trim();
            SceneError::Invalid {
                path: path.to_path_buf(),
                location: Location::line(line),
                message: if shown.is_empty() {
                    e.message().to_string()
                } else {
                    format!("{} (in `{shown}`)", e.message())
                },
            }
        })?;
        Scene::from_spec(&spec, text, path)
    }

    /// Check and resolve a parsed scene (see [`Scene::from_toml`]); `text` is
    /// only used to find table lines for messages.
    pub fn from_spec(spec: &SceneSpec, text: &str, path: &Path) -> Result<Scene, SceneError> {
        let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
        let file = SpecText { path, text };
        let mut warnings = Vec::new();
        let mut luminaires = Vec::new();
        let mut receivers = Vec::new();
        if let Some(road) = &spec.road {
            let (lums, field) = road_parts(spec, road, file)?;
            luminaires.extend(lums);
            receivers.push(field);
        }
        for (k, l) in spec.luminaires.iter().enumerate() {
            luminaires.push(luminaire(l, &file.table("luminaire", k), &base, &mut warnings)?);
        }
        let mut total = receivers.iter().map(|r: &Receiver| r.points.len()).sum::<usize>();
        for (k, r) in spec.receivers.iter().enumerate() {
            let at = file.table("receiver", k);
            let rec = receiver(r, &at)?;
            total += rec.points.len();
            if total > MAX_POINTS {
                return Err(at.error(format!("the scene has more than {MAX_POINTS} receiver points")));
            }
            receivers.push(rec);
        }
        let mut occluders = Vec::new();
        for (k, o) in spec.occluders.iter().enumerate() {
            let verts: Vec<DVec3> = o.vertices.iter().map(|v| vec3(*v)).collect();
            occluders.push(Occluder::new(verts).map_err(|e| file.table("occluder", k).error(e.to_string()))?);
        }
        // A scene that cannot light anything is a mistake, not 0 lx.
        let none = |what: &str, table: &str| SceneError::Invalid {
            path: path.to_path_buf(),
            location: Location::default(),
            message: format!("the scene has no {what}: add at least one [[{table}]] table (docs/scene.md)"),
        };
        if luminaires.is_empty() {
            return Err(none("luminaires", "luminaire"));
        }
        if receivers.is_empty() {
            return Err(none("receivers", "receiver"));
        }
        Ok(Scene {
            path: Some(path.to_path_buf()),
            luminaires,
            receivers,
            occluders,
            warnings,
        })
    }
}
