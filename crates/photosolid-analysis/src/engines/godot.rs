//! Godot 4: no IES support (godot-proposals #715, open; PR #63835 closed). The practice is an
//! `OmniLight3D` whose `light_projector` is an equirectangular panorama of the profile; Godot
//! turns it into a dual paraboloid in its decal atlas and looks it up per fragment.
//!
//! Sources (godotengine/godot, read through the public code index; the stored versions, not the
//! files at a release tag: the index holds the 4.3-stable commit 77dcf97d for `version.py` but
//! not these files at it):
//! - `servers/rendering/renderer_rd/shaders/scene_forward_lights_inc.glsl` (commit 001d4b23),
//!   `light_process_omni`: `local_v = normalize(shadow_matrix * vertex)` (the light-space
//!   direction to the fragment); `atlas_rect = projector_rect`, `atlas_rect.y += atlas_rect.w`
//!   when `local_v.z >= 0`; `local_v.z = 1 + |local_v.z|`, `local_v.xy /= local_v.z`,
//!   `* 0.5 + 0.5`, `proj_uv = local_v.xy * atlas_rect.zw`; then
//!   `textureGrad(...)` (with `sc_projector_use_mipmaps`) or `textureLod(..., 0.0)` of
//!   `sampler2D(decal_atlas_srgb, light_projector_sampler)` at `proj_uv + atlas_rect.xy`, and
//!   `color *= proj.rgb * proj.a`.
//! - `servers/rendering/renderer_rd/storage_rd/light_storage.cpp` (commit 006f0390): for an omni
//!   light `projector_rect = (rect.x, rect.y, rect.w, rect.h * 0.5)` ("used by dp, so needs to be
//!   half"); `light_set_projector` → `texture_add_to_decal_atlas(texture, type == OMNI)`.
//! - `servers/rendering/renderer_rd/storage_rd/texture_storage.cpp`, `update_decal_atlas`: the
//!   atlas is `DATA_FORMAT_R8G8B8A8_UNORM` with an `R8G8B8A8_SRGB` view (`texture_srgb`), cleared
//!   to (0, 0, 0, 0); each texture's rect is its own pixel size, placed at
//!   `pos * border + border / 2` (`border = 1 << mipmaps`); mip 0 is drawn with
//!   `copy_to_atlas_fb(src->rd_texture, fb, uv_rect, draw_list, false, panorama_to_dp_users > 0)`,
//!   the other levels by `copy_to_fb_rect` blits of the level above.
//! - `servers/rendering/renderer_rd/effects/copy_effects.cpp`, `copy_to_atlas_fb`: the source is
//!   sampled with `CANVAS_ITEM_TEXTURE_FILTER_LINEAR`, `CANVAS_ITEM_TEXTURE_REPEAT_DISABLED`
//!   (bilinear, clamp to edge); no sRGB conversion flag is set.
//! - `servers/rendering/renderer_rd/shaders/effects/copy_to_fb.glsl`, `MODE_PANORAMA_TO_DP`:
//!   `uv.y = modf(uv.y * 2, side)`, `side = side * 2 - 1`, `normal = (uv * 2 - 1, 0)`,
//!   `normal.z = 0.5 - 0.5 (x² + y²)`, `normal *= -side`, `st = (atan(n.x, n.z), acos(n.y))`
//!   (+2π when negative), `uv = st / (2π, π)`, and `uv = 1 - uv` for `side < 0`.
//! - Project settings: `rendering/textures/light_projectors/filter`, default
//!   `LIGHT_PROJECTOR_FILTER_LINEAR_MIPMAPS` (the setting's registration as quoted in the index).
//!
//! Composed, a light-space direction `d` (Godot: +Y up) reads the panorama at
//! `u = 1 − atan2(d.x, −d.z) / 2π` (wrapped to [0, 1)), `v = acos(−d.y) / π` (v = 0 is the first
//! row): the nadir is the panorama's *top* row, which is why users find projected sky panoramas
//! upside down (godotengine/godot #57704). photosolid's frame maps onto an unrotated light as
//! x → +X, y → −Z, z → +Y (a rotation), so column u holds C = 360·u + 90° (mod 360) and row v
//! holds γ = 180·v: C0 points along the light's +X, C90 along −Z (Godot's forward).
//!
//! What the emulation follows: the panorama as Godot holds it (half floats), the atlas copy
//! (bilinear, clamp, then 8-bit UNORM rounding), the lookup through the sRGB view (each texel
//! decoded, then bilinear; the atlas outside the rect is (0, 0, 0, 0), so `rgb * a` falls at
//! the rect's edges), mip level 0. The atlas stores the texture's values and decodes them as
//! sRGB, so the export writes sRGB-encoded I/I_max: Godot decodes it back to I/I_max.
//!
//! A property of the layout the emulation shows: the dual paraboloid's axis is the light's Z, so
//! the nadir (−Y) sits on the seam of the two halves, where the bilinear lookup mixes the last
//! row of the first half (directions near +Y, the zenith) into the nadir.

