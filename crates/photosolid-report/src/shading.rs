//! A plane lit by the luminaire, shaded through the real-time lookups: the
//! Figure 5 setting of Wallner 2008 (§5–6), headless.
//!
//! The luminaire hangs `height_m` above a horizontal plane, unrotated (its
//! nadir, γ = 0, straight down). Pixel (row i, column j) of an `n` × `n`
//! image is the plane point `P = (x, y, −height_m)` relative to the
//! luminaire, x = (j + ½)·2a/n − a, y = a − (i + ½)·2a/n (row 0 at +y,
//! a = `half_width_m`). Its value is Wallner's (2008) equation 4 with the plane's
//! cosine, the illuminance in lux:
//!
//! ```text
//! E(P) = I_max · LDT(θ, φ) · cos(ι) / d²,   d = |P|,   cos(ι) = height_m / d
//! ```
//!
//! (I_max · LDT = I, the intensity in cd towards P; ι the angle of incidence
//! on the plane, whose normal points up). The GPU image takes I from one batch
//! read by the installed device's texture hardware ([`GpuDevice::texture_samples`]); the CPU reference evaluates the same texels
//! with the exact lookup through the scene module's point-source formula
//! ([`crate::scene::illuminance::Source::lux`]), an independent path for
//! the geometry as well.

use std::path::Path;

use exr::prelude::{AttributeValue, FlatSamples, LayerAttributes, Text};
use glam::DVec3;

use crate::device::{GpuDevice, TextureStore};
use crate::error::{Error, GpuError, ModelError};
use crate::model::IntensityField;
use crate::reconstruct::{exr_io, Lookup, Precision, Rendered, StoredTexture};
use crate::scene::aim::{Aim, Pose};
use crate::scene::illuminance::Source;
use crate::scene::ScenePoint;
use crate::solid::ColorMap;

/// Where the plane is and how finely it is sampled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneView {
    /// Height of the luminaire over the plane, m (> 0).
    pub height_m: f64,
    /// Half the side of the square shown, m (> 0), centred under the luminaire.
    pub half_width_m: f64,
    /// Pixels per side (≥ 1).
    pub pixels: usize,
}

impl Default for PlaneView {
    /// 1 m over the plane, ±3 m shown, 256 × 256 pixels.
    fn default() -> Self {
        Self {
            height_m: 1.0,
            half_width_m: 3.0,
            pixels: 256,
        }
    }
}

impl PlaneView {
    /// The plane point of every pixel relative to the luminaire (m), row-major.
    pub fn points(&self) -> Vec<DVec3> {
        let (n, a) = (self.pixels, self.half_width_m);
        let step = 2.0 * a / n as f64;
        (0..n * n)
            .map(|k| {
                let (i, j) = (k / n, k % n);
                DVec3::new((j as f64 + 0.5) * step - a, a - (i as f64 + 0.5) * step, -self.height_m)
            })
            .collect()
    }

    /// cos(ι) / d² (1/m²) at each pixel: what turns candela into lux.
    pub fn lux_per_cd(&self) -> Vec<f64> {
        self.points()
            .iter()
            .map(|p| {
                let d2 = p.length_squared();
                self.height_m / (d2 * d2.sqrt())
            })
            .collect()
    }

    fn check(&self) -> Result<(), GpuError> {
        let positive = |v: f64| v > 0.0 && v.is_finite();
        if !(positive(self.height_m) && positive(self.half_width_m) && (1..=8192).contains(&self.pixels)) {
            return Err(GpuError::InvalidJob {
                index: 0,
                reason: format!("plane view {self:?}: height and half width must be positive, 1-8192 pixels"),
            });
        }
        Ok(())
    }
}

/// The plane lit through the GPU: illuminance (lx) at every pixel and what read the intensities.
#[derive(Debug, Clone, PartialEq)]
pub struct ShadedGpu {
    /// Illuminance (lx) at every pixel, row-major.
    pub lux: Vec<f64>,
    /// Where and how the texels were held (`F16` where the adapter cannot filter f32).
    pub store: TextureStore,
}

