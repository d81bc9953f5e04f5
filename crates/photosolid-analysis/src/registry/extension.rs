//! The open extension point: a representation a caller adds, and the
//! registry value that holds it beside the built-in ones.
//!
//! A [`Representation`] says how it is spelled (parsing its names, one
//! parameter each), how it is built from a distribution into an
//! [`IntensityField`] (whose `bytes()` is its storage), and which of its
//! instances the trade table lists. A [`Registry`] is the value the jobs take
//! (`compare`, `tradeoff`, `plan`, `batch --compact`: their settings' or
//! options' `registry`): the built-in representations and those added to it
//! with [`Registry::register`]. The jobs list the default instances of the
//! representations in their registry after the built-in ones; a registry
//! without a representation lists none of it, so two callers in one process
//! can offer different sets.
//!
//! A registered representation's names parse as [`Recon::Extension`]
//! wherever a reconstruction is named (`--recon`, a scene's
//! `representation`, `Recon::from_str`): a [`Recon`] is a small copyable
//! name, so the definitions it points at are kept for the process
//! (append-only; registering defines).
//!
//! The built-in representations are not (yet) implementations of this trait:
//! [`Recon`]'s variants name them and [`super::Reconstructions`] builds them.

use std::sync::{Arc, RwLock};

use crate::error::ModelError;
use crate::model::{Distribution, IntensityField};

use super::Recon;

/// A representation a caller adds to a [`Registry`].
pub trait Representation: Send + Sync {
    /// The parameter of `name` when it names an instance of this
    /// representation (`"octa:32"` → `Some(32)`), else `None`. A name must
    /// not be one of the built-in ones, and holds no comma (`--recon a,b`).
    fn parse(&self, name: &str) -> Option<u32>;

    /// The name of the instance with parameter `param`; `parse` reads it back.
    fn name(&self, param: u32) -> String;

    /// The instance with parameter `param` built from `dist` (absolute cd, the
    /// comparison's scaling applied): a field that owns what it samples.
    ///
    /// # Errors
    /// A [`ModelError`] when it cannot be built for this distribution.
    fn build(&self, dist: &Distribution, param: u32) -> Result<Box<dyn IntensityField + Send>, ModelError>;

    /// The parameters of the instances `tradeoff` and `plan` list by default.
    fn defaults(&self) -> Vec<u32> {
        Vec::new()
    }
}

/// A representation registered in the process: the index of its definition.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ExtensionId(pub(crate) u16);

/// Every representation registered in the process, in the order registered:
/// what an [`ExtensionId`] points at.
static DEFINED: RwLock<Vec<Arc<dyn Representation>>> = RwLock::new(Vec::new());

/// The definitions, read (a poisoned lock only means a thread panicked while
/// registering: the list itself is whole).
fn read() -> std::sync::RwLockReadGuard<'static, Vec<Arc<dyn Representation>>> {
    DEFINED.read().unwrap_or_else(|e| e.into_inner())
}

/// The representations a job offers: the built-in ones, and those added with
/// [`Registry::register`] (module docs). `Registry::default()` is the
/// built-in ones alone, what the CLI uses.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Registry {
    /// The added representations, in the order added.
    added: Vec<ExtensionId>,
}

impl Registry {
    /// The built-in representations alone.
    pub fn builtin() -> Self {
        Self::default()
    }

    /// Add `representation`: its names parse as [`Recon::Extension`] from now
    /// on, and the jobs given this registry list its default instances.
    ///
    /// Its names are checked against the built-in ones and this registry's:
    /// another registry may hold the same representation (or another that
    /// spells the same names), since each job reads its own registry.
    ///
    /// # Errors
    /// [`ModelError::Parameter`] when one of its default names is already
    /// spelled by a built-in representation or one of this registry's, or
    /// past 65,536 registrations in the process.
    pub fn register(&mut self, representation: Arc<dyn Representation>) -> Result<ExtensionId, ModelError> {
        for param in representation.defaults() {
            let name = representation.name(param);
            if self.parse(&name).is_ok() {
                return Err(ModelError::Parameter {
                    name: "representation",
                    value: name,
                    reason: "this name is already a reconstruction's in this registry: a registered \
                             representation needs names of its own"
                        .into(),
                });
            }
        }
        let id = define(representation)?;
        self.added.push(id);
        Ok(id)
    }

    /// This registry with `representation` added ([`Registry::register`]).
    ///
    /// # Errors
    /// As [`Registry::register`].
    pub fn with(mut self, representation: Arc<dyn Representation>) -> Result<Self, ModelError> {
        self.register(representation)?;
        Ok(self)
    }

    /// `name` read as a built-in reconstruction, else as an instance of a
    /// representation of this registry.
    ///
    /// # Errors
    /// The built-in parser's [`ModelError::Parameter`] when neither spells it.
    pub fn parse(&self, name: &str) -> Result<Recon, ModelError> {
        super::recon::parse_builtin(name).or_else(|e| parse_among(self.added.iter().copied(), name.trim()).ok_or(e))
    }

    /// The default instances of the added representations, in the order added.
    pub fn default_instances(&self) -> Vec<Recon> {
        let defined = read();
        self.added
            .iter()
            .filter_map(|&id| Some((id, defined.get(usize::from(id.0))?.clone())))
            .flat_map(|(id, rep)| {
                rep.defaults()
                    .into_iter()
                    .map(move |param| Recon::Extension { id, param })
            })
            .collect()
    }
}

/// Define `representation` for the process and give its id.
fn define(representation: Arc<dyn Representation>) -> Result<ExtensionId, ModelError> {
    let mut all = DEFINED.write().unwrap_or_else(|e| e.into_inner());
    let id = u16::try_from(all.len()).map_err(|_| ModelError::Parameter {
        name: "representation",
        value: all.len().to_string(),
        reason: "at most 65,536 representations can be registered in a process".into(),
    })?;
    all.push(representation);
    Ok(ExtensionId(id))
}

/// The first of `ids` that reads `name`, as a [`Recon`].
fn parse_among(mut ids: impl Iterator<Item = ExtensionId>, name: &str) -> Option<Recon> {
    let defined = read();
    ids.find_map(|id| {
        let param = defined.get(usize::from(id.0))?.parse(name)?;
        Some(Recon::Extension { id, param })
    })
}

/// The registered representation `id` names.
fn get(id: ExtensionId) -> Option<Arc<dyn Representation>> {
    read().get(usize::from(id.0)).cloned()
}

/// The [`Recon`] the first representation registered in the process that
/// reads `name` reads it as, if any.
pub(crate) fn parse(name: &str) -> Option<Recon> {
    let count = read().len();
    parse_among((0..count).filter_map(|i| u16::try_from(i).ok().map(ExtensionId)), name)
}

/// The name of an extension's instance (`?ID:PARAM` for an id never registered: a bug).
pub(crate) fn name(id: ExtensionId, param: u32) -> String {
    get(id).map_or_else(|| format!("?{}:{param}", id.0), |rep| rep.name(param))
}

/// The instance `id`/`param` built from `dist`.
pub(crate) fn build(
    id: ExtensionId,
    param: u32,
    dist: &Distribution,
) -> Result<Box<dyn IntensityField + Send>, ModelError> {
    let rep = get(id).ok_or_else(|| ModelError::Internal(format!("representation {} was never registered", id.0)))?;
    rep.build(dist, param)
}
