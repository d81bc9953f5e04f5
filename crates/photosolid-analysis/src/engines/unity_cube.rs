//! Unity's point-light IES path after `IESEngine`: the cube map Unity's
//! texture importer makes of the 2N x 2N cylindrical buffer, and HDRP's
//! octahedral copy of that cube map in its cookie atlas, looked up bilinearly.
//!
//! Steps and their sources:
//! 1. Cube map, face side N. `IESEngine.GenerateCubeCookie` hands the buffer
//!    to `TextureGenerator.GenerateTexture` with `TextureImporterShape.TextureCube`
//!    and `generateCubemap = Cylindrical` (Unity-Technologies/Graphics,
//!    commit 0328a1b1, `com.unity.render-pipelines.core/Editor/Lighting/IESEngine.cs`);
//!    the HDRP manual (IES importer, 10.x) says "For point lights, this is the
//!    size of the cubemap" of `IES Size` (N). The conversion itself is in
//!    Unity's native editor code, which is not public: **stand-in** — each
//!    face texel takes the bilinear value of the buffer at its centre's
//!    direction, the buffer's angles read as the inverse of
//!    `BuildTypeCCylindricalTexture` ([`cylindrical_coords`]),
//!    rounded to 8 bits (uncompressed RGBA32; the importer's default BC7
//!    compression is not modelled).
//! 2. Face layout: the cube-map face selection and face coordinates of the
//!    OpenGL 4.6 specification, §8.13 "Cube Map Texture Selection", table 8.19
//!    (Direct3D uses the same faces and orientation).
//! 3. Octahedral projection: `LightCookieManager.FetchCubeCookie`
//!    (`com.unity.render-pipelines.high-definition/Runtime/Lighting/LightCookieManager.cs`,
//!    commit 85898ebe, `UNITY_2020_1_OR_NEWER`): `projectionSize = 2 * cookie.width`,
//!    `FilterAreaLightTexture` pass 3 ("Project Cube to Octahedral",
//!    `com.unity.render-pipelines.high-definition/Runtime/Core/CoreResources/FilterAreaLightCookies.shader`,
//!    commit cfc4b936, lines 129–142):
//!    each texel samples the cube with its own sampler (bilinear, set by
//!    `IESEngine.GenerateTexture`) at `UnpackNormalOctQuadEncode(2·uv − 1)`;
//!    the shader compiles only for d3d11, consoles, Vulkan and Metal, whose
//!    cube sampling is seamless (bilinear footprints cross face edges; at a
//!    cube corner the missing texel is the mean of the three others, as the
//!    Direct3D 11 specification describes). The atlas is `R11G11B10` by
//!    default (`GlobalLightLoopSettings.NewDefault`): 6-bit mantissas.
//! 4. Lookup: `CookieSampling.hlsl` (commit a1e46132) lines 45–52 `SamplePointCookie`:
//!    `uv = saturate(PackNormalOctQuadEncode(lightToSample) * 0.5 + 0.5)`,
//!    `SampleCookie2D` bilinear at mip 0 (`s_trilinear_clamp_sampler`, LOD 0).
//!    `RemapUVWithPadding` (the atlas padding, under a texel) is not modelled.
//!
//! Directions are in the buffer's cube space: +X = C90, +Y = C0, +Z = nadir
//! (`BuildTypeCCylindricalTexture` "orient it toward +Z at the center").

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use glam::DVec3;

use super::table::{to_f11, Image};

/// Continuous texel coordinates (x, y) of direction (C, γ) in the cylindrical buffer.
pub fn cylindrical_coords(c_deg: f64, gamma_deg: f64, w: usize, h: usize) -> (f64, f64) {
    let (sg, cg) = crate::model::frame::sin_cos_deg(gamma_deg);
    let (sc, cc) = crate::model::frame::sin_cos_deg(c_deg);
    // Components: +X = C90, +Y = C0, +Z = nadir.
    let (dx, dy, dz) = (sg * sc, sg * cc, cg);
    let v = dy.clamp(-1.0, 1.0).asin();
    let u = dx.atan2(dz);
    ((PI - u) / TAU * (w - 1) as f64, (v + FRAC_PI_2) / PI * (h - 1) as f64)
}

/// `(major axis, s axis, t axis)` of each face, in the order +X, −X, +Y,
/// −Y, +Z, −Z: a direction on face f is `major + sc·s + tc·t` with
/// `sc, tc ∈ [−1, 1]` (OpenGL 4.6 table 8.19).
const FACES: [(DVec3, DVec3, DVec3); 6] = [
    (DVec3::X, DVec3::NEG_Z, DVec3::NEG_Y),
    (DVec3::NEG_X, DVec3::Z, DVec3::NEG_Y),
    (DVec3::Y, DVec3::X, DVec3::Z),
    (DVec3::NEG_Y, DVec3::X, DVec3::NEG_Z),
    (DVec3::Z, DVec3::X, DVec3::NEG_Y),
    (DVec3::NEG_Z, DVec3::NEG_X, DVec3::NEG_Y),
];