/// Illuminance (lx) at every pixel of `view`, the intensities read by `device`'s texture hardware
/// through `lookup` of `rendered` stored in f32, or f16 where the adapter cannot filter f32 (one batch).
///
/// # Errors
/// An invalid view; the errors of [`GpuDevice::texture_samples`].
pub fn shade_gpu(
    device: &dyn GpuDevice,
    rendered: &Rendered,
    lookup: Lookup,
    view: &PlaneView,
) -> Result<ShadedGpu, GpuError> {
    view.check()?;
    let samples = device.texture_samples(rendered, Precision::F32, lookup, &view.points())?;
    Ok(ShadedGpu {
        lux: samples.cd.iter().zip(view.lux_per_cd()).map(|(i, g)| i * g).collect(),
        store: samples.store,
    })
}

/// Illuminance (lx) at every pixel of `view` from `field` on the CPU,
/// through [`Source::lux`] (a point source `height_m` over the plane, maintenance factor 1).
///
/// # Errors
/// An invalid view.
pub fn shade_cpu(field: &dyn IntensityField, view: &PlaneView) -> Result<Vec<f64>, GpuError> {
    view.check()?;
    let source = Source {
        field,
        pose: Pose::new(DVec3::new(0.0, 0.0, view.height_m), Aim::default()),
        maintenance_factor: 1.0,
        patches: vec![(DVec3::ZERO, 1.0)],
    };
    let points: Vec<ScenePoint> = view
        .points()
        .iter()
        .enumerate()
        .map(|(index, p)| ScenePoint {
            position: DVec3::new(p.x, p.y, 0.0),
            normal: DVec3::Z,
            receiver: 0,
            index,
        })
        .collect();
    Ok(source.lux_all(&points, &[], None))
}

/// Write an image of `view` (lux or lux differences, row-major) as a
/// one-channel f32 OpenEXR (`Y`), recording what it shows in `photosolid.*` attributes.
///
/// # Errors
/// [`Error::Io`] / [`Error::Encode`] / [`ModelError::Parameter`] from [`exr_io::write_layer`].
pub fn write_exr(path: &Path, view: &PlaneView, values: &[f64], what: &str) -> Result<(), Error> {
    let mut attrs = LayerAttributes::named("photosolid-plane");
    let mut put = |k: &str, v: AttributeValue| {
        attrs.other.insert(Text::from(k), v);
    };
    put("photosolid.image", AttributeValue::Text(exr_io::text(what)));
    put("photosolid.unit", AttributeValue::Text(exr_io::text("lx")));
    put("photosolid.height_m", AttributeValue::F64(view.height_m));
    put("photosolid.half_width_m", AttributeValue::F64(view.half_width_m));
    put(
        "photosolid.formula",
        AttributeValue::Text(exr_io::text(
            "E = I_max LDT(theta, phi) cos(i) / d^2, cos(i) = height / d",
        )),
    );
    let samples = FlatSamples::F32(values.iter().map(|&v| v as f32).collect());
    exr_io::write_layer(path, (view.pixels, view.pixels), attrs, "Y", samples)
}

/// How [`png`] colours an image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tone {
    /// Grey levels through Wallner's exposure `1 − e^(−k·E/E_max)`, k = 3 (white: bright).
    Exposure,
    /// Blue–white–red over ±max |value| (white: 0), for differences.
    Diverging,
}

/// An 8-bit RGB PNG of `values` (`view.pixels` square, row-major).
///
/// # Errors
/// [`ModelError::Parameter`] when the sizes disagree, [`Error::Encode`] when encoding fails.
pub fn png(view: &PlaneView, values: &[f64], tone: Tone) -> Result<Vec<u8>, Error> {
    let n = view.pixels;
    if values.len() != n * n {
        return Err(ModelError::Parameter {
            name: "values",
            value: format!("{} values", values.len()),
            reason: format!("a {n} x {n} image needs {}", n * n),
        }
        .into());
    }
    let scale = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut pm = tiny_skia::Pixmap::new(n as u32, n as u32).ok_or_else(|| Error::Encode {
        format: "PNG",
        message: format!("cannot allocate a {n} x {n} image"),
    })?;
    for (px, &v) in pm.pixels_mut().iter_mut().zip(values) {
        let t = if scale > 0.0 && v.is_finite() { v / scale } else { 0.0 };
        let [r, g, b] = match tone {
            Tone::Exposure => {
                let y = (255.0 * (1.0 - (-3.0 * t).exp()) / (1.0 - (-3.0f64).exp())).round() as u8;
                [y, y, y]
            }
            Tone::Diverging => ColorMap::RdBu.rgb8(0.5 + 0.5 * t),
        };
        *px = tiny_skia::PremultipliedColorU8::from_rgba(r, g, b, 255)
            .unwrap_or(tiny_skia::PremultipliedColorU8::TRANSPARENT);
    }
    pm.encode_png().map_err(|e| Error::Encode {
        format: "PNG",
        message: e.to_string(),
    })
}

