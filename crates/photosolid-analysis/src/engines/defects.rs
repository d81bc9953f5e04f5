//! Documented defects of the engines' loaders, each as a pair of lookups:
//! the engine with the defect and the same engine without it. The error the
//! defect causes on a file is the distance between the two
//! ([`super::measure()`] reports it as a separate row).

use super::table::IesTable;
use super::{blender, ue, unity, web, Engine};
use crate::error::ModelError;
use crate::model::{Distribution, IntensityField, Luminaire, PhotometricType, Symmetry};

/// One defect of one engine on one file.
pub struct Defect {
    /// The engine.
    pub engine: Engine,
    /// Short name (`squared candela`, `single C-plane`, ...).
    pub name: String,
    /// Where the engine's source does it (file, function and the statement).
    pub source: &'static str,
    /// The engine versions that have the defect (`engine_version` of the row).
    pub versions: &'static str,
    /// The engine's lookup with the defect, cd.
    pub with: Box<dyn IntensityField>,
    /// The same lookup without it, cd.
    pub without: Box<dyn IntensityField>,
}

const THREE_SQUARE: &str = "three.js examples/jsm/loaders/IESLoader.js, IESLamp: \
    `_self.candelaValues[ i ][ j ] *= _self.candelaValues[ i ][ j ] * _self.multiplier * _self.ballFactor * _self.blpFactor;`";
const THREE_PLANE: &str = "three.js examples/jsm/loaders/IESLoader.js, parse: \
    `new DataTexture( data, 180, 1, RedFormat, type )` uploads data[0..180], the theta = 0 plane";
const THREE_TILT: &str =
    "three.js examples/jsm/loaders/IESLoader.js, IESLamp: readTilt() fills tiltData, which nothing applies";
const BABYLON_SQUARE: &str = "Babylon.js packages/dev/core/src/Lights/IES/iesLoader.ts, LoadIESData: \
    `data.candelaValues[index][subIndex] *= data.candelaValues[index][subIndex] * data.candelaMultiplier * \
    data.ballastFactor * data.fileGenerationType` (before PR #18833); the factors cancel in the division by \
    the maximum that follows whenever their product is positive (fileGenerationType is 1 in LM-63-2002 files \
    and >= 1.00001 in LM-63-2019 ones), so the row measures the squaring";
const BABYLON_ROW: &str = "Babylon.js iesLoader.ts `RawTexture.CreateRTexture(arrayBuffer, width=360, height=180)` \
    filled at `arrayBuffer[phi + theta * height]`, read by lightsFragmentFunctions getIESAttenuation \
    `texture(iesLightSampler, vec2(acos(cosAngle)/PI, 0.))`: row 0 = theta 0 and 1, gamma doubled";
const BABYLON_TILT: &str = "Babylon.js iesLoader.ts, LoadIESData: `// Not supported yet` for TILT=INCLUDE";
const BLENDER_ROTATE: &str = "Blender intern/cycles/util/ies.cpp, IESFile::process_type_c: \
    `if (h_angles[0] == 90.0f) { ... h_angles[i] -= 90.0f; }` turns 90-270 files by 90 degrees";
const THREE_TYPE: &str = "three.js examples/jsm/loaders/IESLoader.js, IESLamp: readLampValues stores \
    `_self.gonioType = Number( values[ 5 ] )`, which nothing reads: Type A/B angles are used as Type C";
const BABYLON_TYPE: &str = "Babylon.js iesLoader.ts, LoadIESData: \
    `data.photometricType = header[5]; // We ignore cylindrical type for now`";
const UE_TYPE_B: &str = "UE IESLoader.cpp, FIESLoader::Interpolate2D: only `EIESPhotometricType::TypeA` is \
    converted; Type B takes the Type C path";
