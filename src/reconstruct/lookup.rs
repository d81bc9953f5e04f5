//! Lookups into a stored (rendered) texture, as a renderer's sampler does them.
//!
//! Wallner's pipeline renders the texture once with a good filter at a
//! factor k, then looks it up in the shader with the hardware's filter. The
//! lookup's error depends on k; these are those lookups, on the texel grid
//! of [`TexelMapping`](super::TexelMapping): row i centred at
//! γ = (i + ½)·180/H, column j at C = (j + ½)·360/W. C is periodic; rows are
//! clamped at the first and last texel (held towards the poles, as
//! `CLAMP_TO_EDGE` does). Values are clamped at 0 (Catmull–Rom overshoot).

use std::fmt;
use std::str::FromStr;

use serde::Serialize;

use super::filter::Filter;
use super::texture::Rendered;
use crate::error::ModelError;
use crate::model::{wrap360, IntensityField};

/// How a stored texture is read back.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Lookup {
    /// The texel the direction falls in (`GL_NEAREST`).
    Nearest,
    /// Bilinear between the four nearest texel centres (`GL_LINEAR`).
    Bilinear,
    /// Separable Catmull–Rom on the 4 x 4 nearest texel centres (a bicubic shader lookup).
    CatmullRom,
}

impl Lookup {
    /// Every lookup, cheapest first.
    pub const ALL: [Lookup; 3] = [Lookup::Nearest, Lookup::Bilinear, Lookup::CatmullRom];
    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Lookup::Nearest => "nearest",
            Lookup::Bilinear => "bilinear",
            Lookup::CatmullRom => "catmull-rom",
        }
    }
}

impl fmt::Display for Lookup {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Lookup {
    type Err = ModelError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Lookup::ALL
            .into_iter()
            .find(|l| l.name() == s.trim())
            .ok_or_else(|| ModelError::Parameter {
                name: "lookup",
                value: s.to_string(),
                reason: "expected nearest, bilinear or catmull-rom".into(),
            })
    }
}

impl Rendered {
    /// The stored value (dimensionless, I / I_max) at texel (row, column),
    /// rows clamped, columns periodic.
    #[inline]
    fn texel(&self, i: isize, j: isize) -> f64 {
        let (h, w) = (self.mapping.height as isize, self.mapping.width as isize);
        let i = i.clamp(0, h - 1) as usize;
        let j = j.rem_euclid(w) as usize;
        self.data[i * w as usize + j] as f64
    }

    /// Intensity (cd) at (C, γ) degrees read with `lookup`; 0 for an empty
    /// texture or non-finite angles.
    pub fn lookup_cd(&self, lookup: Lookup, c_deg: f64, gamma_deg: f64) -> f64 {
        let (h, w) = (self.mapping.height, self.mapping.width);
        if h == 0 || w == 0 || !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        let y = gamma_deg.clamp(0.0, 180.0) / 180.0 * h as f64 - 0.5;
        let x = wrap360(c_deg) / 360.0 * w as f64 - 0.5;
        let v = match lookup {
            Lookup::Nearest => self.texel((y + 0.5).floor() as isize, (x + 0.5).floor() as isize),
            Lookup::Bilinear => {
                let (i0, j0) = (y.floor(), x.floor());
                let (ty, tx) = (y - i0, x - j0);
                let (i0, j0) = (i0 as isize, j0 as isize);
                let row = |i| self.texel(i, j0) * (1.0 - tx) + self.texel(i, j0 + 1) * tx;
                row(i0) * (1.0 - ty) + row(i0 + 1) * ty
            }
            Lookup::CatmullRom => {
                let (i0, j0) = (y.floor(), x.floor());
                let wy = uniform_catmull_rom(y - i0);
                let wx = uniform_catmull_rom(x - j0);
                let (i0, j0) = (i0 as isize, j0 as isize);
                let mut acc = 0.0;
                for (a, wa) in wy.iter().enumerate() {
                    let mut row = 0.0;
                    for (b, wb) in wx.iter().enumerate() {
                        row += wb * self.texel(i0 - 1 + a as isize, j0 - 1 + b as isize);
                    }
                    acc += wa * row;
                }
                acc
            }
        };
        (v * self.i_max_cd).max(0.0)
    }

    /// Bytes of the stored texels (f32).
    pub fn texel_bytes(&self) -> usize {
        self.data.len() * std::mem::size_of::<f32>()
    }
}

/// Catmull–Rom weights of the four texels around fraction `s` on a uniform grid.
#[inline]
fn uniform_catmull_rom(s: f64) -> [f64; 4] {
    Filter::CatmullRom
        .linear_weights([-1.0, 0.0, 1.0, 2.0], s)
        .unwrap_or([0.0, 1.0 - s, s, 0.0])
}

/// A rendered texture is an intensity field read bilinearly (the default
/// hardware lookup); [`TextureField`] chooses another lookup.
impl IntensityField for Rendered {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        self.lookup_cd(Lookup::Bilinear, c_deg, gamma_deg)
    }
    fn name(&self) -> String {
        format!("texture {} x{} / bilinear", self.filter, self.factor)
    }
    fn bytes(&self) -> usize {
        self.texel_bytes()
    }
}

/// A stored texture with the lookup a renderer reads it with.
#[derive(Debug, Clone, PartialEq)]
pub struct TextureField {
    /// The stored texels.
    pub rendered: Rendered,
    /// How they are read.
    pub lookup: Lookup,
}

impl IntensityField for TextureField {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        self.rendered.lookup_cd(self.lookup, c_deg, gamma_deg)
    }
    fn name(&self) -> String {
        format!(
            "texture {} x{} / {}",
            self.rendered.filter, self.rendered.factor, self.lookup
        )
    }
    fn bytes(&self) -> usize {
        self.rendered.texel_bytes()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reconstruct::{render, LightTexture};
    use crate::synth::{GridSpec, Synth};

    #[test]
    fn lookups_return_texel_values_at_texel_centres() {
        let lum = Synth::CosinePower { p: 5.0 }
            .build(&GridSpec::uniform(15.0, 5.0).unwrap(), 100.0)
            .unwrap();
        let tex = LightTexture::new(&lum.distribution).unwrap();
        let r = render(&tex, Filter::CatmullRom, 2).unwrap();
        let (h, w) = (r.mapping.height, r.mapping.width);
        for i in [0, h / 3, h - 1] {
            for j in [0, w / 2, w - 1] {
                let (c, g) = (r.mapping.c_of_column(j), r.mapping.gamma_of_row(i));
                let want = (r.data[i * w + j] as f64 * r.i_max_cd).max(0.0);
                for l in Lookup::ALL {
                    let got = r.lookup_cd(l, c, g);
                    assert!(
                        (got - want).abs() <= 1e-9 * r.i_max_cd,
                        "{l} at ({c}, {g}): {got} vs {want}"
                    );
                }
            }
        }
        assert_eq!(r.lookup_cd(Lookup::Bilinear, f64::NAN, 3.0), 0.0);
        assert_eq!("catmull-rom".parse::<Lookup>().unwrap(), Lookup::CatmullRom);
        assert!("cubic".parse::<Lookup>().is_err());
    }
}
