//! A filter on the measured grid re-stored first: cropped to the directions
//! a scene sees ([`Recon::Cropped`], `FILTER+gamma:A-B[+c:A-B]`) or with a
//! smaller symmetry the data has ([`Recon::Symmetric`], `FILTER+isym:N`).

use super::{Builtin, Job};
use crate::error::ModelError;
use crate::model::Symmetry;
use crate::reconstruct::Filter;
use crate::registry::Recon;

/// The cropped and re-stored grids; `plan` offers them where they apply.
pub(crate) struct Regridded;

/// Whether `name` is of a re-gridded representation's shape.
pub(crate) fn claims(name: &str) -> bool {
    name.contains("+gamma:") || name.contains("+isym:")
}

impl Builtin for Regridded {
    fn spelling(&self) -> String {
        "FILTER+gamma:A-B[+c:A-B], FILTER+isym:N".into()
    }

    fn parse(&self, name: &str) -> Option<Result<Recon, ModelError>> {
        claims(name).then(|| parse_regridded(name))
    }

    fn candidates(&self, job: &Job<'_>) -> Vec<Recon> {
        let Job::Plan { dist, visible } = *job else {
            return Vec::new();
        };
        let mut out = Vec::new();
        if let Some((gamma_from, gamma_to, c)) = visible {
            out.push(Recon::Cropped {
                filter: Filter::CatmullRom,
                gamma_from,
                gamma_to,
                c,
            });
        }
        // A symmetry the data has but does not declare, when it stores fewer planes.
        let found = dist.detect_symmetry(1e-9 * dist.max_cd());
        if found != dist.symmetry() && dist.with_symmetry(found).is_ok_and(|s| s.n_c() < dist.n_c()) {
            out.push(Recon::Symmetric {
                filter: Filter::CatmullRom,
                symmetry: found,
            });
        }
        out
    }
}

/// `FILTER+gamma:A-B[+c:A-B]` or `FILTER+isym:N`.
///
/// # Errors
/// [`ModelError::Parameter`] for any other spelling.
fn parse_regridded(s: &str) -> Result<Recon, ModelError> {
    let bad = || ModelError::Parameter {
        name: "recon",
        value: s.to_string(),
        reason: "expected FILTER+gamma:FROM-TO[+c:FROM-TO] or FILTER+isym:N (N 0-4)".into(),
    };
    // `A-B` with finite A, B (a leading minus sign belongs to A).
    let range = |t: &str| -> Option<(f64, f64)> {
        let at = t.char_indices().skip(1).find(|&(_, ch)| ch == '-')?.0;
        let (a, b) = (t[..at].parse::<f64>().ok()?, t[at + 1..].parse::<f64>().ok()?);
        (a.is_finite() && b.is_finite()).then_some((a, b))
    };
    let mut parts = s.split('+');
    let filter: Filter = parts.next().ok_or_else(bad)?.parse()?;
    let (mut gamma, mut c, mut isym) = (None, None, None);
    for part in parts {
        match part.split_once(':') {
            Some(("gamma", v)) if gamma.is_none() => gamma = Some(range(v).ok_or_else(bad)?),
            Some(("c", v)) if c.is_none() => c = Some(range(v).ok_or_else(bad)?),
            Some(("isym", v)) if isym.is_none() => {
                isym = Some(v.parse::<i64>().ok().and_then(Symmetry::from_isym).ok_or_else(bad)?)
            }
            _ => return Err(bad()),
        }
    }
    match (gamma, c, isym) {
        (Some((gamma_from, gamma_to)), c, None) => Ok(Recon::Cropped {
            filter,
            gamma_from,
            gamma_to,
            c,
        }),
        (None, None, Some(symmetry)) => Ok(Recon::Symmetric { filter, symmetry }),
        _ => Err(bad()),
    }
}