/// The shaded-plane images of `rendered` for a report: the plane under the
/// bilinear and the Catmull–Rom lookup and their difference (bilinear −
/// Catmull–Rom), on `device`'s texture hardware when one is given and always
/// with the exact CPU lookups on the same texels (the reference). EXRs (lux,
/// f32) are written into `dir`; the PNGs come back as report figures, with
/// one line per image pair saying how far GPU and CPU differ.
///
/// # Errors
/// Writing the EXRs, encoding the PNGs ([`Error::Encode`]), device errors ([`crate::error::GpuError`]).
pub fn report_figures(
    device: Option<&dyn GpuDevice>,
    rendered: &Rendered,
    view: &PlaneView,
    dir: &Path,
) -> Result<(Vec<crate::compare_report::Figure>, Vec<String>), Error> {
    let formula = format!(
        "E = I cos(i) / d^2 on a plane {} m under the luminaire, ±{} m shown",
        view.height_m, view.half_width_m
    );
    let (mut figs, mut notes) = (Vec::new(), vec![formula.clone()]);
    for (device, tag) in [(device, "gpu"), (None, "cpu")] {
        if tag == "gpu" && device.is_none() {
            continue;
        }
        let mut lit = Vec::new();
        for lookup in [Lookup::Bilinear, Lookup::CatmullRom] {
            let name = lookup.name().replace('-', "_");
            let values = lit_plane(device, rendered, view, lookup, &mut notes)?;
            let who = if tag == "gpu" {
                "GPU texture hardware"
            } else {
                "CPU exact lookup"
            };
            figs.push(plane_image(
                dir,
                view,
                &format!("plane_{name}_{tag}"),
                format!("Plane lit through the {lookup} lookup ({who}); {formula}"),
                &values,
                Tone::Exposure,
            )?);
            lit.push(values);
        }
        let diff: Vec<f64> = lit[0].iter().zip(&lit[1]).map(|(a, b)| a - b).collect();
        let m = diff.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        figs.push(plane_image(
            dir,
            view,
            &format!("plane_difference_{tag}"),
            format!("Bilinear minus Catmull-Rom ({tag}), blue < 0 < red, ±{m:.2} lx; {formula}"),
            &diff,
            Tone::Diverging,
        )?);
    }
    Ok((figs, notes))
}

/// The plane lit through `lookup` of `rendered`: on `device`'s texture
/// hardware (with a note on how far it is from the CPU lookup of the same
/// texels), or with the exact CPU lookup when there is no device.
fn lit_plane(
    device: Option<&dyn GpuDevice>,
    rendered: &Rendered,
    view: &PlaneView,
    lookup: Lookup,
    notes: &mut Vec<String>,
) -> Result<Vec<f64>, Error> {
    let Some(device) = device else {
        return Ok(shade_cpu(
            &StoredTexture::new(rendered, None, Precision::F32, lookup),
            view,
        )?);
    };
    let gpu = shade_gpu(device, rendered, lookup, view)?;
    // The CPU lookup of the same texels: stored as the device stored them.
    let cpu = shade_cpu(&StoredTexture::new(rendered, None, gpu.store.precision, lookup), view)?;
    let d = gpu.lux.iter().zip(&cpu).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    notes.push(format!(
        "{lookup} on {} ({}): max |GPU - CPU| = {d:.3e} lx of {:.1} lx",
        gpu.store.adapter,
        gpu.store.texture_format,
        cpu.iter().copied().fold(0.0, f64::max)
    ));
    Ok(gpu.lux)
}

/// One image of the plane: its EXR `name`.exr written into `dir` (created
/// if missing), its PNG in `tone` returned as a report figure.
fn plane_image(
    dir: &Path,
    view: &PlaneView,
    name: &str,
    caption: String,
    values: &[f64],
    tone: Tone,
) -> Result<crate::compare_report::Figure, Error> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    write_exr(&dir.join(format!("{name}.exr")), view, values, &caption)?;
    Ok(crate::compare_report::Figure {
        file: format!("{name}.png"),
        caption,
        png: png(view, values, tone)?,
    })
}