use std::f64::consts::{PI, TAU};

use super::table::{lerp, to_half, Image};
use crate::error::ModelError;
use crate::model::{frame, IntensityField};

/// Default panorama height (the width is twice it).
pub const DEFAULT_HEIGHT: usize = 256;
/// Largest panorama height photosolid writes (Godot's own limit is the GPU's texture size).
pub const MAX_HEIGHT: usize = 8192;

/// The steps of the emulation that follow no source.
pub const STAND_INS: &[&str] = &[
    "mip level 0 only: with the default filter (Linear Mipmaps) Godot's textureGrad picks the level from \
     the fragment's screen-space derivatives, which a lookup by direction does not have; the atlas mip \
     chain (copy_to_fb_rect blits of the whole atlas) is not modelled",
    "texture import: the EXR taken as imported Lossless in half floats (no VRAM compression modelled)",
];

/// sRGB encoding of a linear value in [0, 1] (the transfer function of `*_SRGB` formats).
pub use crate::solid::colormap::srgb_encode as linear_to_srgb;

/// sRGB decoding of an encoded value in [0, 1] (what sampling an `*_SRGB` view does per texel).
pub fn srgb_to_linear(c: f64) -> f64 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.040_45 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The (C, γ) of panorama texture coordinates (u, v) ∈ [0, 1]², degrees.
pub fn panorama_angles(u: f64, v: f64) -> (f64, f64) {
    (crate::model::wrap360(360.0 * u + 90.0), 180.0 * v)
}

/// Godot light-space direction (+Y up) of a photosolid direction: x → X, y → −Z, z → Y.
#[inline]
fn to_godot(d: glam::DVec3) -> glam::DVec3 {
    glam::DVec3::new(d.x, d.z, -d.y)
}

/// The panorama texture coordinates Godot reads for a Godot light-space direction `n`
/// (`copy_to_fb.glsl` `MODE_PANORAMA_TO_DP` composed with `light_process_omni`).
fn panorama_uv(n: glam::DVec3) -> (f64, f64) {
    let mut s = n.x.atan2(-n.z);
    if s < 0.0 {
        s += TAU;
    }
    let u = 1.0 - s / TAU;
    (if u >= 1.0 { u - 1.0 } else { u }, (-n.y).clamp(-1.0, 1.0).acos() / PI)
}

/// The equirectangular panorama of `field` (cd), `2h x h`: I / `i_max_cd` at texel centres,
/// linear (values above 1, a filter's overshoot, are kept; Godot's 8-bit atlas clips them).
///
/// # Errors
/// A height out of range, a non-positive `i_max_cd`.
pub fn bake_linear(field: &dyn IntensityField, h: usize, i_max_cd: f64) -> Result<Image, ModelError> {
    if !(2..=MAX_HEIGHT).contains(&h) {
        return Err(ModelError::Parameter {
            name: "resolution",
            value: h.to_string(),
            reason: format!("godot takes a panorama height of 2..={MAX_HEIGHT}"),
        });
    }
    if !(i_max_cd > 0.0 && i_max_cd.is_finite()) {
        return Err(ModelError::AllZero(
            "a Godot projector needs a positive maximum intensity",
        ));
    }
    let w = 2 * h;
    Image::from_fn(w, h, |x, y| {
        let (c, g) = panorama_angles((x as f64 + 0.5) / w as f64, (y as f64 + 0.5) / h as f64);
        (field.intensity_cd(c, g).max(0.0) / i_max_cd) as f32
    })
}

