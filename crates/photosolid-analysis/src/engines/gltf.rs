//! glTF 2.0: the solid mesh, the fitted lights as `KHR_lights_punctual` and
//! the IES profile itself through `EXT_lights_ies`, in one GLB.
//!
//! Sources (KhronosGroup/glTF):
//! - `extensions/2.0/Khronos/KHR_lights_punctual/README.md`: point and spot
//!   intensities in candela, spot `innerConeAngle` < `outerConeAngle` ≤ π/2
//!   (radians), lights point down the node's −Z; the recommended angular
//!   attenuation is `saturate(cosθ · scale + offset)²` with
//!   `scale = 1 / max(0.001, cos(inner) − cos(outer))`, `offset = −cos(outer) · scale`.
//! - `extensions/2.0/Vendor/EXT_lights_ies/README.md` (commit 10301d57, "Status: Complete"):
//!   a profile is a `uri` or a `bufferView` with `mimeType`
//!   `application/x-ies-lm-63`; a node's `EXT_lights_ies.light` instantiates
//!   it (`multiplier`, `color` optional); (0, 0) points down −Z, the X/Z
//!   plane is the vertical photometric plane (C0 on +X) and positive
//!   rotation is counter-clockwise: the luminaire frame of
//!   [`crate::model::frame`] unchanged.
//!
//! The light nodes are children of the solid's node, whose −90° rotation
//! about x turns the luminaire frame (z up) into glTF's +Y up. The emulated
//! field of the `gltf` engine is the `KHR_lights_punctual` fallback (the
//! fitted OpenGL lights converted to glTF cones), which is what a viewer
//! without `EXT_lights_ies` shows; a renderer with it reads the embedded
//! IES file (its lookup is the renderer's own).

use glam::{DQuat, DVec3};
use serde_json::json;

use crate::fit::{FittedLights, Light};
use crate::model::IntensityField;
use crate::solid::Mesh;

/// One `KHR_lights_punctual` light in the luminaire frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KhrLight {
    /// A point light, cd.
    Point {
        /// Intensity, cd.
        intensity_cd: f64,
    },
    /// A spot light.
    Spot {
        /// Intensity on the axis, cd.
        intensity_cd: f64,
        /// Unit axis, luminaire frame.
        axis: DVec3,
        /// Inner cone angle, radians.
        inner_rad: f64,
        /// Outer cone angle, radians (≤ π/2).
        outer_rad: f64,
    },
}

/// The KHR angular attenuation at cos θ (recommended implementation).
#[inline]
pub fn khr_attenuation(cos_theta: f64, inner_rad: f64, outer_rad: f64) -> f64 {
    let scale = 1.0 / (inner_rad.cos() - outer_rad.cos()).max(0.001);
    let offset = -outer_rad.cos() * scale;
    let a = (cos_theta * scale + offset).clamp(0.0, 1.0);
    a * a
}

impl KhrLight {
    /// Intensity (cd) in the unit direction `d`.
    pub fn intensity_dir(&self, d: DVec3) -> f64 {
        match *self {
            KhrLight::Point { intensity_cd } => intensity_cd,
            KhrLight::Spot {
                intensity_cd,
                axis,
                inner_rad,
                outer_rad,
            } => intensity_cd * khr_attenuation(d.dot(axis), inner_rad, outer_rad),
        }
    }
}

/// The fitted OpenGL lights as glTF lights: a point light as is; a spot
/// `w cos^n θ` (cut off at θ_c) as a KHR spot of intensity w whose outer and
/// inner cones (1° steps, outer ≤ min(θ_c, 90°) rounded up, inner < outer)
/// minimise the solid-angle-weighted squared difference of the two profiles.
pub fn khr_lights(fitted: &FittedLights) -> Vec<KhrLight> {
    fitted
        .lights
        .iter()
        .map(|l| match l {
            Light::Point { weight_cd } => KhrLight::Point {
                intensity_cd: *weight_cd,
            },
            Light::Spot(s) => {
                let (inner, outer) = khr_cone(s.exponent, s.cutoff_deg);
                KhrLight::Spot {
                    intensity_cd: s.weight_cd,
                    axis: s.axis(),
                    inner_rad: inner,
                    outer_rad: outer,
                }
            }
        })
        .collect()
}

/// The KHR (inner, outer) cone angles (radians) closest to the GL profile `cos^n θ` cut off at `cutoff_deg`.
fn khr_cone(exponent: f64, cutoff_deg: f64) -> (f64, f64) {
    let cut = cutoff_deg.clamp(0.0, 90.0).to_radians();
    let samples: Vec<(f64, f64, f64)> = (0..=360)
        .map(|k| {
            let t = std::f64::consts::FRAC_PI_2 * k as f64 / 360.0;
            let gl = if t <= cut { t.cos().powf(exponent) } else { 0.0 };
            (t.cos(), gl, t.sin())
        })
        .collect();
    let err = |inner: f64, outer: f64| -> f64 {
        samples
            .iter()
            .map(|&(c, gl, w)| (gl - khr_attenuation(c, inner, outer)).powi(2) * w)
            .sum()
    };
    let max_outer = (cutoff_deg.clamp(1.0, 90.0)).ceil() as usize;
    let mut best = (f64::INFINITY, 0.0, 1f64.to_radians());
    for o in 1..=max_outer {
        for i in 0..o {
            let (inner, outer) = ((i as f64).to_radians(), (o as f64).to_radians());
            let e = err(inner, outer);
            if e < best.0 {
                best = (e, inner, outer);
            }
        }
    }
    (best.1, best.2)
}

