//! Output of a fit: a serde report (`photosolid fit --json`), a text table,
//! and snippets a renderer can paste (GLSL and `glLight` parameters).
//!
//! # Frames
//! Every direction is given twice: `direction_luminaire` in the luminaire
//! frame of [`crate::model`] (z up, C0 = +x, C90 = +y) and `direction_gl` in
//! the y-up OpenGL frame of Zotti et al. 2005 (`(x, z, −y)`: C0 = +x, zenith = +y,
//! C90 = −z). `GL_SPOT_DIRECTION` is transformed by the modelview matrix
//! current at `glLight` time, so set it with the luminaire's model matrix
//! loaded (OpenGL 1.x §2.14.1).

use serde::Serialize;

use super::model::{FittedLights, Hemisphere, Light};
use super::{ErrorMetric, Fit};

/// One light in OpenGL units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GlLight {
    /// `spot` or `point`.
    pub kind: &'static str,
    /// The spot's hemisphere (`down`/`up`); `null` for a point light.
    pub hemisphere: Option<Hemisphere>,
    /// Diffuse scale, cd (the spot's on-axis intensity; the point light's intensity).
    pub weight_cd: f64,
    /// Diffuse scale relative to the measured I_max.
    pub weight_relative: f64,
    /// `GL_SPOT_EXPONENT` in [0, 128] (0 for a point light).
    pub exponent: f64,
    /// `GL_SPOT_CUTOFF`, degrees: [0, 90] for a spot, 180 for a point light.
    pub cutoff_deg: f64,
    /// Tilt of the spot axis from its hemisphere's pole, degrees.
    pub tilt_deg: Option<f64>,
    /// C angle of the spot axis, degrees.
    pub azimuth_deg: Option<f64>,
    /// Unit spot axis, luminaire frame (z up).
    pub direction_luminaire: Option<[f64; 3]>,
    /// Unit spot axis, y-up OpenGL frame (`GL_SPOT_DIRECTION`).
    pub direction_gl: Option<[f64; 3]>,
    /// (`GL_CONSTANT_ATTENUATION`, `GL_LINEAR_ATTENUATION`, `GL_QUADRATIC_ATTENUATION`):
    /// always (0, 0, 1), the inverse-square law of far-field photometry.
    pub attenuation: [f64; 3],
}

impl GlLight {
    fn of(l: &Light, i_max: f64) -> Self {
        let rel = |w: f64| if i_max > 0.0 { w / i_max } else { 0.0 };
        match l {
            Light::Spot(s) => Self {
                kind: "spot",
                hemisphere: Some(s.hemisphere),
                weight_cd: s.weight_cd,
                weight_relative: rel(s.weight_cd),
                exponent: s.exponent,
                cutoff_deg: s.cutoff_deg,
                tilt_deg: Some(s.tilt_deg),
                azimuth_deg: Some(s.azimuth_deg),
                direction_luminaire: Some(s.axis().to_array()),
                direction_gl: Some(s.axis_gl().to_array()),
                attenuation: [0.0, 0.0, 1.0],
            },
            Light::Point { weight_cd } => Self {
                kind: "point",
                hemisphere: None,
                weight_cd: *weight_cd,
                weight_relative: rel(*weight_cd),
                exponent: 0.0,
                cutoff_deg: 180.0,
                tilt_deg: None,
                azimuth_deg: None,
                direction_luminaire: None,
                direction_gl: None,
                attenuation: [0.0, 0.0, 1.0],
            },
        }
    }
}

/// One row of the table of combinations.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrialRow {
    /// Combination name, e.g. `point+spot-down`.
    pub combination: &'static str,
    /// Number of lights.
    pub lights: usize,
    /// Whether this is the chosen combination.
    pub chosen: bool,
    /// The error minimised; `null` when skipped.
    pub error: Option<f64>,
    /// Largest |approximation − measurement| / I_max.
    pub max_error: Option<f64>,
    /// Model flux / data flux on the data's grid.
    pub flux_ratio: Option<f64>,
    /// Objective evaluations spent.
    pub evaluations: usize,
    /// Why it was skipped.
    pub skipped: Option<String>,
    /// The fitted lights.
    pub parameters: Vec<GlLight>,
}

