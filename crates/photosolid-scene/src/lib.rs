//! Scenes: luminaires placed and aimed over receivers, the illuminance they
//! put there, and the cheapest representation that keeps it within a tolerance.
//!
//! - [`mod@file`]: the TOML scene file (schema in `docs/scene.md`);
//! - [`aim`]: LM-72 aiming, the luminaire frame in the world;
//! - [`near_field`]: luminous openings, Lambert's polygon formula, the
//!   directional area source;
//! - [`illuminance`]: E = Σ MF · I(d) cos(incidence) / r² at every receiver
//!   point, with any [`crate::model::IntensityField`];
//! - [`road`]: road lighting (EN 13201-3): luminance, uniformities, TI;
//! - [`representation`]: each luminaire's representation, named by the one
//!   registry's [`Recon`] and built as a field ([`representation::Models`]);
//! - [`plan`]: per luminaire, the cheapest representation within a
//!   tolerance of the reference, measured on the scene.
//!
//! Inside the module, too, the files point one way: `representation` below
//! `illuminance` below `plan`.
//!
//! World frame: right-handed, z up, metres. A luminaire's frame is that of
//! [`crate::model::frame`], turned by its [`aim::Pose`].
//!
//! ```
//! use photosolid_scene::demo_scene;
//! let scene = demo_scene().unwrap();
//! let result = photosolid_scene::illuminance::evaluate(&scene, None).unwrap();
//! assert!(result.receivers.iter().all(|r| r.e_max_lux.is_finite()));
//! ```
//!
//! The scene layer of photosolid, above `photosolid-analysis`; `photosolid` re-exports it as
//! `photosolid::scene`.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

// The layers below, under the names this crate's modules use (`crate::model`, ...).
use photosolid_analysis::{compare, error, fit, metrics, model, numfmt, photometry, reconstruct, registry, synth};
use photosolid_analysis::{load, Error, ModelError, Result};

pub mod aim;
pub mod file;
pub mod illuminance;
pub mod near_field;
pub use crate::model::opening;
pub mod plan;
pub mod representation;
pub mod road;

use std::path::PathBuf;

use glam::DVec3;
use serde::Serialize;

use crate::model::{IntensityField, Luminaire};
use crate::reconstruct::LightTexture;
use crate::registry::Recon;
use aim::Pose;
use opening::Opening;

/// Everything that can go wrong with a scene: now a part of the crate's
/// error ([`SceneError`], this crate's), with stable codes.
mod scene_error;
pub use scene_error::SceneError;

/// How a luminaire's light leaves it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SourceKind {
    /// All light from the photometric centre (far field, inverse square).
    Point,
    /// The directional area source: the opening cut into patches each
    /// carrying the far-field distribution times its share.
    Area,
}

impl std::fmt::Display for SourceKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            SourceKind::Point => "point",
            SourceKind::Area => "area",
        })
    }
}

/// A luminaire placed in a scene.
#[derive(Debug, Clone)]
pub struct SceneLuminaire {
    /// Name for reports (the file name unless given).
    pub name: String,
    /// The loaded luminaire.
    pub luminaire: Luminaire,
    /// Where it hangs and how it is aimed.
    pub pose: Pose,
    /// Maintenance factor in (0, 1].
    pub maintenance_factor: f64,
    /// Its luminous opening (declared or given in the scene).
    pub opening: Opening,
    /// The representation asked for; `None`: the reference
    /// ([`representation::REFERENCE`]).
    pub representation: Option<Recon>,
    /// The source model asked for; `None`: area when the opening has a size.
    pub source: Option<SourceKind>,
}

impl SceneLuminaire {
    /// A luminaire at `pose` with the declared opening, MF 1, the reference representation.
    ///
    /// # Errors
    /// [`crate::error::ModelError::Opening`] when the declared opening is not one this crate models.
    pub fn new(name: &str, luminaire: Luminaire, pose: Pose) -> Result<Self, crate::ModelError> {
        let opening = Opening::of_luminaire(&luminaire)?;
        Ok(Self {
            name: name.into(),
            luminaire,
            pose,
            maintenance_factor: 1.0,
            opening,
            representation: None,
            source: None,
        })
    }

    /// The source model used: the one asked for, else area when the opening has a size.
    pub fn source_kind(&self) -> SourceKind {
        self.source.unwrap_or(if self.opening.is_point() {
            SourceKind::Point
        } else {
            SourceKind::Area
        })
    }

    /// The light texture every grid representation samples; `None` for an
    /// all-zero distribution (whose every representation is [`Dark`]).
    pub fn texture(&self) -> Result<Option<LightTexture>, SceneError> {
        match LightTexture::new(self.luminaire.distribution()) {
            Ok(t) => Ok(Some(t)),
            Err(crate::ModelError::AllZero(_)) => Ok(None),
            Err(e) => Err(self.model_error(e)),
        }
    }

