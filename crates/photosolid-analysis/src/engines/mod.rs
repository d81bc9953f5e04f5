//! Light profiles for real renderers: each engine's layout, written out, and
//! each engine's lookup emulated as an [`IntensityField`] so that the metrics
//! of the trade table measure what the engine loses ([`measure()`]).
//!
//! One file per engine, each citing the engine's own source:
//! [`pbrt`] (pbrt-v4 goniometric light), [`ue`] (Unreal Engine 5 and 4),
//! [`unity`] (HDRP point and spot; [`unity_cube`] the point light's cube map
//! and HDRP's octahedral atlas copy), [`web`] (three.js, Babylon.js),
//! [`blender`] (Cycles), [`gltf`] (`KHR_lights_punctual` + `EXT_lights_ies`), [`godot`]
//! (no IES support: an `OmniLight3D` projector panorama).
//! `docs/engines.md` describes every layout and its orientation.
//!
//! Every emulation reads the file as the engine would: the engines that read
//! IES files themselves see the table photosolid's IES writer writes
//! ([`table::IesTable`]); pbrt has no IES reader, so photosolid bakes its
//! image with a filter of the native grid (`filter`, default Catmull–Rom).
//! Intensities are absolute candela: the engines that normalise to the
//! maximum get the file's maximum candela as the light's intensity.

pub mod blender;
pub mod defects;
pub mod gltf;
pub mod godot;
pub mod measure;
pub mod pbrt;
pub mod table;
pub mod ue;
pub mod unity;
pub mod unity_cube;
pub mod web;

use std::fmt;
use std::path::Path;
use std::str::FromStr;

use serde::Serialize;

use crate::error::{Error, ModelError};
use crate::model::{Distribution, IntensityField, Luminaire};
use crate::reconstruct::{Filter, LightTexture};
pub use measure::{measure, EngineRow, EnginesOptions, EnginesReport, ResolutionSearch, SkippedEngine};
use table::{IesTable, Image};

/// A renderer whose light-profile layout photosolid writes and emulates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Engine {
    /// pbrt-v4 goniometric light (equal-area octahedral image, nearest texel).
    Pbrt,
    /// Unreal Engine 5 (256 x 256, bilinear).
    Ue5,
    /// Unreal Engine 4 (256 x 1, averaged over C).
    Ue4,
    /// Unity HDRP point light (2N x 2N cylindrical buffer).
    UnityPoint,
    /// Unity HDRP spot light (N x N gnomonic cookie).
    UnitySpot,
    /// three.js `IESLoader` (1° grid).
    Threejs,
    /// Babylon.js `LoadIESData` (1° grid).
    Babylon,
    /// Blender Cycles (the IES table, Catmull–Rom).
    Blender,
    /// glTF 2.0 (`KHR_lights_punctual` + `EXT_lights_ies`).
    Gltf,
    /// Godot 4 `OmniLight3D` projector (equirectangular panorama → dual-paraboloid decal atlas).
    Godot,
}

/// The spellings of [`Engine`] on the command line.
pub const ENGINE_NAMES: &str = "pbrt, ue5, ue4, unity-point, unity-spot, threejs, babylon, blender, gltf, godot";

