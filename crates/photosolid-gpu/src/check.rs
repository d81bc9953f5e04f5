//! The GPU check (`photosolid gpu-check`): render every loadable file with
//! every filter on the GPU and on the CPU, from the same plans, and compare
//! texel by texel (texels are I / I_max, so differences are fractions of I_max).
//!
//! [`CheckInputs::collect`] finds and loads the files (before the GPU is
//! touched, so a run that would check nothing fails early), [`check_file`]
//! renders one file's filters in submissions of at most
//! [`MAX_TEXELS_PER_SUBMISSION`] texels and compares them with
//! [`super::render_cpu`] on the same jobs, and [`CheckSummary`] adds the
//! files up. A check that checked nothing is an error
//! ([`Error::NothingChecked`]), never a pass.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use super::GpuContext;
use crate::error::{Error, Result};
use crate::formats::ReadOptions;
use crate::reconstruct::{Filter, LightTexture, RenderOptions};

/// Texels per GPU submission (2^25 f32 = 128 MiB of output): bounds the
/// memory a check of a large file holds at once.
pub const MAX_TEXELS_PER_SUBMISSION: usize = 1 << 25;

/// What to check.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckOptions {
    /// Supersampling factor in both axes (1-32).
    pub factor: u32,
    /// Filters rendered per file.
    pub filters: Vec<Filter>,
    /// Largest allowed |gpu − cpu| per texel, a fraction of I_max.
    pub tolerance: f64,
}

impl CheckOptions {
    /// Every filter ([`Filter::ALL`]) and Mitchell–Netravali with B = 0, C = 0.75.
    pub fn default_filters() -> Vec<Filter> {
        let mut f = Filter::ALL.to_vec();
        f.push(Filter::Mitchell { b: 0.0, c: 0.75 });
        f
    }
}

impl Default for CheckOptions {
    /// Factor 5, [`CheckOptions::default_filters`], tolerance 1e-5 of I_max.
    fn default() -> Self {
        Self {
            factor: 5,
            filters: Self::default_filters(),
            tolerance: 1e-5,
        }
    }
}

/// A file that was found but not checked, with the first line of its error.
#[derive(Debug, Clone, PartialEq)]
pub struct Skipped {
    /// The file.
    pub path: PathBuf,
    /// Why (the first line of the load error).
    pub reason: String,
}

/// The files a check runs on, loaded.
#[derive(Debug)]
pub struct CheckInputs {
    /// Every photometric file found under the paths.
    pub files: Vec<PathBuf>,
    /// The files that loaded, as textures.
    pub textures: Vec<(PathBuf, LightTexture)>,
    /// The files that did not load (or have no positive intensity).
    pub skipped: Vec<Skipped>,
}

impl CheckInputs {
    /// Find the photometric files under `paths` (directories recursively, as
    /// [`crate::formats::collect_files`]) and load each with `read`.
    ///
    /// # Errors
    /// [`Error::Io`] (not found) naming a path that does not exist: nothing to check there.
    pub fn collect(paths: &[PathBuf], read: &ReadOptions) -> Result<Self> {
        let mut files = Vec::new();
        for p in paths {
            if !p.exists() {
                return Err(Error::io(
                    p,
                    std::io::Error::new(
                        std::io::ErrorKind::NotFound,
                        "no such file or directory: nothing to check",
                    ),
                ));
            }
            crate::formats::collect_files(p, &mut files)?;
        }
        let (mut textures, mut skipped) = (Vec::new(), Vec::new());
        for f in &files {
            match crate::formats::load_with(f, read).and_then(|l| Ok(LightTexture::new(l.distribution())?)) {
                Ok(t) => textures.push((f.clone(), t)),
                Err(e) => skipped.push(Skipped {
                    path: f.clone(),
                    reason: e.to_string().lines().next().unwrap_or("").to_string(),
                }),
            }
        }
        Ok(Self {
            files,
            textures,
            skipped,
        })
    }

