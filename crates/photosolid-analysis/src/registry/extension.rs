//! The open extension point: a representation as a trait, and the registry
//! value that holds the representations a job offers.
//!
//! A [`Representation`] says how it is spelled (parsing its names, one
//! parameter each), how it is built from a distribution into an
//! [`IntensityField`] (whose `bytes()` is its storage), optionally how the
//! GPU evaluates it (its names with `+gpu`), and which of its instances each
//! [`Job`] lists. A [`Registry`] is the value the jobs take (`compare`,
//! `tradeoff`, `plan`, `batch --compact`: their settings' or options'
//! `registry`): the built-in representations ([`super::builtin`], registered
//! there in one place) and those added to it with [`Registry::register`].
//! Each job reads its candidates from [`Registry::candidates`]; a registry
//! without a representation lists none of it, so two callers in one process
//! can offer different sets.
//!
//! A representation on this trait is named [`Recon::Extension`] wherever a
//! reconstruction is named (`--recon`, a scene's `representation`,
//! `Recon::from_str`): a [`Recon`] is a small copyable name, so the
//! definitions it points at are kept for the process (append-only;
//! registering defines).

use std::sync::{Arc, RwLock};

use crate::device::GpuDevice;
use crate::error::ModelError;
use crate::model::{Distribution, IntensityField};

use super::builtin::{self, Job};
use super::recon::{strip_gpu, GPU_SUFFIX};
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

    /// The parameters of the instances the jobs list by default.
    fn defaults(&self) -> Vec<u32> {
        Vec::new()
    }

    /// The parameters of the instances `job` lists: [`Representation::defaults`]
    /// unless a representation lists by job.
    fn candidates(&self, job: &Job<'_>) -> Vec<u32> {
        let _ = job;
        self.defaults()
    }

    /// Whether the GPU evaluates this representation
    /// ([`Representation::build_gpu`]): its names with `+gpu` then parse.
    fn evaluates_on_gpu(&self) -> bool {
        false
    }

    /// The instance with parameter `param` built from `dist` and evaluated by
    /// `device` (the installed GPU device, [`crate::device::device`]).
    ///
    /// # Errors
    /// A [`ModelError`] when it cannot be built or the device fails; by
    /// default, that this representation has no GPU evaluation.
    fn build_gpu(
        &self,
        dist: &Distribution,
        param: u32,
        device: &'static dyn GpuDevice,
    ) -> Result<Box<dyn IntensityField>, ModelError> {
        let _ = (dist, device);
        Err(ModelError::Parameter {
            name: "recon",
            value: format!("{}{GPU_SUFFIX}", self.name(param)),
            reason: "this representation has no GPU evaluation".into(),
        })
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
        builtin::parse(name).or_else(|e| parse_among(self.ids().into_iter(), name.trim()).ok_or(e))
    }

    /// The built-in open representations' ids, then the added ones'
    /// (collected first: the open ones are defined on first use, which takes
    /// the definitions' write lock).
    fn ids(&self) -> Vec<ExtensionId> {
        open_builtins().iter().chain(&self.added).copied().collect()
    }

    /// The candidates `job` lists: the built-in families' ([`super::builtin`]),
    /// then the open built-in representations', then the added ones', each in
    /// the order registered. A `tradeoff --gpu` table also lists the GPU's
    /// evaluation (`NAME+gpu`) of each instance of a representation the GPU
    /// evaluates, after its CPU instances.
    pub fn candidates(&self, job: &Job<'_>) -> Vec<Recon> {
        let mut out = builtin::candidates(job);
        let ids = self.ids();
        let defined = read();
        let gpu_twins = matches!(job, Job::Tradeoff { gpu: true, .. });
        for id in ids {
            let Some(rep) = defined.get(usize::from(id.0)) else {
                continue;
            };
            let params = rep.candidates(job);
            let twins = if gpu_twins && rep.evaluates_on_gpu() {
                params.clone()
            } else {
                Vec::new()
            };
            out.extend(
                params
                    .into_iter()
                    .map(|param| Recon::Extension { id, param, gpu: false }),
            );
            out.extend(twins.into_iter().map(|param| Recon::Extension { id, param, gpu: true }));
        }
        out
    }
}

/// The built-in representations on the open trait ([`builtin::open`]),
/// defined for the process on first use.
fn open_builtins() -> &'static [ExtensionId] {
    static IDS: std::sync::OnceLock<Vec<ExtensionId>> = std::sync::OnceLock::new();
    IDS.get_or_init(|| builtin::open().into_iter().filter_map(|rep| define(rep).ok()).collect())
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

/// The first of `ids` that reads `name` (or, for a representation the GPU
/// evaluates, `name` without its `+gpu`), as a [`Recon`].
fn parse_among(mut ids: impl Iterator<Item = ExtensionId>, name: &str) -> Option<Recon> {
    let (body, gpu) = strip_gpu(name);
    let defined = read();
    ids.find_map(|id| {
        let rep = defined.get(usize::from(id.0))?;
        match rep.parse(name) {
            Some(param) => Some(Recon::Extension { id, param, gpu: false }),
            None if gpu && rep.evaluates_on_gpu() => Some(Recon::Extension {
                id,
                param: rep.parse(body)?,
                gpu: true,
            }),
            None => None,
        }
    })
}

/// The registered representation `id` names.
fn get(id: ExtensionId) -> Option<Arc<dyn Representation>> {
    read().get(usize::from(id.0)).cloned()
}

/// The [`Recon`] the first representation registered in the process that
/// reads `name` reads it as, if any.
pub(crate) fn parse(name: &str) -> Option<Recon> {
    open_builtins();
    let count = read().len();
    parse_among((0..count).filter_map(|i| u16::try_from(i).ok().map(ExtensionId)), name)
}

/// The name of an extension's instance (`?ID:PARAM` for an id never registered: a bug).
pub(crate) fn name(id: ExtensionId, param: u32, gpu: bool) -> String {
    let name = get(id).map_or_else(|| format!("?{}:{param}", id.0), |rep| rep.name(param));
    if gpu {
        name + GPU_SUFFIX
    } else {
        name
    }
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

/// The instance `id`/`param` built from `dist` and evaluated by the installed GPU device.
pub(crate) fn build_gpu(
    id: ExtensionId,
    param: u32,
    dist: &Distribution,
) -> Result<Box<dyn IntensityField>, ModelError> {
    let rep = get(id).ok_or_else(|| ModelError::Internal(format!("representation {} was never registered", id.0)))?;
    let device = crate::device::device().map_err(|e| ModelError::gpu(name(id, param, true), e))?;
    rep.build_gpu(dist, param, device)
}