impl Engine {
    /// Every engine, in report order.
    pub const ALL: [Engine; 10] = [
        Engine::Pbrt,
        Engine::Ue5,
        Engine::Ue4,
        Engine::UnityPoint,
        Engine::UnitySpot,
        Engine::Threejs,
        Engine::Babylon,
        Engine::Blender,
        Engine::Gltf,
        Engine::Godot,
    ];

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Pbrt => "pbrt",
            Engine::Ue5 => "ue5",
            Engine::Ue4 => "ue4",
            Engine::UnityPoint => "unity-point",
            Engine::UnitySpot => "unity-spot",
            Engine::Threejs => "threejs",
            Engine::Babylon => "babylon",
            Engine::Blender => "blender",
            Engine::Gltf => "gltf",
            Engine::Godot => "godot",
        }
    }

    /// What the emulation follows: the release (npm, for three.js and Babylon.js) or the
    /// commit of the source photosolid read (`docs/engines.md`, "Sources"). The JSON rows
    /// carry it as `engine_version`; a defect row names the versions that have the defect.
    pub fn version(self) -> &'static str {
        match self {
            Engine::Pbrt => "pbrt-v4 commit 00aad0a6 (mmp/pbrt-v4; pbrt-v4 has no releases)",
            Engine::Ue5 => {
                "Unreal Engine 5 source as mirrored in chenyong2github/UnrealEngine \
                 (IESLoader.cpp, PointLightComponentVisualizer.cpp; mirror commit not recorded)"
            }
            Engine::Ue4 => "Unreal Engine 4.19.2 (mirror Kryptexas/UE4-GameWorks-4.19.2, commit 324683ce)",
            Engine::UnityPoint | Engine::UnitySpot => {
                "Unity HDRP, Unity-Technologies/Graphics: IESReader.cs commit 20072799, IESEngine.cs \
                 commit 0328a1b1, LightLoop/cookie code commits 85898ebe, cfc4b936, a1e46132 \
                 (HDRP 10.x manual for the cube-map size)"
            }
            Engine::Threejs => {
                "three 0.187.0 (npm, 2026-10-30: examples/jsm/loaders/IESLoader.js and \
                 src/nodes/lighting/IESSpotLightNode.js read from the package; the first release with PR \
                 #34554, candela linear, and every plane uploaded)"
            }
            Engine::Babylon => {
                "@babylonjs/core 9.35.0 (npm; Lights/IES/iesLoader.js and lightsFragmentFunctions read from \
                 the package, the loader byte-identical to 9.23.0's, the first release with PR #18833: \
                 candela linear, no file-generation factor, a 180 x 1 texture of the C0 plane)"
            }
            Engine::Blender => {
                "Blender Cycles (blender/blender intern/cycles/util/ies.cpp, kernel/svm/ies.h; \
                 cross-checked against Debian's Blender 3.4.1)"
            }
            Engine::Gltf => {
                "glTF 2.0: EXT_lights_ies README at KhronosGroup/glTF commit 10301d57 (Status: Complete), \
                 KHR_lights_punctual README"
            }
            Engine::Godot => {
                "Godot 4 RD renderers (Forward+, Mobile), godotengine/godot as stored in the code index: \
                 scene_forward_lights_inc.glsl commit 001d4b23, light_storage.cpp commit 006f0390, \
                 texture_storage.cpp, copy_effects.cpp, copy_to_fb.glsl (not read at a release tag)"
            }
        }
    }

    /// `(default, smallest, largest)` resolution when the engine's resolution
    /// is a choice: pbrt's image side, Unity's N (the point buffer is 2N x 2N).
    pub fn resolution_range(self) -> Option<(usize, usize, usize)> {
        match self {
            Engine::Pbrt => Some((256, 4, 4096)),
            Engine::UnityPoint => Some((unity::DEFAULT_SIZE, 4, unity::MAX_SIDE / 2)),
            Engine::UnitySpot => Some((unity::DEFAULT_SIZE, 8, unity::MAX_SIDE)),
            Engine::Godot => Some((godot::DEFAULT_HEIGHT, 8, 4096)),
            _ => None,
        }
    }

    /// The file extension of the export.
    pub fn extension(self) -> &'static str {
        match self {
            Engine::Blender => "ies",
            Engine::Gltf => "glb",
            _ => "exr",
        }
    }
}

impl fmt::Display for Engine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Serialize for Engine {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl FromStr for Engine {
    type Err = ModelError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Engine::ALL
            .into_iter()
            .find(|e| e.name() == s.trim())
            .ok_or_else(|| ModelError::Parameter {
                name: "engine",
                value: s.to_string(),
                reason: format!("expected one of {ENGINE_NAMES}"),
            })
    }
}

