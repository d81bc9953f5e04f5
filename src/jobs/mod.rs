//! Jobs: what each command computes, built here from loaded documents and the
//! command's options, so the CLI and the Python package only parse and print.
//!
//! A job decides what a caller used to decide itself: the reference and the
//! truth a synth file records, the Type A/B readings a withheld reference
//! withholds, the lamp flux of `--units klm`, the file names and the warnings
//! of the files. Each job takes one settings value whose fields are the
//! command's options, spelled as the CLI spells them (percents as
//! [`PctOfPeak`](crate::numfmt::PctOfPeak)), and returns the document the
//! command prints with `--json`.

mod compare;
mod info;
mod road;
mod scene;
mod solid;
mod validate;
mod write;

pub use compare::{compare, engines, tradeoff, CompareSettings, EnginesSettings, TradeoffSettings};
pub use info::{info, InfoSettings};
pub use road::{parse_class, parse_grid, parse_key, parse_range, road, Range, RoadSettings};
pub use scene::{plan, scene, JobError, PlanAnswer, PlanSettings};
pub use solid::{mesh, BuiltSolid, MeshSettings};
pub use validate::{validate, ValidateLine, Validated};
pub use write::{convert, export, synth, ConvertSettings, ExportSettings, SynthSettings, Written};

use std::path::Path;

use crate::error::{Error, Result};
use crate::formats::{Document, Handedness, ReadOptions};

/// A loaded document and what a job reports of it: the name outputs give it
/// (the path as the user wrote it) and the rotation sense it was read with.
#[derive(Clone, Copy, Debug)]
pub struct Named<'a> {
    /// The name in outputs (`file`, `vs`, warnings): the path as given.
    pub name: &'a str,
    /// The document.
    pub document: &'a Document,
    /// The rotation sense of Type A/B horizontal angles it was read with
    /// (a withheld reference withholds its readings in that sense).
    pub handedness: Handedness,
}

/// A document loaded by a job's caller, owning what [`Named`] borrows.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The path as given.
    pub name: String,
    /// The document read from it.
    pub document: Document,
    /// The reader options it was read with.
    pub read: ReadOptions,
}

impl Loaded {
    /// Load `path` (any format, `FILE.gldf#ID` included) with `read`.
    pub fn load(path: &Path, read: &ReadOptions) -> Result<Loaded> {
        Ok(Loaded {
            name: path.display().to_string(),
            document: crate::formats::load_document_with(path, read)?,
            read: read.clone(),
        })
    }

    /// The borrowed form jobs take.
    pub fn named(&self) -> Named<'_> {
        Named {
            name: &self.name,
            document: &self.document,
            handedness: self.read.handedness,
        }
    }
}

impl Named<'_> {
    /// The Type A/B readings and the sense they were read in, for a withheld
    /// reference that withholds the readings themselves (None for Type C).
    pub fn source(&self) -> Option<crate::compare::SourceMeasurements> {
        self.document
            .luminaire
            .source_grid()
            .map(|grid| crate::compare::SourceMeasurements {
                grid: grid.clone(),
                handedness: self.handedness,
            })
    }

    /// The warnings of this file and of `other` (its messages prefixed with its name).
    pub fn warnings_with(&self, other: Option<Named<'_>>) -> Vec<crate::error::Warning> {
        crate::compare::file_warnings(&self.document.luminaire, other.map(|o| (o.name, &o.document.luminaire)))
    }
}

/// An [`Error::Option`] naming `option`.
pub(crate) fn option_error(option: &str, message: impl Into<String>) -> Error {
    Error::Option {
        option: option.to_string(),
        message: message.into(),
    }
}

/// A progress callback that reports nothing.
pub fn no_progress(_: usize, _: usize, _: &str) {}