    /// `e`, met building one of this luminaire's representations, as the
    /// scene's error naming the luminaire.
    pub fn model_error(&self, e: crate::ModelError) -> SceneError {
        SceneError::Model {
            luminaire: self.name.clone(),
            source: e,
        }
    }
}

/// The field of an all-zero distribution: 0 cd everywhere, nothing stored.
#[derive(Debug, Clone, Copy)]
pub struct Dark;

impl IntensityField for Dark {
    fn intensity_cd(&self, _c: f64, _g: f64) -> f64 {
        0.0
    }
    fn name(&self) -> String {
        "dark (all-zero distribution)".into()
    }
    fn bytes(&self) -> usize {
        0
    }
}

/// The geometry of a receiver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ReceiverShape {
    /// A rectangle `origin + s·u + t·v`, s, t in [0, 1], sampled at `nu × nv`
    /// cell centres (u fastest).
    Plane {
        /// Corner, m.
        origin: DVec3,
        /// First edge, m.
        u: DVec3,
        /// Second edge, m.
        v: DVec3,
        /// Points along u.
        nu: usize,
        /// Points along v.
        nv: usize,
    },
    /// One point.
    Point,
}

/// A surface that matters: where the illuminance is computed.
#[derive(Debug, Clone)]
pub struct Receiver {
    /// Name for reports.
    pub name: String,
    /// Plane or point.
    pub shape: ReceiverShape,
    /// Unit normal (the side that receives light).
    pub normal: DVec3,
    /// Calculation points, world m.
    pub points: Vec<DVec3>,
}

/// An opaque planar polygon that blocks light (shadow rays).
#[derive(Debug, Clone)]
pub struct Occluder {
    /// Vertices, world m.
    pub vertices: Vec<DVec3>,
    normal: DVec3,
    /// Projection axes for the 2-D inside test.
    axes: (usize, usize),
}

impl Occluder {
    /// A polygon of at least 3 finite, coplanar vertices (within 1e-9 of its size).
    ///
    /// # Errors
    /// [`crate::error::ModelError::Parameter`] `vertices` naming what is wrong.
    pub fn new(vertices: Vec<DVec3>) -> Result<Self, crate::ModelError> {
        let bad = |value: String, reason: &str| crate::ModelError::Parameter {
            name: "vertices",
            value,
            reason: reason.into(),
        };
        if vertices.len() < 3 || !vertices.iter().all(|v| v.is_finite()) {
            return Err(bad(
                crate::error::count(vertices.len(), "point", "points"),
                "expected at least 3 points of 3 finite numbers",
            ));
        }
        let mut n = DVec3::ZERO;
        for (i, &a) in vertices.iter().enumerate() {
            n += a.cross(vertices[(i + 1) % vertices.len()]);
        }
        let points = || crate::error::count(vertices.len(), "point", "points");
        let normal = n
            .try_normalize()
            .ok_or_else(|| bad(points(), "the polygon has no area; expected a polygon with area"))?;
        let size = vertices.iter().map(|v| (*v - vertices[0]).length()).fold(0.0, f64::max);
        if vertices
            .iter()
            .any(|v| normal.dot(*v - vertices[0]).abs() > 1e-9 * size)
        {
            return Err(bad(points(), "not coplanar; expected the points in one plane"));
        }
        let a = normal.abs();
        let axes = if a.x >= a.y && a.x >= a.z {
            (1, 2)
        } else if a.y >= a.z {
            (0, 2)
        } else {
            (0, 1)
        };
        Ok(Self { vertices, normal, axes })
    }

    /// Whether the open segment from `a` to `b` crosses the polygon.
    pub fn blocks(&self, a: DVec3, b: DVec3) -> bool {
        let d = b - a;
        let den = self.normal.dot(d);
        if den == 0.0 {
            return false;
        }
        let t = self.normal.dot(self.vertices[0] - a) / den;
        if !(t > 1e-9 && t < 1.0 - 1e-9) {
            return false;
        }
        let p = a + d * t;
        let (i, j) = self.axes;
        let (px, py) = (p[i], p[j]);
        let mut inside = false;
        let n = self.vertices.len();
        for k in 0..n {
            let (u, v) = (self.vertices[k], self.vertices[(k + 1) % n]);
            let (ux, uy, vx, vy) = (u[i], u[j], v[i], v[j]);
            if (uy > py) != (vy > py) && px < ux + (py - uy) * (vx - ux) / (vy - uy) {
                inside = !inside;
            }
        }
        inside
    }
}

/// A scene: luminaires, receivers, occluders.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The scene file, when read from one.
    pub path: Option<PathBuf>,
    /// The luminaires.
    pub luminaires: Vec<SceneLuminaire>,
    /// The receivers.
    pub receivers: Vec<Receiver>,
    /// Opaque polygons.
    pub occluders: Vec<Occluder>,
    /// What the scene file says that still works but should change (an old
    /// representation spelling); reported with every result, coded.
    pub warnings: Vec<crate::error::Warning>,
}