/// Choices of a layout.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EngineOptions {
    /// The resolution, for engines whose resolution is a choice (default: the engine's).
    pub resolution: Option<usize>,
    /// The filter photosolid bakes pbrt's image with (the other engines interpolate the table themselves).
    pub filter: Filter,
}

impl Default for EngineOptions {
    fn default() -> Self {
        Self {
            resolution: None,
            filter: Filter::CatmullRom,
        }
    }
}

/// One engine's emulated lookup and, for image layouts, the image.
pub struct Emulation {
    /// The engine.
    pub engine: Engine,
    /// The resolution used (engines with a choice).
    pub resolution: Option<usize>,
    /// The layout in words (size, mapping, filter).
    pub layout: String,
    /// The engine's lookup, cd.
    pub field: Box<dyn IntensityField>,
    /// The image the engine holds (texture layouts).
    pub image: Option<Image>,
    /// Steps of the emulation that follow no source photosolid could read
    /// (stand-ins, or parts not modelled); empty when every step is from source.
    pub stand_ins: Vec<&'static str>,
}

/// The resolution `opts` asks of `engine`, checked against its range.
///
/// # Errors
/// [`ModelError::Parameter`] for a resolution on an engine without a choice, or out of range.
pub fn resolution(engine: Engine, opts: &EngineOptions) -> Result<Option<usize>, ModelError> {
    match (engine.resolution_range(), opts.resolution) {
        (None, None) => Ok(None),
        (None, Some(n)) => Err(ModelError::Parameter {
            name: "resolution",
            value: n.to_string(),
            reason: format!("{engine}'s layout has a fixed size"),
        }),
        (Some((d, _, _)), None) => Ok(Some(d)),
        (Some((_, lo, hi)), Some(n)) if (lo..=hi).contains(&n) => Ok(Some(n)),
        (Some((_, lo, hi)), Some(n)) => Err(ModelError::Parameter {
            name: "resolution",
            value: n.to_string(),
            reason: format!("{engine} takes {lo}..={hi}"),
        }),
    }
}

/// One engine's layout baked from a file.
struct Baked {
    /// The layout in words (size, mapping, filter).
    layout: String,
    /// The engine's lookup, cd.
    field: Box<dyn IntensityField>,
    /// The image the engine holds (texture layouts).
    image: Option<Image>,
}

/// pbrt's `n` x `n` equal-area octahedral image, baked from `texture` with `filter`.
fn bake_pbrt(texture: &LightTexture, n: usize, filter: Filter) -> Result<Baked, ModelError> {
    let image = pbrt::bake(&texture.sampler(filter), n)?;
    let f = pbrt::PbrtField { image: image.clone() };
    Ok(Baked {
        layout: format!("{n}x{n} equal-area octahedral, Y in cd, {filter} bake, nearest lookup"),
        field: Box::new(f),
        image: Some(image),
    })
}

/// UE5's 256 x 256 or UE4's 256 x 1 (averaged over C) texture of `table`
/// (`engine`: UE5 or UE4), I/I_max (`i_max` in cd).
fn bake_ue(engine: Engine, table: &IesTable, i_max: f64) -> Result<Baked, ModelError> {
    let image = if engine == Engine::Ue5 {
        ue::bake_ue5(table)?
    } else {
        ue::bake_ue4(table)?
    };
    let layout = format!(
        "{}x{} half float, x -> gamma = 180x/256{}, I/I_max, bilinear",
        image.width,
        image.height,
        if engine == Engine::Ue5 {
            ", y -> C = 360y/256"
        } else {
            ", averaged over C"
        }
    );
    Ok(Baked {
        layout,
        field: Box::new(ue::UeField {
            image: image.clone(),
            i_max_cd: i_max,
        }),
        image: Some(image),
    })
}