/// The face (0..6: +X, −X, +Y, −Y, +Z, −Z) a direction selects and its face
/// coordinates `(s, t)` in [0, 1] (the largest component's axis; ties go to
/// x, then y). The zero vector gives face +Z's centre.
pub fn face_coords(d: DVec3) -> (usize, f64, f64) {
    let a = d.abs();
    let face = if a.x >= a.y && a.x >= a.z && a.x > 0.0 {
        usize::from(d.x < 0.0)
    } else if a.y >= a.z && a.y > 0.0 {
        2 + usize::from(d.y < 0.0)
    } else if a.z > 0.0 {
        4 + usize::from(d.z < 0.0)
    } else {
        return (4, 0.5, 0.5);
    };
    let (major, s_axis, t_axis) = FACES[face];
    let ma = d.dot(major);
    (face, 0.5 * (d.dot(s_axis) / ma + 1.0), 0.5 * (d.dot(t_axis) / ma + 1.0))
}

/// The (unnormalised) direction of face coordinates `(sc, tc)` in [−1, 1]
/// (beyond it for points past the face's edge).
fn face_point(face: usize, sc: f64, tc: f64) -> DVec3 {
    let (major, s_axis, t_axis) = FACES[face];
    major + sc * s_axis + tc * t_axis
}

/// The unit direction of texel `(i, j)`'s centre on `face` of side `size`.
pub fn texel_direction(face: usize, i: usize, j: usize, size: usize) -> DVec3 {
    let c = |k: usize| 2.0 * (k as f64 + 0.5) / size as f64 - 1.0;
    face_point(face, c(i), c(j)).normalize()
}

/// A cube map of one channel: `data[(face * size + j) * size + i]`.
#[derive(Debug, Clone, PartialEq)]
pub struct CubeMap {
    /// Texels a face side.
    pub size: usize,
    /// Texel values, faces +X, −X, +Y, −Y, +Z, −Z, each row-major.
    pub data: Vec<f32>,
}

impl CubeMap {
    /// A cube map whose texel `(i, j)` of `face` is `f(face, i, j)`.
    pub fn from_fn(size: usize, f: impl Fn(usize, usize, usize) -> f32 + Sync) -> Self {
        use rayon::prelude::*;
        let size = size.max(1);
        let mut data = vec![0.0f32; 6 * size * size];
        data.par_chunks_mut(size).enumerate().for_each(|(row, out)| {
            let (face, j) = (row / size, row % size);
            for (i, v) in out.iter_mut().enumerate() {
                *v = f(face, i, j);
            }
        });
        Self { size, data }
    }

    /// Step 1 (stand-in for Unity's native conversion): the cube map of
    /// side `size` of the `2N x 2N` cylindrical buffer, 8-bit texels.
    pub fn from_cylindrical(buffer: &Image, size: usize) -> Self {
        Self::from_fn(size, |face, i, j| {
            let d = texel_direction(face, i, j, size);
            let (c, g) = crate::model::frame::unit_angles(cube_to_frame(d));
            let (x, y) = cylindrical_coords(c, g, buffer.width, buffer.height);
            // Rounded to the nearest 8-bit step (a resampler's output; IESEngine's own
            // truncation is in the buffer already, and truncating twice would halve the
            // flux of dim regions by another half step).
            ((buffer.bilinear_clamped(x, y) * 255.0).round().clamp(0.0, 255.0) / 255.0) as f32
        })
    }

    #[inline]
    fn texel(&self, face: usize, i: usize, j: usize) -> f64 {
        f64::from(self.data[(face * self.size + j) * self.size + i])
    }

    /// Texel `(i, j)` of `face` where `i` or `j` may lie one texel past the
    /// face's edge: the neighbouring face's texel under that point (seamless
    /// addressing). `None` past a corner (both outside).
    fn texel_seamless(&self, face: usize, i: i64, j: i64) -> Option<f64> {
        let n = self.size as i64;
        let inside = |k: i64| (0..n).contains(&k);
        match (inside(i), inside(j)) {
            (true, true) => Some(self.texel(face, i as usize, j as usize)),
            (false, false) => None,
            _ => {
                let c = |k: i64| 2.0 * (k as f64 + 0.5) / n as f64 - 1.0;
                let (f2, s, t) = face_coords(face_point(face, c(i), c(j)));
                let k = |u: f64| ((u * n as f64).floor() as i64).clamp(0, n - 1) as usize;
                Some(self.texel(f2, k(s), k(t)))
            }
        }
    }