/// The texels to write: `linear` (I/I_max) sRGB-encoded, so that Godot's sRGB view of its
/// atlas decodes them back to I/I_max.
pub fn encode_for_godot(linear: &Image) -> Result<Image, ModelError> {
    Image::new(
        linear.width,
        linear.height,
        linear
            .data
            .iter()
            .map(|&v| linear_to_srgb(f64::from(v)) as f32)
            .collect(),
    )
}

/// Bilinear lookup at continuous texel coordinates (texel i centred at i), clamp to edge: the
/// copy's `REPEAT_DISABLED` linear sampler.
fn bilinear_clamp(im: &Image, x: f64, y: f64) -> f64 {
    im.bilinear_clamped(x, y)
}

/// Godot's omni projector: the dual-paraboloid rect of the decal atlas (mip 0) and its lookup.
#[derive(Debug, Clone)]
pub struct GodotField {
    /// The atlas rect: `w x h` 8-bit values (0..=255), the first half (rows 0..h/2) for
    /// light-space z < 0, the second for z ≥ 0.
    pub rect: Vec<u8>,
    /// Rect width (the panorama's width).
    pub width: usize,
    /// Rect height (the panorama's height; each half is `height / 2`, fractional when odd).
    pub height: usize,
    /// The light's intensity for a texel value of 1 (cd).
    pub i_max_cd: f64,
    /// sRGB decoding of each byte (Godot's `decal_atlas_srgb` view).
    decoded: [f64; 256],
}

impl GodotField {
    /// Build the atlas rect from the texels Godot holds (`texels`: the exported values, which
    /// Godot keeps as half floats) exactly as `update_decal_atlas` draws it.
    pub fn new(texels: &Image, i_max_cd: f64) -> Self {
        let (w, h) = (texels.width, texels.height);
        let held = Image {
            width: w,
            height: h,
            data: texels.data.iter().map(|&v| to_half(f64::from(v))).collect(),
        };
        let mut rect = vec![0u8; w * h];
        for j in 0..h {
            // The fragment's uv in the rect, then `MODE_PANORAMA_TO_DP`.
            let vy = (j as f64 + 0.5) / h as f64;
            let t = vy * 2.0;
            let side_index = t.floor();
            let frac_y = t - side_index;
            let side = side_index * 2.0 - 1.0;
            for i in 0..w {
                let ux = (i as f64 + 0.5) / w as f64;
                let (x, y) = (ux * 2.0 - 1.0, frac_y * 2.0 - 1.0);
                let z = 0.5 - 0.5 * (x * x + y * y);
                let n = (glam::DVec3::new(x, y, z) * -side).normalize();
                let mut s = n.x.atan2(n.z);
                if s < 0.0 {
                    s += TAU;
                }
                let (mut pu, mut pv) = (s / TAU, n.y.clamp(-1.0, 1.0).acos() / PI);
                if side < 0.0 {
                    pu = 1.0 - pu;
                    pv = 1.0 - pv;
                }
                let v = bilinear_clamp(&held, pu * w as f64 - 0.5, pv * h as f64 - 0.5);
                // UNORM8 attachment: clamp, round to nearest.
                rect[j * w + i] = (v.clamp(0.0, 1.0) * 255.0).round() as u8;
            }
        }
        let mut decoded = [0.0; 256];
        for (k, d) in decoded.iter_mut().enumerate() {
            *d = srgb_to_linear(k as f64 / 255.0);
        }
        Self {
            rect,
            width: w,
            height: h,
            i_max_cd,
            decoded,
        }
    }