/// Unity's point light (`2n` x `2n` cylindrical buffer, a cube map of `n`
/// per face) or spot light (`n` x `n` cookie) of `table` (`engine`: one of
/// the two), I/I_max (`i_max` in cd).
fn bake_unity(engine: Engine, table: &IesTable, n: usize, i_max: f64) -> Result<Baked, ModelError> {
    if engine == Engine::UnityPoint {
        let image = unity::bake_point(table, n, true)?;
        let f = unity::UnityField::point(&image, n, i_max)?;
        let layout = format!(
            "{0}x{0} cylindrical, 8-bit I/I_max -> cube map {n}x{n} per face -> HDRP octahedral atlas {1}x{1} R11G11B10, bilinear (90-270 files folded; Unity's clamp is a defect row)",
            2 * n,
            f.image.width
        );
        Ok(Baked {
            layout,
            field: Box::new(f),
            image: Some(image),
        })
    } else {
        let cone = unity::DEFAULT_CONE_DEG;
        let image = unity::bake_spot(table, n, cone, true)?;
        let f = unity::UnityField::spot(&image, cone, i_max);
        let layout = format!(
            "{n}x{n} gnomonic cookie, cone {cone} deg, attenuation on, 8-bit I/I_max, atlas R11G11B10, bilinear"
        );
        Ok(Baked {
            layout,
            field: Box::new(f),
            image: Some(image),
        })
    }
}

/// three.js's or Babylon.js's 1-degree grid of `table` (`engine`: one of
/// the two), I/I_max (`i_max` in cd).
fn bake_web(engine: Engine, table: &IesTable, i_max: f64) -> Result<Baked, ModelError> {
    let three = engine == Engine::Threejs;
    let data = if three {
        web::bake_grid_three(table)
    } else {
        web::bake_grid(table, false)
    };
    let image = web::grid_image(&data, !three)?;
    let lookup = if three {
        web::WebLookup::Three
    } else {
        web::WebLookup::Babylon
    };
    let layout = if three {
        "180x360 grid data[phi + theta*180] (gamma = phi*180/179, theta 0..359 wrapping), half float, I/I_max, every plane, bilinear"
    } else {
        "180x1 R32F: the C0 plane of the 1-degree grid (LoadIESData returns width 180, height 1), I/I_max, linear, gamma read 0.5 deg early, every C alike"
    };
    let f = web::WebField {
        data,
        lookup,
        i_max_cd: i_max,
    };
    Ok(Baked {
        layout: layout.to_string(),
        field: Box::new(f),
        image: Some(image),
    })
}

/// Cycles' processed IES table of `table` (no image).
fn bake_blender(table: &IesTable) -> Result<Baked, ModelError> {
    let t = blender::process(table, false)?;
    let layout = format!(
        "IES table {} x {} (0..360), separable Catmull-Rom, clamped at 0",
        t.h.len(),
        t.v.len()
    );
    Ok(Baked {
        layout,
        field: Box::new(blender::BlenderField { table: t }),
        image: None,
    })
}

/// Godot's `2h` x `h` projector panorama, baked from `texture` with
/// `filter`, sRGB-encoded I/I_max (`i_max` in cd).
fn bake_godot(texture: &LightTexture, h: usize, filter: Filter, i_max: f64) -> Result<Baked, ModelError> {
    let linear = godot::bake_linear(&texture.sampler(filter), h, i_max)?;
    let image = godot::encode_for_godot(&linear)?;
    let f = godot::GodotField::new(&image, i_max);
    let layout = format!(
        "{w}x{h} equirectangular panorama (row 0 = nadir, column u: C = 360u + 90 deg), sRGB-encoded \
         I/I_max, {} bake -> dual-paraboloid decal atlas rect {w}x{h} RGBA8 read through its sRGB \
         view, bilinear, mip 0",
        filter,
        w = 2 * h
    );
    Ok(Baked {
        layout,
        field: Box::new(f),
        image: Some(image),
    })
}