/// The glTF lights as a field (cd): what a viewer with only `KHR_lights_punctual` emits.
#[derive(Debug, Clone)]
pub struct KhrField {
    /// The lights, summed.
    pub lights: Vec<KhrLight>,
}

impl IntensityField for KhrField {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        self.intensity_dir_cd(crate::model::frame::direction(c_deg, gamma_deg))
    }
    fn intensity_dir_cd(&self, d: DVec3) -> f64 {
        match d.try_normalize() {
            Some(u) => self.lights.iter().map(|l| l.intensity_dir(u)).sum(),
            None => 0.0,
        }
    }
    fn name(&self) -> String {
        format!("KHR_lights_punctual x{}", self.lights.len())
    }
    fn bytes(&self) -> usize {
        self.lights.len() * std::mem::size_of::<KhrLight>()
    }
}

/// The GLB: `solid` (node 0), the IES profile `ies` embedded through a
/// bufferView on a child node, and each KHR light on its own child node.
pub fn encode(solid: &Mesh, ies: &[u8], lights: &[KhrLight]) -> Vec<u8> {
    let (mut doc, mut bin) = crate::solid::export::glb::document(solid);
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let offset = bin.len();
    bin.extend_from_slice(ies);
    #[allow(
        clippy::expect_used,
        reason = "`glb::document` always writes the solid's bufferViews array"
    )]
    let views = doc["bufferViews"].as_array_mut().expect("the solid's buffer views");
    views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": ies.len()}));
    let ies_view = views.len() - 1;

    let mut khr = Vec::new();
    let mut nodes = vec![json!({
        "name": "IES profile (EXT_lights_ies)",
        "extensions": {"EXT_lights_ies": {"light": 0, "multiplier": 1.0}}
    })];
    for (i, l) in lights.iter().enumerate() {
        match *l {
            KhrLight::Point { intensity_cd } => {
                khr.push(json!({"type": "point", "intensity": intensity_cd, "name": format!("fitted point {i}")}));
                nodes.push(json!({"name": format!("fitted point {i} (KHR_lights_punctual)"),
                    "extensions": {"KHR_lights_punctual": {"light": i}}}));
            }
            KhrLight::Spot {
                intensity_cd,
                axis,
                inner_rad,
                outer_rad,
            } => {
                khr.push(
                    json!({"type": "spot", "intensity": intensity_cd, "name": format!("fitted spot {i}"),
                    "spot": {"innerConeAngle": inner_rad, "outerConeAngle": outer_rad}}),
                );
                let q = DQuat::from_rotation_arc(DVec3::NEG_Z, axis.normalize());
                nodes.push(json!({"name": format!("fitted spot {i} (KHR_lights_punctual)"),
                    "rotation": [q.x, q.y, q.z, q.w],
                    "extensions": {"KHR_lights_punctual": {"light": i}}}));
            }
        }
    }
    #[allow(
        clippy::expect_used,
        reason = "`glb::document` always writes the nodes array with the solid's node"
    )]
    let all = doc["nodes"].as_array_mut().expect("the solid's node");
    let first_child = all.len();
    let children: Vec<usize> = (first_child..first_child + nodes.len()).collect();
    all[0]["children"] = json!(children);
    all.extend(nodes);
    doc["extensionsUsed"] = json!(["KHR_lights_punctual", "EXT_lights_ies"]);
    doc["extensions"] = json!({
        "KHR_lights_punctual": {"lights": khr},
        "EXT_lights_ies": {"lights": [{"bufferView": ies_view, "mimeType": "application/x-ies-lm-63", "name": "photometric file"}]}
    });
    doc["asset"]["extras"]["photosolid"]["lights"] = json!(
        "node 0's children: the IES profile (EXT_lights_ies, light frame = luminaire frame) and the fitted \
         lights (KHR_lights_punctual, a fallback for viewers without EXT_lights_ies; a renderer with both \
         should show only one of them)"
    );
    crate::solid::export::glb::pack(&doc, bin)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn attenuation_and_cone_fit() {
        assert_eq!(khr_attenuation(1.0, 0.2, 0.5), 1.0);
        assert_eq!(khr_attenuation(0.5f64.cos() - 1e-9, 0.2, 0.5), 0.0);
        let fitted = FittedLights::new(vec![Light::Spot(crate::fit::Spot::vertical(
            crate::fit::Hemisphere::Down,
            100.0,
            0.0,
            30.0,
        ))]);
        // A hard-edged GL cone (n = 0) is best matched by an inner cone close to the outer one.
        match khr_lights(&fitted)[0] {
            KhrLight::Spot {
                inner_rad, outer_rad, ..
            } => {
                assert!(
                    (outer_rad.to_degrees() - 30.0).abs() <= 1.0 + 1e-9,
                    "{}",
                    outer_rad.to_degrees()
                );
                assert!(inner_rad.to_degrees() >= 28.0, "{}", inner_rad.to_degrees());
            }
            _ => panic!("a spot"),
        }
    }
}