    /// (decoded value, alpha) of atlas texel (x, y) of the rect; (0, 0) outside it (the atlas
    /// border, cleared to (0, 0, 0, 0)).
    #[inline]
    fn texel(&self, x: i64, y: i64) -> (f64, f64) {
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
            return (0.0, 0.0);
        }
        (
            self.decoded[self.rect[y as usize * self.width + x as usize] as usize],
            1.0,
        )
    }

    /// `light_process_omni`'s projector factor (`proj.rgb * proj.a`, one channel) for a Godot
    /// light-space unit direction.
    pub fn factor(&self, n: glam::DVec3) -> f64 {
        let (w, h) = (self.width as f64, self.height as f64);
        let half_h = 0.5 * h;
        let offset = if n.z >= 0.0 { half_h } else { 0.0 };
        let zp = 1.0 + n.z.abs();
        let (lx, ly) = (n.x / zp * 0.5 + 0.5, n.y / zp * 0.5 + 0.5);
        // Texel coordinates in the rect (texel i centred at i + 0.5 → subtract 0.5).
        let (px, py) = (lx * w - 0.5, ly * half_h + offset - 0.5);
        let (x0, y0) = (px.floor(), py.floor());
        let (fx, fy) = (px - x0, py - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let (a, b, c, d) = (
            self.texel(x0, y0),
            self.texel(x0 + 1, y0),
            self.texel(x0, y0 + 1),
            self.texel(x0 + 1, y0 + 1),
        );
        let rgb = lerp(lerp(a.0, b.0, fx), lerp(c.0, d.0, fx), fy);
        let alpha = lerp(lerp(a.1, b.1, fx), lerp(c.1, d.1, fx), fy);
        rgb * alpha
    }
}

/// Texture coordinates of the panorama a photosolid direction (C, γ) lands on, [0, 1)² (for
/// tests and the docs: the inverse of [`panorama_angles`]).
pub fn panorama_uv_of(c_deg: f64, gamma_deg: f64) -> (f64, f64) {
    panorama_uv(to_godot(frame::direction(c_deg, gamma_deg)))
}

impl IntensityField for GodotField {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        self.i_max_cd * self.factor(to_godot(frame::direction(c_deg, gamma_deg)))
    }
    fn name(&self) -> String {
        format!("Godot omni projector {}x{}", self.width, self.height)
    }
    fn bytes(&self) -> usize {
        // RGBA8 atlas texels.
        4 * self.width * self.height
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trip() {
        for k in 0..=100 {
            let v = k as f64 / 100.0;
            assert!((srgb_to_linear(linear_to_srgb(v)) - v).abs() < 1e-12);
        }
    }

    #[test]
    fn panorama_mapping_is_the_inverse_of_the_angles() {
        for (c, g) in [(0.0, 30.0), (90.0, 100.0), (200.0, 45.0), (300.0, 170.0)] {
            let (u, v) = panorama_uv_of(c, g);
            let (c2, g2) = panorama_angles(u, v);
            assert!(
                (crate::model::wrap360(c2 - c + 180.0) - 180.0).abs() < 1e-9,
                "{c} {g}: {c2}"
            );
            assert!((g2 - g).abs() < 1e-9, "{c} {g}: {g2}");
        }
        // The nadir is the top row.
        assert!(panorama_uv_of(0.0, 0.0).1.abs() < 1e-12);
    }

    #[test]
    fn a_uniform_panorama_is_one_inside_the_rect() {
        let im = Image::new(64, 32, vec![1.0; 64 * 32]).unwrap();
        let f = GodotField::new(&im, 10.0);
        // Away from the rect's edges and the seam: exactly 1 (255 decodes to 1).
        assert!((f.intensity_cd(45.0, 60.0) - 10.0).abs() < 1e-9);
        assert!((f.intensity_cd(200.0, 120.0) - 10.0).abs() < 1e-9);
    }
}