const UE4_INTEGRAL: &str = "UE 4.19.2 Engine/Source/Editor/UnrealEd/Private/Factories/IESLoader.cpp, \
    FIESLoadHelper::ComputeFullIntegral: `float HAngle = FMath::Acos(Dir.Z) / PI * 180;` \
    `float VAngle = FMath::Atan2(Dir.Y, Dir.X) / PI * 180 + 180;` `Sum += Interpolate2D(HAngle, VAngle);` \
    (polar angle as the horizontal angle); ExtractInRGBA16F returns `MaxValue / Integral`, \
    which ULightComponent::ComputeLightBrightness multiplies into the brightness";
const UNITY_90_270: &str = "Unity com.unity.render-pipelines.core/Editor/Lighting/IESReader.cs, \
    ComputeTypeCHorizontalAnglePosition: `default: // the luminaire is assumed to exhibit no lateral symmetry` \
    leaves a 90-270 file unfolded, and ComputeAnglePosition clamps C < 90 and C > 270 to the first and last plane";
const GODOT_SRGB: &str = "Godot servers/rendering/renderer_rd/storage_rd/texture_storage.cpp, update_decal_atlas: \
    the atlas is DATA_FORMAT_R8G8B8A8_UNORM, filled by copy_to_atlas_fb from the texture's rd_texture with no \
    sRGB conversion; scene_forward_lights_inc.glsl light_process_omni samples \
    `sampler2D(decal_atlas_srgb, light_projector_sampler)`, the R8G8B8A8_SRGB view: a linear texture's values \
    are decoded as sRGB (about v^2.2)";
const BLENDER_TILT: &str = "Blender intern/cycles/util/ies.cpp, IESFile::parse: \
    TILT=INCLUDE angles and factors are read and skipped";

/// Versions with three.js's squared candela.
pub const THREE_SQUARE_VERSIONS: &str =
    "three.js <= 0.186.1 (npm; 0.186.0 and 0.186.1 checked in the published packages) and main before PR \
    #34554 (merged 2026-09-14): squared candela";
/// Versions with Babylon.js's squared candela.
pub const BABYLON_SQUARE_VERSIONS: &str = "Babylon.js (@babylonjs/core) < 9.23.0, before PR #18833 (merged \
    2026-08-25): squared candela x file-generation type";
const THREE_ALL_VERSIONS: &str = "three.js <= 0.186.1 (IESLoader.js at commits 0a5a85c7, f959b152 and in the npm \
    packages 0.186.0/0.186.1): the 180 x 1 texture; 0.187.0 uploads every plane";
const BABYLON_ALL_VERSIONS: &str = "Babylon.js: every iesLoader.ts read (commits 0571ea8c, 48fd6640) and 9.23.0 \
    (PR #18833 changes only the candela scaling)";
const BABYLON_ROW_VERSIONS: &str = "Babylon.js with the 360 x 180 RawTexture (read at commit 0571ea8c); the npm \
    releases checked (@babylonjs/core 7.54.0, 8.0.0, 9.22.2, 9.23.0, 9.35.0) all return the 180 x 1 texture of the \
    theta = 0 plane instead (the babylon layout row)";

fn web_field(t: &IesTable, lookup: web::WebLookup, i_max: f64) -> Box<dyn IntensityField> {
    let half = matches!(
        lookup,
        web::WebLookup::ThreeAllPlanes | web::WebLookup::ThreeSinglePlane
    );
    Box::new(web::WebField {
        data: web::bake_grid(t, half),
        lookup,
        i_max_cd: i_max,
    })
}

/// The tilt angle (degrees) of the file's tilt table whose multiplier is
/// furthest from 1, with that multiplier; `None` without a table.
pub fn worst_tilt(lum: &Luminaire) -> Option<(f64, f64)> {
    let t = lum.tilt().table()?;
    t.angles
        .iter()
        .zip(&t.multipliers)
        .map(|(&a, &m)| (a, m))
        .max_by(|a, b| (a.1 - 1.0).abs().total_cmp(&(b.1 - 1.0).abs()))
}