/// The `photosolid fit --json` document.
///
/// Keys: `reconstruction` (`"fitted-gl"`), `metric` (`relative` |
/// `solid-angle`), `guard` (C, a fraction of I_max), `guard_pct` (the same in percent), `tolerance`, `i_max_cd`,
/// `directions`, `axis_vertical`, `chosen` (combination name), `error`,
/// `lights` ([`GlLight`]s of the chosen combination), `trials` ([`TrialRow`]s,
/// every combination), `frames` (a note), `glsl` (a paste-able function),
/// `gl_fixed_function` (one object of `glLight` parameters per light).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FitReport {
    /// Always `fitted-gl`.
    pub reconstruction: &'static str,
    /// The error minimised.
    pub metric: ErrorMetric,
    /// Guard constant C, relative to I_max.
    pub guard: f64,
    /// The same in percent of I_max (`--guard 2%` is 2).
    pub guard_pct: f64,
    /// Model-selection tolerance.
    pub tolerance: f64,
    /// Largest measured intensity, cd.
    pub i_max_cd: f64,
    /// Number of measured directions in the error.
    pub directions: usize,
    /// Whether the spot axes were held vertical (rotational data).
    pub axis_vertical: bool,
    /// The chosen combination.
    pub chosen: &'static str,
    /// Its error.
    pub error: f64,
    /// Its lights.
    pub lights: Vec<GlLight>,
    /// Every combination tried.
    pub trials: Vec<TrialRow>,
    /// Which frames the directions are in.
    pub frames: &'static str,
    /// A GLSL function `float luminaireIntensity(vec3 L)` (cd; L in the y-up frame).
    pub glsl: String,
    /// `glLight` parameters per light (y-up frame).
    pub gl_fixed_function: Vec<GlFixed>,
}

/// `glLight` parameters of one light, named as OpenGL names them.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[allow(non_snake_case)]
pub struct GlFixed {
    /// (0, 0, 0, 1): positional, at the luminaire's origin.
    pub GL_POSITION: [f64; 4],
    /// Spot axis, y-up frame ((0, −1, 0) for a point light, unused).
    pub GL_SPOT_DIRECTION: [f64; 3],
    /// [0, 128].
    pub GL_SPOT_EXPONENT: f64,
    /// Degrees, [0, 90] or 180 (point light).
    pub GL_SPOT_CUTOFF: f64,
    /// 0.
    pub GL_CONSTANT_ATTENUATION: f64,
    /// 0.
    pub GL_LINEAR_ATTENUATION: f64,
    /// 1.
    pub GL_QUADRATIC_ATTENUATION: f64,
    /// Scale of `GL_DIFFUSE` (and `GL_SPECULAR`), cd.
    pub diffuse_scale_cd: f64,
}

const FRAMES: &str = "direction_luminaire: z up, C0 = +x, C90 = +y, nadir = -z (photosolid's luminaire frame); \
direction_gl and the snippets: y up (OpenGL / Zotti et al.), x = C0, y = zenith, z = -C90";

fn f(x: f64) -> String {
    format!("{x:.6}")
}

/// GLSL source of `float luminaireIntensity(vec3 L)`: intensity in cd for the
/// unit direction `L` from the luminaire (y-up frame).
pub fn glsl(model: &FittedLights) -> String {
    let mut terms = Vec::new();
    for l in &model.lights {
        match l {
            Light::Spot(s) => {
                let a = s.axis_gl();
                let cc = super::model::cos_cutoff(s.cutoff_deg);
                terms.push(format!(
                    "psSpot(L, vec3({}, {}, {}), {}, {}, {})",
                    f(a[0]),
                    f(a[1]),
                    f(a[2]),
                    f(s.weight_cd),
                    f(s.exponent),
                    f(cc)
                ));
            }
            Light::Point { weight_cd } => terms.push(f(*weight_cd)),
        }
    }
    if terms.is_empty() {
        terms.push("0.0".into());
    }
    format!(
        "// photosolid fitted-gl. L: unit vector from the luminaire, OpenGL y-up frame (x = C0, y = up, z = -C90).\n\
         // Returns cd; illuminance at distance d (m) is I / d^2 lux (quadratic attenuation only).\n\
         float psSpot(vec3 L, vec3 axis, float w, float p, float cosCut) {{\n\
         \x20   float t = dot(L, axis);\n\
         \x20   if (t < cosCut) return 0.0;\n\
         \x20   return p == 0.0 ? w : w * pow(max(t, 0.0), p);\n\
         }}\n\
         float luminaireIntensity(vec3 L) {{\n\
         \x20   return {};\n\
         }}\n",
        terms.join("\n         + ")
    )
}

/// `glLight` parameters of every light of `model`.
pub fn gl_fixed(model: &FittedLights) -> Vec<GlFixed> {
    model
        .lights
        .iter()
        .map(|l| {
            let (dir, p, c) = match l {
                Light::Spot(s) => (s.axis_gl().to_array(), s.exponent, s.cutoff_deg),
                Light::Point { .. } => ([0.0, -1.0, 0.0], 0.0, 180.0),
            };
            GlFixed {
                GL_POSITION: [0.0, 0.0, 0.0, 1.0],
                GL_SPOT_DIRECTION: dir,
                GL_SPOT_EXPONENT: p,
                GL_SPOT_CUTOFF: c,
                GL_CONSTANT_ATTENUATION: 0.0,
                GL_LINEAR_ATTENUATION: 0.0,
                GL_QUADRATIC_ATTENUATION: 1.0,
                diffuse_scale_cd: l.weight_cd(),
            }
        })
        .collect()
}

