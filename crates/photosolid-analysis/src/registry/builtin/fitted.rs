//! `fitted-gl`: the fitted OpenGL lights ([`Recon::FittedGl`]).

use super::{Builtin, Job};
use crate::error::ModelError;
use crate::fit::RECONSTRUCTION_NAME;
use crate::registry::Recon;

/// At most two fitted OpenGL lights.
pub(crate) struct FittedGl;

impl Builtin for FittedGl {
    fn spelling(&self) -> String {
        RECONSTRUCTION_NAME.into()
    }

    fn parse(&self, name: &str) -> Option<Result<Recon, ModelError>> {
        (name == RECONSTRUCTION_NAME).then_some(Ok(Recon::FittedGl))
    }

    fn candidates(&self, job: &Job<'_>) -> Vec<Recon> {
        match job {
            Job::Compare | Job::Tradeoff { .. } | Job::TradeRows { .. } | Job::Plan { .. } => vec![Recon::FittedGl],
            // The hold-out pass of `batch` fits on the whole file (its `fitted_gl` column).
            Job::Compact { .. } => Vec::new(),
        }
    }
}