/// What the defects of one file are measured on.
struct FileTables {
    /// The file's distribution as an IES table holds it, cd.
    t: IesTable,
    /// Its largest value, cd.
    i_max: f64,
    /// With a tilt table: the tilt angle (degrees) furthest from a multiplier
    /// of 1 and the table tilted there, cd.
    tilted: Option<(f64, IesTable)>,
    /// With a Type A/B file: its type, the defect's name and the file's own
    /// grid read as if it were Type C, cd.
    as_type_c: Option<(PhotometricType, String, IesTable)>,
}

impl FileTables {
    /// The tables of `lum`.
    ///
    /// # Errors
    /// A tilted distribution that cannot be built.
    fn of(lum: &Luminaire) -> Result<Self, ModelError> {
        let t = IesTable::of(lum.distribution());
        let i_max = t.max_cd();
        let tilted = match worst_tilt(lum) {
            Some((angle, _)) => Some((angle, IesTable::of(&lum.tilted_distribution(angle)?))),
            None => None,
        };
        // The file's own Type A/B grid, read as if it were Type C.
        let as_type_c = lum.source_grid().as_ref().map(|sg| {
            let kind = if sg.kind == PhotometricType::A { "A" } else { "B" };
            let t = IesTable {
                h: sg.horizontal.clone(),
                v: sg.vertical.clone(),
                cd: sg.cd.clone(),
            };
            (sg.kind, format!("Type {kind} read as Type C"), t)
        });
        Ok(Self {
            t,
            i_max,
            tilted,
            as_type_c,
        })
    }
}

/// The name of the ignored-TILT row at tilt angle `a` (degrees).
fn tilt_name(a: f64) -> String {
    format!("ignores TILT (at tilt {a} deg)")
}

/// The defects of `engine` that apply to `lum` (none for the engines
/// without documented defects: pbrt, UE5 on Type C files, glTF).
///
/// Rows: three.js and Babylon square each candela value; three.js keeps one
/// C-plane; Babylon's shader reads row 0 of its 360-wide texture; Blender
/// turns 90-270 files by 90° (only for such files); three.js, Babylon and
/// Blender ignore TILT (only for files with a tilt table: the error at the
/// table's angle furthest from a multiplier of 1); three.js and Babylon read
/// Type A/B angles as Type C, and UE reads Type B as Type C (only for such
/// files: the file's own grid taken as a Type C table, against the engine
/// on photosolid's Type C conversion); UE4 scales by a mean taken with the
/// polar angle and the azimuth swapped (every file); Unity leaves 90-270
/// files unfolded (only for such files).
///
/// # Errors
/// A table Blender refuses.
pub fn defects(engine: Engine, lum: &Luminaire) -> Result<Vec<Defect>, ModelError> {
    let dist = lum.distribution();
    let x = FileTables::of(lum)?;
    Ok(match engine {
        Engine::Threejs | Engine::Babylon => web_defects(engine, &x),
        Engine::Blender => blender_defects(engine, dist.symmetry(), &x)?,
        Engine::UnityPoint | Engine::UnitySpot if dist.symmetry() == Symmetry::C90C270 => {
            vec![unity_defect(engine, &x)?]
        }
        Engine::Ue5 | Engine::Ue4 => ue_defects(engine, &x)?,
        Engine::Godot => vec![godot_defect(engine, dist, x.i_max)?],
        _ => Vec::new(),
    })
}

/// What one web engine's defect rows say and which lookups they compare.
struct WebRows {
    /// The engine's lookup without the defects (every plane).
    lookup: web::WebLookup,
    /// The squared-candela row's name, source and versions.
    square_name: &'static str,
    square_source: &'static str,
    square_versions: &'static str,
    /// The row of the lookup that reads one plane (three.js) or row 0
    /// (Babylon.js): name, source, the lookup and versions.
    plane_name: &'static str,
    plane_source: &'static str,
    plane_lookup: web::WebLookup,
    plane_versions: &'static str,
    /// The sources of the Type A/B and TILT rows, and their versions.
    type_source: &'static str,
    tilt_source: &'static str,
    versions: &'static str,
}