/// One calculation point: where, which way it faces, whose it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScenePoint {
    /// Position, world m.
    pub position: DVec3,
    /// Unit normal.
    pub normal: DVec3,
    /// Index of its receiver in [`Scene::receivers`].
    pub receiver: usize,
    /// Index within the receiver's points.
    pub index: usize,
}

impl Scene {
    /// Every calculation point, receiver after receiver.
    pub fn points(&self) -> Vec<ScenePoint> {
        self.receivers
            .iter()
            .enumerate()
            .flat_map(|(ri, r)| {
                r.points.iter().enumerate().map(move |(index, &position)| ScenePoint {
                    position,
                    normal: r.normal,
                    receiver: ri,
                    index,
                })
            })
            .collect()
    }

    /// Fails with [`SceneError::InsideOpening`] when a receiver point lies
    /// on or inside a luminaire's opening (or on a point source's centre).
    pub fn check_points(&self) -> Result<(), SceneError> {
        for p in self.points() {
            for l in &self.luminaires {
                if l.opening.contains(l.pose.to_local(p.position - l.pose.position)) {
                    return Err(SceneError::InsideOpening {
                        receiver: self.receivers[p.receiver].name.clone(),
                        index: p.index + 1,
                        position: p.position.to_array(),
                        luminaire: l.name.clone(),
                        opening: serde_json::to_string(&l.opening).unwrap_or_default(),
                    });
                }
            }
        }
        Ok(())
    }
}

/// The built-in scene of `photosolid demo`: the synthetic road luminaire
/// (peak 12,000 cd, 5° × 2.5° grid, a 0.6 m × 0.25 m opening) 8 m over a
/// 40 m × 7 m road, tilted 10° towards the road, MF 0.8, and a sensor
/// 1 m below the opening (1.5 luminaire sizes away: near field).
pub fn demo_scene() -> Result<Scene, crate::ModelError> {
    use crate::synth::{GridSpec, Synth};
    let lum = Synth::Roadway.build(&GridSpec::uniform(5.0, 2.5)?, 12_000.0)?;
    let pose = Pose::new(
        DVec3::new(0.0, 0.0, 8.0),
        aim::Aim {
            orient: 90.0,
            tilt: 10.0,
            ..Default::default()
        },
    );
    let luminaire = SceneLuminaire {
        name: "built-in road luminaire".into(),
        luminaire: lum,
        pose,
        maintenance_factor: 0.8,
        opening: Opening::Rectangle {
            length_m: 0.6,
            width_m: 0.25,
        },
        representation: None,
        source: None,
    };
    let road = Receiver::plane(
        "road",
        DVec3::new(-20.0, 0.0, 0.0),
        DVec3::new(40.0, 0.0, 0.0),
        DVec3::new(0.0, 7.0, 0.0),
        16,
        3,
    );
    let scene = Scene {
        path: None,
        luminaires: vec![luminaire],
        receivers: vec![road, Receiver::point("sensor", DVec3::new(0.0, 0.0, 7.0), DVec3::Z)],
        occluders: Vec::new(),
        warnings: Vec::new(),
    };
    Ok(scene)
}

impl Receiver {
    /// A point receiver at `position` facing `normal` (normalised; +z when zero).
    pub fn point(name: &str, position: DVec3, normal: DVec3) -> Self {
        Receiver {
            name: name.into(),
            shape: ReceiverShape::Point,
            normal: normal.try_normalize().unwrap_or(DVec3::Z),
            points: vec![position],
        }
    }

    /// A plane receiver `origin + s·u + t·v` with `nu × nv` cell-centre points.
    pub fn plane(name: &str, origin: DVec3, u: DVec3, v: DVec3, nu: usize, nv: usize) -> Self {
        Receiver {
            name: name.into(),
            shape: ReceiverShape::Plane {
                origin,
                u,
                v,
                nu: nu.max(1),
                nv: nv.max(1),
            },
            normal: u.cross(v).try_normalize().unwrap_or(DVec3::Z),
            points: Vec::new(),
        }
        .with_grid_points()
    }

    /// Fill `points` from the plane's grid (cell centres, u fastest); a point receiver is unchanged.
    fn with_grid_points(mut self) -> Self {
        if let ReceiverShape::Plane { origin, u, v, nu, nv } = self.shape {
            self.points = (0..nv)
                .flat_map(|j| {
                    (0..nu)
                        .map(move |i| origin + u * ((i as f64 + 0.5) / nu as f64) + v * ((j as f64 + 0.5) / nv as f64))
                })
                .collect();
        }
        self
    }
}