    /// [`Error::NothingChecked`] when no file loaded (`paths` names where they were looked for).
    pub fn require_some(&self, paths: &[PathBuf]) -> Result<()> {
        if self.textures.is_empty() {
            return Err(Error::NothingChecked(format!(
                "none of the {} file(s) found under {} loaded",
                self.files.len(),
                paths
                    .iter()
                    .map(|p| p.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )));
        }
        Ok(())
    }
}

/// Clamped-texel counts that differ between the GPU and the CPU for one filter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClampMismatch {
    /// The filter.
    pub filter: Filter,
    /// Texels the GPU clamped.
    pub gpu: usize,
    /// Texels the CPU clamped.
    pub cpu: usize,
    /// The counts a device within the tolerance may report
    /// ([`super::clamp_count_range`]): inclusive bounds.
    pub within_tolerance: (usize, usize),
}

impl ClampMismatch {
    /// Whether the GPU's count is one a device within the tolerance may
    /// report: the differing texels are overshoots that end within rounding of 0.
    pub fn within_rounding(&self) -> bool {
        (self.within_tolerance.0..=self.within_tolerance.1).contains(&self.gpu)
    }
}

/// One file's check.
#[derive(Debug, Clone, PartialEq)]
pub struct FileCheck {
    /// The file.
    pub path: PathBuf,
    /// Texture rows (gamma) and columns (C) of the first filter's render.
    pub height: usize,
    /// Texture columns (C).
    pub width: usize,
    /// Renders compared (one per filter).
    pub renders: usize,
    /// Renders over the tolerance (or of different sizes).
    pub failed: usize,
    /// Largest |gpu − cpu| over the file's renders (fraction of I_max; NaN counts as infinity).
    pub max_diff: f64,
    /// The filter where `max_diff` occurs (the first filter when all agree exactly).
    pub max_filter: Filter,
    /// Filters whose clamped-texel counts differ (within rounding of 0 or not:
    /// [`ClampMismatch::within_rounding`]).
    pub clamp_mismatches: Vec<ClampMismatch>,
}

/// Render `tex` with every filter of `opts` on `ctx` and on the CPU, from
/// the same plans, and compare.
///
/// # Errors
/// [`crate::GpuError`] from the device or the plans; [`Error::NothingChecked`]
/// when `opts.filters` is empty.
pub fn check_file(ctx: &GpuContext, path: &Path, tex: &LightTexture, opts: &CheckOptions) -> Result<FileCheck> {
    let Some(&first) = opts.filters.first() else {
        return Err(Error::NothingChecked("no filter to render".into()));
    };
    let items: Vec<(&LightTexture, RenderOptions)> = opts
        .filters
        .iter()
        .map(|&filter| {
            (
                tex,
                RenderOptions {
                    filter,
                    factor: opts.factor,
                    ..RenderOptions::default()
                },
            )
        })
        .collect();
    // One plan per filter, shared by both renders.
    let plans = super::plans(&items)?;
    let jobs = super::jobs(&items, &plans);
    let mut out = FileCheck {
        path: path.to_path_buf(),
        height: plans[0].mapping.height,
        width: plans[0].mapping.width,
        renders: 0,
        failed: 0,
        max_diff: 0.0,
        max_filter: first,
        clamp_mismatches: Vec::new(),
    };
    for group in submissions(&jobs, MAX_TEXELS_PER_SUBMISSION) {
        let gpu = ctx.render_jobs(&jobs[group.clone()])?;
        for (job, g) in jobs[group].iter().zip(&gpu) {
            let cpu = super::render_cpu(job);
            let d = g
                .data
                .iter()
                .zip(&cpu.data)
                .map(|(x, y)| {
                    let d = (x - y).abs() as f64;
                    if d.is_nan() {
                        f64::INFINITY
                    } else {
                        d
                    }
                })
                .fold(0.0, f64::max);
            if g.data.len() != cpu.data.len() || d > opts.tolerance {
                out.failed += 1;
            }
            if g.clamped != cpu.clamped {
                let range = super::clamp_count_range(job, opts.tolerance as f32);
                out.clamp_mismatches.push(ClampMismatch {
                    filter: job.plan.filter,
                    gpu: g.clamped,
                    cpu: cpu.clamped,
                    within_tolerance: (*range.start(), *range.end()),
                });
            }
            if d > out.max_diff {
                out.max_diff = d;
                out.max_filter = job.plan.filter;
            }
            out.renders += 1;
        }
    }
    Ok(out)
}