const THREE_ROWS: WebRows = WebRows {
    lookup: web::WebLookup::ThreeAllPlanes,
    square_name: "squared candela (three.js <= 0.186.1, before PR #34554)",
    square_source: THREE_SQUARE,
    square_versions: THREE_SQUARE_VERSIONS,
    plane_name: "single C-plane",
    plane_source: THREE_PLANE,
    plane_lookup: web::WebLookup::ThreeSinglePlane,
    plane_versions: THREE_ALL_VERSIONS,
    type_source: THREE_TYPE,
    tilt_source: THREE_TILT,
    versions: THREE_ALL_VERSIONS,
};

const BABYLON_ROWS: WebRows = WebRows {
    lookup: web::WebLookup::Babylon,
    square_name: "squared candela x file-generation type (Babylon.js < 9.23.0, before PR #18833)",
    square_source: BABYLON_SQUARE,
    square_versions: BABYLON_SQUARE_VERSIONS,
    plane_name: "row-0 lookup",
    plane_source: BABYLON_ROW,
    plane_lookup: web::WebLookup::BabylonRowZero,
    plane_versions: BABYLON_ROW_VERSIONS,
    type_source: BABYLON_TYPE,
    tilt_source: BABYLON_TILT,
    versions: BABYLON_ALL_VERSIONS,
};

/// three.js's or Babylon.js's defects (`engine` is one of the two): the
/// squared candela, the one plane (three.js) or row 0 (Babylon), and for
/// such files the Type A/B grid read as Type C and the ignored TILT.
fn web_defects(engine: Engine, x: &FileTables) -> Vec<Defect> {
    let w = if engine == Engine::Threejs {
        &THREE_ROWS
    } else {
        &BABYLON_ROWS
    };
    let (t, i_max, all) = (&x.t, x.i_max, w.lookup);
    let mut out = vec![
        Defect {
            engine,
            name: w.square_name.into(),
            source: w.square_source,
            versions: w.square_versions,
            with: web_field(&t.squared(), all, i_max),
            without: web_field(t, all, i_max),
        },
        Defect {
            engine,
            name: w.plane_name.into(),
            source: w.plane_source,
            versions: w.plane_versions,
            with: web_field(t, w.plane_lookup, i_max),
            without: web_field(t, all, i_max),
        },
    ];
    if let Some((_, name, tab)) = &x.as_type_c {
        out.push(Defect {
            engine,
            name: name.clone(),
            source: w.type_source,
            versions: w.versions,
            with: web_field(tab, all, tab.max_cd()),
            without: web_field(t, all, i_max),
        });
    }
    if let Some((angle, tt)) = &x.tilted {
        out.push(Defect {
            engine,
            name: tilt_name(*angle),
            source: w.tilt_source,
            versions: w.versions,
            with: web_field(t, all, i_max),
            without: web_field(tt, all, tt.max_cd()),
        });
    }
    out
}

/// Blender's defects: a 90-270 file (`symmetry`) turned by 90°, and the
/// ignored TILT of a file with a tilt table.
///
/// # Errors
/// A table Blender refuses.
fn blender_defects(engine: Engine, symmetry: Symmetry, x: &FileTables) -> Result<Vec<Defect>, ModelError> {
    let mut out = Vec::new();
    if symmetry == Symmetry::C90C270 {
        out.push(Defect {
            engine,
            name: "90-270 file turned by 90 deg".into(),
            source: BLENDER_ROTATE,
            versions: engine.version(),
            with: Box::new(blender::BlenderField {
                table: blender::process(&x.t, true)?,
            }),
            without: Box::new(blender::BlenderField {
                table: blender::process(&x.t, false)?,
            }),
        });
    }
    if let Some((angle, tt)) = &x.tilted {
        out.push(Defect {
            engine,
            name: tilt_name(*angle),
            source: BLENDER_TILT,
            versions: engine.version(),
            with: Box::new(blender::BlenderField {
                table: blender::process(&x.t, false)?,
            }),
            without: Box::new(blender::BlenderField {
                table: blender::process(tt, false)?,
            }),
        });
    }
    Ok(out)
}

