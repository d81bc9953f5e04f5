//! A rendered texture as a renderer stores and reads it: [`TextureSpec`],
//! written `FILTER@xK/LOOKUP[+f16|+u16|+u8|+bc6h][+reduced]`.

use std::fmt;
use std::str::FromStr;

use super::filter::Filter;
use super::lookup::{Lookup, Precision};
use crate::error::ModelError;

/// A rendered texture as a renderer stores and reads it. Written
/// `FILTER@xK/LOOKUP[+f16|+u16|+u8|+bc6h][+reduced]`, e.g. `catmull-rom@x5/bilinear+f16`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextureSpec {
    /// The filter the texture is rendered with.
    pub filter: Filter,
    /// Oversampling factor of the render (1–32).
    pub factor: u32,
    /// How it is read back.
    pub lookup: Lookup,
    /// Storage precision.
    pub precision: Precision,
    /// Only the C sector the data's symmetry needs is stored.
    pub reduced: bool,
}

impl fmt::Display for TextureSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}@x{}/{}{}",
            self.filter,
            self.factor,
            self.lookup,
            self.precision.suffix()
        )?;
        if self.reduced {
            f.write_str("+reduced")?;
        }
        Ok(())
    }
}

impl FromStr for TextureSpec {
    type Err = ModelError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = |why: &str| ModelError::Parameter {
            name: "texture",
            value: s.to_string(),
            reason: format!(
                "{why}; expected FILTER@xK/LOOKUP[+f16|+u16|+u8|+bc6h][+reduced], e.g. catmull-rom@x5/bilinear"
            ),
        };
        let (filter, rest) = s.trim().split_once('@').ok_or_else(|| bad("no @"))?;
        let mut parts = rest.split('+');
        let (factor, lookup) = parts
            .next()
            .and_then(|p| p.split_once('/'))
            .ok_or_else(|| bad("no /LOOKUP"))?;
        let factor: u32 = factor
            .strip_prefix('x')
            .and_then(|k| k.parse().ok())
            .filter(|k| (1..=32).contains(k))
            .ok_or_else(|| bad("the factor is xK with K from 1 to 32"))?;
        let mut spec = TextureSpec {
            filter: filter.parse().map_err(|_| bad("unknown filter"))?,
            factor,
            lookup: lookup.parse().map_err(|_| bad("unknown lookup"))?,
            precision: Precision::F32,
            reduced: false,
        };
        for p in parts {
            match p {
                "f16" => spec.precision = Precision::F16,
                "u16" => spec.precision = Precision::U16,
                "u8" => spec.precision = Precision::U8,
                "bc6h" if super::bc6h::available() => spec.precision = Precision::Bc6h,
                "bc6h" => return Err(bad("+bc6h needs photosolid built with the `bc6h` feature")),
                "reduced" => spec.reduced = true,
                _ => return Err(bad("unknown option")),
            }
        }
        Ok(spec)
    }
}
