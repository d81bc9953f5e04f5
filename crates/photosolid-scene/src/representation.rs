//! How a scene builds the representation of each luminaire: the one
//! registry's [`Recon`] names it (the spelling of `compare --recon` and the
//! trade table) and [`Models`] builds it with [`Reconstructions`], answering
//! [`Dark`] for an all-zero distribution. The candidates of a plan
//! ([`super::plan`]) and the model of every luminaire the illuminance is
//! computed with ([`super::illuminance`]) are built here.

use super::{Dark, SceneLuminaire};
use crate::error::ModelError;
use crate::fit::{fit, FitOptions};
use crate::model::IntensityField;
use crate::reconstruct::{Lookup, Precision, TextureSpec};
use crate::registry::{Recon, Reconstructions};

/// The reference representation of a scene: Catmull-Rom on the native grid.
pub const REFERENCE: Recon = Recon::Filter(crate::reconstruct::Filter::CatmullRom);

/// Read a scene file's `representation` value: a [`Recon`] name, or the
/// spelling scene files used before (`texture FILTER xK / LOOKUP [+f16]
/// [+reduced]`, `fitted`), which is read with a deprecation warning
/// (the second value) naming the current spelling.
///
/// # Errors
/// [`ModelError::Parameter`] when it is neither.
pub fn parse_representation(text: &str) -> Result<(Recon, Option<String>), ModelError> {
    let t = text.trim();
    let legacy = if let Some(rest) = t.strip_prefix("texture ") {
        Some(Recon::Texture(parse_legacy_texture(text, rest)?))
    } else if t == "fitted" {
        Some(Recon::FittedGl)
    } else {
        None
    };
    match legacy {
        Some(r) => Ok((
            r,
            Some(format!(
                "representation = {t:?} is the old spelling (deprecated): write {:?}",
                r.to_string()
            )),
        )),
        None => t.parse::<Recon>().map(|r| (r, None)),
    }
}

/// `FILTER xK / LOOKUP [+f16] [+reduced]` (after `texture `).
fn parse_legacy_texture(text: &str, rest: &str) -> Result<TextureSpec, ModelError> {
    let bad = || ModelError::Parameter {
        name: "representation",
        value: text.to_string(),
        reason: "expected `texture FILTER xFACTOR / LOOKUP` (old spelling) or FILTER@xFACTOR/LOOKUP".into(),
    };
    let (left, lookup) = rest.split_once('/').ok_or_else(bad)?;
    let (filter, factor) = left.trim().rsplit_once(' ').ok_or_else(bad)?;
    let factor: u32 = factor
        .trim()
        .strip_prefix('x')
        .and_then(|x| x.parse().ok())
        .ok_or_else(bad)?;
    let mut words = lookup.split_whitespace();
    let mut spec = TextureSpec {
        filter: filter.parse()?,
        factor,
        lookup: words.next().ok_or_else(bad)?.parse::<Lookup>()?,
        precision: Precision::F32,
        reduced: false,
    };
    for w in words {
        match w {
            "+f16" => spec.precision = Precision::F16,
            "+reduced" => spec.reduced = true,
            _ => return Err(bad()),
        }
    }
    Ok(spec)
}

/// What the representations of one luminaire are built from: its
/// [`Reconstructions`] (`None` for an all-zero distribution).
pub struct Models {
    recons: Option<Reconstructions>,
}

impl Models {
    /// Prepare the representations `wanted` of `lum` (the fit only when
    /// [`Recon::FittedGl`] is among them; a failed fit makes only that
    /// representation unavailable).
    ///
    /// # Errors
    /// [`ModelError`] when the light texture cannot be built (other than all-zero).
    pub fn new(lum: &SceneLuminaire, wanted: &[Recon]) -> Result<Self, ModelError> {
        let dist = lum.luminaire.distribution();
        let others: Vec<Recon> = wanted.iter().copied().filter(|r| *r != Recon::FittedGl).collect();
        let mut recons = match Reconstructions::new(dist.clone(), &others) {
            Ok(r) => r,
            Err(ModelError::AllZero(_)) => return Ok(Self { recons: None }),
            Err(e) => return Err(e),
        };
        if wanted.contains(&Recon::FittedGl) {
            // A failed fit leaves `fitted` empty: `field` reports why.
            recons.fitted = fit(dist, &FitOptions::default()).ok().map(|f| f.model().prepare());
        }
        Ok(Self { recons: Some(recons) })
    }

    /// Representation `r` as an intensity field (cd); every representation
    /// of an all-zero distribution is [`Dark`].
    ///
    /// # Errors
    /// The fit's error for [`Recon::FittedGl`] when it failed; what
    /// [`Reconstructions::field`] returns.
    pub fn field(&self, r: &Recon) -> Result<Box<dyn IntensityField + '_>, ModelError> {
        let Some(recons) = &self.recons else {
            return Ok(Box::new(Dark));
        };
        if *r == Recon::FittedGl && recons.fitted.is_none() {
            // The fit failed in `new` (deterministic): run it again for its error.
            fit(&recons.dist, &FitOptions::default())?;
        }
        recons.field(*r)
    }
}