impl FitReport {
    /// The report of a fit.
    pub fn of(fit: &Fit) -> Self {
        let i_max = fit.i_max_cd;
        let model = fit.model();
        let trials = fit
            .trials
            .iter()
            .enumerate()
            .map(|(i, t)| TrialRow {
                combination: t.combination.name(),
                lights: t.lights,
                chosen: i == fit.chosen,
                error: t.error,
                max_error: t.max_error,
                flux_ratio: t.flux_ratio,
                evaluations: t.evaluations,
                skipped: t.skipped.clone(),
                parameters: t
                    .model
                    .as_ref()
                    .map(|m| m.lights.iter().map(|l| GlLight::of(l, i_max)).collect())
                    .unwrap_or_default(),
            })
            .collect();
        Self {
            reconstruction: super::RECONSTRUCTION_NAME,
            metric: fit.options.metric,
            guard: fit.options.guard,
            guard_pct: crate::error::percent_of(fit.options.guard),
            tolerance: fit.options.tolerance,
            i_max_cd: i_max,
            directions: fit.directions,
            axis_vertical: fit.axis_vertical,
            chosen: fit.chosen().combination.name(),
            error: fit.error(),
            lights: model.lights.iter().map(|l| GlLight::of(l, i_max)).collect(),
            trials,
            frames: FRAMES,
            glsl: glsl(model),
            gl_fixed_function: gl_fixed(model),
        }
    }

    /// Human-readable report.
    pub fn to_text(&self) -> String {
        use std::fmt::Write;
        let mut o = String::new();
        let n = self.lights.len();
        let _ = writeln!(
            o,
            "fitted-gl: {} ({} light{}), error {:.5} ({}, C = {} % of I_max), I_max {:.2} cd, {} directions{}",
            self.chosen,
            n,
            if n == 1 { "" } else { "s" },
            self.error,
            self.metric.name(),
            self.guard_pct,
            self.i_max_cd,
            self.directions,
            if self.axis_vertical {
                ", rotational data: axes vertical"
            } else {
                ""
            }
        );
        for (i, l) in self.lights.iter().enumerate() {
            let _ = writeln!(o, "  light {}: {}", i + 1, describe(l));
        }
        let _ = writeln!(
            o,
            "combinations (chosen: fewest lights within {} of the best error):",
            self.tolerance
        );
        let _ = writeln!(
            o,
            "    {:<18} {:>6} {:>9} {:>9} {:>10} {:>6}",
            "combination", "lights", "error", "max err", "flux ratio", "evals"
        );
        for t in &self.trials {
            let mark = if t.chosen { "*" } else { " " };
            match (&t.skipped, t.error) {
                (Some(why), _) => {
                    let _ = writeln!(o, "  {mark} {:<18} {:>6}  skipped: {why}", t.combination, t.lights);
                }
                (None, Some(e)) => {
                    let _ = writeln!(
                        o,
                        "  {mark} {:<18} {:>6} {:>9.5} {:>9.5} {:>10} {:>6}",
                        t.combination,
                        t.lights,
                        e,
                        t.max_error.unwrap_or(f64::NAN),
                        t.flux_ratio.map_or("-".to_string(), |r| format!("{r:.4}")),
                        t.evaluations
                    );
                    for l in &t.parameters {
                        let _ = writeln!(o, "        {}", describe(l));
                    }
                }
                _ => {}
            }
        }
        let _ = writeln!(o, "frames: {}", self.frames);
        let _ = write!(o, "GLSL:\n{}", self.glsl);
        o
    }
}

fn describe(l: &GlLight) -> String {
    match (l.hemisphere, l.direction_luminaire, l.direction_gl) {
        (Some(h), Some(d), Some(g)) => format!(
            "spot {:<4} w {:.4} cd ({:.4} I_max), exponent {:.3}, cut-off {:.2} deg, tilt {:.2} deg, azimuth {:.2} deg, \
             axis z-up ({:.5}, {:.5}, {:.5}), GL y-up ({:.5}, {:.5}, {:.5})",
            h.name(),
            l.weight_cd,
            l.weight_relative,
            l.exponent,
            l.cutoff_deg,
            l.tilt_deg.unwrap_or(0.0),
            l.azimuth_deg.unwrap_or(0.0),
            d[0],
            d[1],
            d[2],
            g[0],
            g[1],
            g[2]
        ),
        _ => format!(
            "point     w {:.4} cd ({:.4} I_max), GL cut-off 180",
            l.weight_cd, l.weight_relative
        ),
    }
}