    /// Bilinear lookup with seamless cube filtering (the footprint crosses
    /// face edges; at a corner the missing texel is the mean of the other three).
    pub fn sample(&self, d: DVec3) -> f64 {
        if !d.is_finite() {
            return 0.0;
        }
        let (face, s, t) = face_coords(d);
        let n = self.size as f64;
        let (x, y) = (s * n - 0.5, t * n - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let taps = [
            self.texel_seamless(face, x0, y0),
            self.texel_seamless(face, x0 + 1, y0),
            self.texel_seamless(face, x0, y0 + 1),
            self.texel_seamless(face, x0 + 1, y0 + 1),
        ];
        let known: Vec<f64> = taps.iter().flatten().copied().collect();
        let fill = known.iter().sum::<f64>() / known.len().max(1) as f64;
        let v = |k: usize| taps[k].unwrap_or(fill);
        let a = v(0) + (v(1) - v(0)) * fx;
        let b = v(2) + (v(3) - v(2)) * fx;
        a + (b - a) * fy
    }
}

/// `PackNormalOctQuadEncode` (`com.unity.render-pipelines.core/ShaderLibrary/Packing.hlsl`):
/// the octahedral coordinates in [−1, 1]² of direction `d`.
pub fn oct_encode(d: DVec3) -> (f64, f64) {
    let l1 = d.x.abs() + d.y.abs() + d.z.abs();
    let n = d / l1.max(1e-6);
    let t = (-n.z).clamp(0.0, 1.0);
    let push = |a: f64| if a >= 0.0 { a + t } else { a - t };
    (push(n.x), push(n.y))
}

/// `UnpackNormalOctQuadEncode`: the unit direction of octahedral coordinates `(fx, fy)`.
pub fn oct_decode(fx: f64, fy: f64) -> DVec3 {
    let z = 1.0 - fx.abs() - fy.abs();
    let t = (-z).max(0.0);
    let pull = |a: f64| if a >= 0.0 { a - t } else { a + t };
    DVec3::new(pull(fx), pull(fy), z).normalize()
}

/// Step 3: HDRP's octahedral copy of `cube` (side `2 · cube.size`), each
/// texel the seamless bilinear cube sample at its centre's direction, in
/// `R11G11B10` precision.
pub fn octahedral(cube: &CubeMap) -> Result<Image, crate::error::ModelError> {
    let side = 2 * cube.size;
    Image::from_fn(side, side, |i, j| {
        let uv = |k: usize| (k as f64 + 0.5) / side as f64;
        to_f11(cube.sample(oct_decode(2.0 * uv(i) - 1.0, 2.0 * uv(j) - 1.0)))
    })
}

/// Step 4: `SamplePointCookie` on the octahedral image (bilinear, clamped).
pub fn sample_octahedral(oct: &Image, d: DVec3) -> f64 {
    if !d.is_finite() || d == DVec3::ZERO {
        return 0.0;
    }
    let (fx, fy) = oct_encode(d);
    let u = (0.5 * fx + 0.5).clamp(0.0, 1.0);
    let v = (0.5 * fy + 0.5).clamp(0.0, 1.0);
    oct.bilinear_clamped(u * oct.width as f64 - 0.5, v * oct.height as f64 - 0.5)
}

/// The buffer's cube-space direction (+X = C90, +Y = C0, +Z = nadir) of a
/// luminaire-frame direction ([`crate::model::frame`]: C0 = +x, C90 = +y, nadir −z).
#[inline]
pub fn frame_to_cube(d: DVec3) -> DVec3 {
    DVec3::new(d.y, d.x, -d.z)
}

/// Inverse of [`frame_to_cube`].
#[inline]
pub fn cube_to_frame(d: DVec3) -> DVec3 {
    DVec3::new(d.y, d.x, -d.z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texel_centres_round_trip() {
        let n = 8;
        for face in 0..6 {
            for (i, j) in [(0, 0), (3, 5), (7, 7), (7, 0)] {
                let (f2, s, t) = face_coords(texel_direction(face, i, j, n));
                assert_eq!(f2, face);
                assert_eq!(((s * n as f64) as usize, (t * n as f64) as usize), (i, j));
            }
        }
    }

    #[test]
    fn octahedral_round_trip() {
        for d in [
            DVec3::new(0.3, -0.5, 0.8),
            DVec3::new(-0.2, 0.1, -0.97),
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::new(1.0, 0.0, 0.0),
        ] {
            let d = d.normalize();
            let (x, y) = oct_encode(d);
            assert!((oct_decode(x, y) - d).length() < 1e-12, "{d}");
        }
        // +Z is the centre, −Z the corners.
        assert_eq!(oct_encode(DVec3::Z), (0.0, 0.0));
        let (x, y) = oct_encode(DVec3::NEG_Z);
        assert_eq!((x.abs(), y.abs()), (1.0, 1.0));
    }

    #[test]
    fn frame_maps_to_the_buffer_axes() {
        let c = |c, g| frame_to_cube(crate::model::frame::direction(c, g));
        assert!((c(0.0, 0.0) - DVec3::Z).length() < 1e-12);
        assert!((c(0.0, 90.0) - DVec3::Y).length() < 1e-12);
        assert!((c(90.0, 90.0) - DVec3::X).length() < 1e-12);
        let d = DVec3::new(0.2, -0.3, 0.9);
        assert!((cube_to_frame(frame_to_cube(d)) - d).length() < 1e-15);
    }
}