/// glTF's `KHR_lights_punctual` fallback: the lights fitted to `dist` (no image).
fn bake_gltf(dist: &Distribution) -> Result<Baked, ModelError> {
    let fitted = crate::fit::fit(dist, &crate::fit::FitOptions::default())?;
    let lights = gltf::khr_lights(fitted.model());
    let layout = format!(
        "KHR_lights_punctual fallback: {} fitted light(s); EXT_lights_ies embeds the IES file",
        lights.len()
    );
    Ok(Baked {
        layout,
        field: Box::new(gltf::KhrField { lights }),
        image: None,
    })
}

/// Emulate `engine`'s lookup of the distribution `dist` (cd).
///
/// # Errors
/// All-zero data, a bad resolution, a table the engine refuses (Blender), a failed fit (glTF).
pub fn emulate(engine: Engine, dist: &Distribution, opts: &EngineOptions) -> Result<Emulation, ModelError> {
    let n = resolution(engine, opts)?;
    let table = IesTable::of(dist);
    let i_max = table.max_cd();
    if !(i_max > 0.0 && i_max.is_finite()) {
        return Err(ModelError::AllZero(
            "an engine layout needs a positive maximum intensity",
        ));
    }
    let texture = LightTexture::new(dist)?;
    let baked = match engine {
        Engine::Pbrt => bake_pbrt(&texture, n.unwrap_or(256), opts.filter)?,
        Engine::Ue5 | Engine::Ue4 => bake_ue(engine, &table, i_max)?,
        Engine::UnityPoint | Engine::UnitySpot => bake_unity(engine, &table, n.unwrap_or(unity::DEFAULT_SIZE), i_max)?,
        Engine::Threejs | Engine::Babylon => bake_web(engine, &table, i_max)?,
        Engine::Blender => bake_blender(&table)?,
        Engine::Godot => bake_godot(&texture, n.unwrap_or(godot::DEFAULT_HEIGHT), opts.filter, i_max)?,
        Engine::Gltf => bake_gltf(dist)?,
    };
    let stand_ins = match engine {
        Engine::UnityPoint => unity::POINT_STAND_INS.to_vec(),
        Engine::UnitySpot => unity::SPOT_STAND_INS.to_vec(),
        Engine::Godot => godot::STAND_INS.to_vec(),
        _ => Vec::new(),
    };
    Ok(Emulation {
        engine,
        resolution: n,
        layout: baked.layout,
        field: baked.field,
        image: baked.image,
        stand_ins,
    })
}

/// What [`export`] wrote.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Exported {
    /// The engine.
    pub engine: Engine,
    /// The layout in words.
    pub layout: String,
    /// Image size (width, height), for image layouts.
    pub size: Option<(usize, usize)>,
    /// For pbrt: 4π × the image mean, lm (the flux pbrt's `power` scales by).
    pub pbrt_flux_lm: Option<f64>,
}

fn exr_attrs(engine: Engine, lum: &Luminaire, layout: &str, unit: &str, i_max: f64) -> exr::prelude::LayerAttributes {
    use crate::reconstruct::exr_io::text;
    use exr::prelude::{AttributeValue, LayerAttributes, Text};
    let mut attrs = LayerAttributes::named(format!("photosolid-{engine}").as_str());
    let source = lum.path().map(|p| p.display().to_string()).unwrap_or_default();
    for (k, v) in [
        ("photosolid.engine", engine.name().to_string()),
        ("photosolid.source", source),
        ("photosolid.layout", layout.to_string()),
        ("photosolid.unit", unit.to_string()),
    ] {
        attrs.other.insert(Text::from(k), AttributeValue::Text(text(&v)));
    }
    attrs
        .other
        .insert(Text::from("photosolid.i_max_cd"), AttributeValue::F64(i_max));
    attrs
}

