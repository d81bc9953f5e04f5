//! `measured`: the measured solid ([`Recon::Measured`]).

use super::{Builtin, Job};
use crate::error::ModelError;
use crate::registry::Recon;

/// The measured solid: `compare`'s first row and the trade table's.
pub(crate) struct Measured;

impl Builtin for Measured {
    fn spelling(&self) -> String {
        "measured".into()
    }

    fn parse(&self, name: &str) -> Option<Result<Recon, ModelError>> {
        (name == "measured").then_some(Ok(Recon::Measured))
    }

    fn candidates(&self, job: &Job<'_>) -> Vec<Recon> {
        match job {
            Job::Compare | Job::Tradeoff { .. } | Job::TradeRows { .. } => vec![Recon::Measured],
            Job::Plan { .. } | Job::Compact { .. } => Vec::new(),
        }
    }
}