/// Consecutive groups of `jobs`, each of at most `max_texels` texels (a
/// single larger job is a group of its own).
fn submissions(jobs: &[super::RenderJob<'_>], max_texels: usize) -> Vec<std::ops::Range<usize>> {
    let mut groups = Vec::new();
    let mut start = 0;
    while start < jobs.len() {
        let mut end = start + 1;
        let mut n = jobs[start].height() * jobs[start].width();
        while end < jobs.len() && n + jobs[end].height() * jobs[end].width() <= max_texels {
            n += jobs[end].height() * jobs[end].width();
            end += 1;
        }
        groups.push(start..end);
        start = end;
    }
    groups
}

/// The files of a check added up.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckSummary {
    /// Renders compared.
    pub checked: usize,
    /// Renders over the tolerance.
    pub failed: usize,
    /// Renders whose clamped-texel counts differ by more than texels within
    /// rounding of 0 (a failure).
    pub clamp_mismatches: usize,
    /// Renders whose clamped-texel counts differ only by texels whose value is
    /// within the tolerance of 0 (not a failure; reported).
    pub clamp_rounding: usize,
    /// The largest |gpu − cpu| and where: `FILE [FILTER]` (None before any file).
    pub worst: Option<(f64, String)>,
    /// Since [`CheckSummary::start`].
    pub elapsed: Duration,
    started: Instant,
}

impl CheckSummary {
    /// An empty summary; the clock starts now.
    pub fn start() -> Self {
        Self {
            checked: 0,
            failed: 0,
            clamp_mismatches: 0,
            clamp_rounding: 0,
            worst: None,
            elapsed: Duration::ZERO,
            started: Instant::now(),
        }
    }

    /// Add one file's check.
    pub fn add(&mut self, f: &FileCheck) {
        self.checked += f.renders;
        self.failed += f.failed;
        let rounding = f.clamp_mismatches.iter().filter(|m| m.within_rounding()).count();
        self.clamp_rounding += rounding;
        self.clamp_mismatches += f.clamp_mismatches.len() - rounding;
        if self.worst.as_ref().is_none_or(|w| f.max_diff > w.0) {
            self.worst = Some((f.max_diff, format!("{} [{}]", f.path.display(), f.max_filter)));
        }
        self.elapsed = self.started.elapsed();
    }

    /// Whether every render was within the tolerance and clamped the texels a
    /// device within the tolerance may clamp.
    ///
    /// # Errors
    /// [`Error::NothingChecked`] when no render was compared.
    pub fn passed(&self) -> Result<bool> {
        if self.checked == 0 {
            return Err(Error::NothingChecked("no render was compared".into()));
        }
        Ok(self.failed == 0 && self.clamp_mismatches == 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A path that does not exist is an error naming it; a run where nothing loads is `NothingChecked`.
    #[test]
    fn nothing_to_check_is_an_error() {
        let missing = PathBuf::from("/nonexistent/photosolid-check");
        let e = CheckInputs::collect(std::slice::from_ref(&missing), &ReadOptions::default()).unwrap_err();
        assert!(matches!(&e, Error::Io { path, .. } if path == &missing), "{e}");
        assert!(e.to_string().contains("nothing to check"), "{e}");

        let dir = tempfile::tempdir().unwrap();
        let bad = dir.path().join("bad.ies");
        std::fs::write(&bad, "not a photometric file").unwrap();
        let paths = vec![dir.path().to_path_buf()];
        let inputs = CheckInputs::collect(&paths, &ReadOptions::default()).unwrap();
        assert_eq!(
            (inputs.files.len(), inputs.textures.len(), inputs.skipped.len()),
            (1, 0, 1)
        );
        assert_eq!(inputs.skipped[0].path, bad);
        let e = inputs.require_some(&paths).unwrap_err();
        assert!(matches!(e, Error::NothingChecked(_)), "{e}");
        assert_eq!(crate::error::ErrorRecord::from(&e).code, "nothing-checked");

        let s = CheckSummary::start();
        assert!(matches!(s.passed(), Err(Error::NothingChecked(_))));
    }
}