/// Unity's clamp of a 90-270 file outside 90..270 (`engine`: the point or
/// the spot light; the caller checks the symmetry).
fn unity_defect(engine: Engine, x: &FileTables) -> Result<Defect, ModelError> {
    let (t, i_max) = (&x.t, x.i_max);
    let n = super::resolution(engine, &super::EngineOptions::default())?.unwrap_or(unity::DEFAULT_SIZE);
    // Unity's lookup of the table baked with or without the fold.
    let field = |fold: bool| -> Result<Box<dyn IntensityField>, ModelError> {
        Ok(if engine == Engine::UnityPoint {
            Box::new(unity::UnityField::point(&unity::bake_point(t, n, fold)?, n, i_max)?)
        } else {
            let cone = unity::DEFAULT_CONE_DEG;
            Box::new(unity::UnityField::spot(
                &unity::bake_spot(t, n, cone, fold)?,
                cone,
                i_max,
            ))
        })
    };
    Ok(Defect {
        engine,
        name: "90-270 file clamped outside 90..270".into(),
        source: UNITY_90_270,
        versions: engine.version(),
        with: field(false)?,
        without: field(true)?,
    })
}

/// UE's defects (`engine`: UE5 or UE4): UE4's integral with the angles
/// swapped, and a Type B file read as Type C.
fn ue_defects(engine: Engine, x: &FileTables) -> Result<Vec<Defect>, ModelError> {
    let (t, i_max) = (&x.t, x.i_max);
    let mut out = Vec::new();
    if engine == Engine::Ue4 {
        let strip = ue::bake_ue4(t)?;
        let (right, swapped) = (ue::ue4_integral(t, false), ue::ue4_integral(t, true));
        if right > 0.0 && swapped > 0.0 {
            out.push(Defect {
                engine,
                name: "swapped-angle integral".into(),
                source: UE4_INTEGRAL,
                versions: engine.version(),
                with: Box::new(ue::UeField {
                    image: strip.clone(),
                    i_max_cd: i_max * right / swapped,
                }),
                without: Box::new(ue::UeField {
                    image: strip,
                    i_max_cd: i_max,
                }),
            });
        }
    }
    if let Some((PhotometricType::B, name, tab)) = &x.as_type_c {
        let bake = |t: &IesTable| {
            if engine == Engine::Ue5 {
                ue::bake_ue5(t)
            } else {
                ue::bake_ue4(t)
            }
        };
        out.push(Defect {
            engine,
            name: name.clone(),
            source: UE_TYPE_B,
            versions: engine.version(),
            with: Box::new(ue::UeField {
                image: bake(tab)?,
                i_max_cd: tab.max_cd(),
            }),
            without: Box::new(ue::UeField {
                image: bake(t)?,
                i_max_cd: i_max,
            }),
        });
    }
    Ok(out)
}

/// Godot's naive export: linear I/I_max (`i_max` in cd) in the EXR, decoded
/// as sRGB by the atlas view.
fn godot_defect(engine: Engine, dist: &Distribution, i_max: f64) -> Result<Defect, ModelError> {
    let texture = crate::reconstruct::LightTexture::new(dist)?;
    let h = super::godot::DEFAULT_HEIGHT;
    let linear = super::godot::bake_linear(&texture.sampler(crate::reconstruct::Filter::CatmullRom), h, i_max)?;
    let encoded = super::godot::encode_for_godot(&linear)?;
    Ok(Defect {
        engine,
        name: "linear texture read through the sRGB atlas view".into(),
        source: GODOT_SRGB,
        versions: engine.version(),
        with: Box::new(super::godot::GodotField::new(&linear, i_max)),
        without: Box::new(super::godot::GodotField::new(&encoded, i_max)),
    })
}
