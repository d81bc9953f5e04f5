//! The open extension point: a representation a caller adds, and the
//! registry that holds it beside the built-in ones.
//!
//! A [`Representation`] says how it is spelled (parsing its names, one
//! parameter each), how it is built from a distribution into an
//! [`IntensityField`] (whose `bytes()` is its storage), and which of its
//! instances the trade table lists. [`register`] adds one to the process's
//! registry and returns its [`ExtensionId`]; from then on its names parse as
//! [`Recon::Extension`] wherever a reconstruction is named (`--recon`, a
//! scene's `representation`), `compare` builds and measures it as any other
//! row, and `tradeoff` and `plan` list its default instances after the
//! built-in ones.
//!
//! The built-in representations are not (yet) implementations of this trait:
//! [`Recon`]'s variants name them and [`super::Reconstructions`] builds them.

use std::sync::{Arc, RwLock};

use crate::error::ModelError;
use crate::model::{Distribution, IntensityField};

use super::Recon;

/// A representation a caller adds to the registry ([`register`]).
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

/// The index of a registered representation in the process's registry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ExtensionId(pub(crate) u16);

/// The process's registry of added representations, in the order added.
static EXTENSIONS: RwLock<Vec<Arc<dyn Representation>>> = RwLock::new(Vec::new());

/// The registry, read (a poisoned lock only means a thread panicked while
/// registering: the list itself is whole).
fn read() -> std::sync::RwLockReadGuard<'static, Vec<Arc<dyn Representation>>> {
    EXTENSIONS.read().unwrap_or_else(|e| e.into_inner())
}

/// Add `representation` to the process's registry; its names parse as
/// [`Recon::Extension`] from now on.
///
/// # Errors
/// [`ModelError::Parameter`] when one of its default names is already
/// spelled by a built-in or a registered representation, or past 65,536
/// registrations.
pub fn register(representation: Arc<dyn Representation>) -> Result<ExtensionId, ModelError> {
    let taken = |name: &str| ModelError::Parameter {
        name: "representation",
        value: name.to_string(),
        reason: "this name is already a reconstruction's: a registered representation needs names of its own".into(),
    };
    for param in representation.defaults() {
        let name = representation.name(param);
        if name.parse::<Recon>().is_ok() {
            return Err(taken(&name));
        }
    }
    let mut all = EXTENSIONS.write().unwrap_or_else(|e| e.into_inner());
    let id = u16::try_from(all.len()).map_err(|_| ModelError::Parameter {
        name: "representation",
        value: all.len().to_string(),
        reason: "at most 65,536 representations can be registered".into(),
    })?;
    all.push(representation);
    Ok(ExtensionId(id))
}

/// The registered representation `id` names.
fn get(id: ExtensionId) -> Option<Arc<dyn Representation>> {
    read().get(usize::from(id.0)).cloned()
}

/// The [`Recon`] a registered representation reads `name` as, if any.
pub(crate) fn parse(name: &str) -> Option<Recon> {
    read().iter().enumerate().find_map(|(i, rep)| {
        let param = rep.parse(name)?;
        Some(Recon::Extension {
            id: ExtensionId(u16::try_from(i).ok()?),
            param,
        })
    })
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

/// Every registered representation's default instances, in registration order.
pub fn default_instances() -> Vec<Recon> {
    read()
        .iter()
        .enumerate()
        .filter_map(|(i, rep)| Some((ExtensionId(u16::try_from(i).ok()?), rep)))
        .flat_map(|(id, rep)| {
            rep.defaults()
                .into_iter()
                .map(move |param| Recon::Extension { id, param })
        })
        .collect()
}