/// Write `engine`'s layout of `lum` to `path`: an EXR (channel `Y`) for the
/// image layouts, an IES file for Blender, a GLB for glTF.
///
/// # Errors
/// What [`emulate`] fails on, and I/O errors.
pub fn export(engine: Engine, lum: &Luminaire, path: &Path, opts: &EngineOptions) -> Result<Exported, Error> {
    let dist = lum.distribution();
    let i_max = dist.max_cd();
    if !(i_max > 0.0 && i_max.is_finite()) {
        return Err(ModelError::AllZero("an engine layout needs a positive maximum intensity").into());
    }
    match engine {
        Engine::Blender => {
            resolution(engine, opts)?;
            let text = crate::formats::ies::write(&lum.clone().into(), Default::default());
            crate::formats::write_atomic(path, text.as_bytes())?;
            Ok(Exported {
                engine,
                layout: "IES LM-63-2002 (Cycles reads the file itself)".into(),
                size: None,
                pbrt_flux_lm: None,
            })
        }
        Engine::Gltf => {
            resolution(engine, opts)?;
            let texture = LightTexture::new(dist)?;
            let grid = crate::solid::SolidGrid::refined(dist, 3)?;
            let mesh = crate::solid::grid_solid(&texture.sampler(opts.filter), &grid, crate::solid::Units::Peak)?;
            let fitted = crate::fit::fit(dist, &crate::fit::FitOptions::default())?;
            let lights = gltf::khr_lights(fitted.model());
            let ies = crate::formats::ies::write(&lum.clone().into(), Default::default());
            crate::formats::write_atomic(path, &gltf::encode(&mesh, ies.as_bytes(), &lights))?;
            Ok(Exported {
                engine,
                layout: format!(
                    "GLB: solid (I/I_max = 1), EXT_lights_ies profile, {} KHR_lights_punctual light(s)",
                    lights.len()
                ),
                size: None,
                pbrt_flux_lm: None,
            })
        }
        Engine::Godot => {
            let em = emulate(engine, dist, opts)?;
            let image = em
                .image
                .ok_or(ModelError::Internal("the godot layout has an image".into()))?;
            let attrs = exr_attrs(engine, lum, &em.layout, "sRGB-encoded I/I_max", i_max);
            let half: Vec<exr::prelude::f16> = image.data.iter().map(|&v| exr::prelude::f16::from_f32(v)).collect();
            let channels = ["R", "G", "B"]
                .into_iter()
                .map(|c| (c, exr::prelude::FlatSamples::F16(half.clone())))
                .collect();
            crate::reconstruct::exr_io::write_layer_channels(path, (image.width, image.height), attrs, channels)?;
            Ok(Exported {
                engine,
                layout: em.layout,
                size: Some((image.width, image.height)),
                pbrt_flux_lm: None,
            })
        }
        _ => {
            let em = emulate(engine, dist, opts)?;
            let image = em
                .image
                .ok_or_else(|| ModelError::Internal(format!("the {engine} layout has an image")))?;
            let unit = if engine == Engine::Pbrt { "cd" } else { "I/I_max" };
            let attrs = exr_attrs(engine, lum, &em.layout, unit, i_max);
            let half = matches!(engine, Engine::Ue5 | Engine::Ue4 | Engine::Threejs);
            let samples = if half {
                exr::prelude::FlatSamples::F16(image.data.iter().map(|&v| exr::prelude::f16::from_f32(v)).collect())
            } else {
                exr::prelude::FlatSamples::F32(image.data.clone())
            };
            crate::reconstruct::exr_io::write_layer(path, (image.width, image.height), attrs, "Y", samples)?;
            Ok(Exported {
                engine,
                layout: em.layout,
                size: Some((image.width, image.height)),
                pbrt_flux_lm: (engine == Engine::Pbrt).then(|| pbrt::flux_lm(&image)),
            })
        }
    }
}
