//! Command-line arguments and dispatch. Each subcommand lives in its own file.

/// `println!` that returns the write error (`?`) instead of panicking, so a
/// closed stdout (`| head`) ends the command quietly through `main`.
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        writeln!(std::io::stdout().lock(), $($arg)*)?
    }};
}

mod batch;
mod choice;
mod compare;
mod convert;
mod demo;
mod engines;
mod export;
mod fit;
mod gpu_check;
mod grid;
mod hausdorff;
mod holdout;
mod info;
mod mesh;
mod road;
mod scene;
mod synth;
mod texture;
mod tradeoff;
mod validate;

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use photosolid::formats::ReadOptions;

/// Analyse and compare the photometric solids of real luminaires (IES LM-63, EULUMDAT).
#[derive(Parser, Debug)]
#[command(
    name = "photosolid",
    version,
    about,
    propagate_version = true,
    after_help = "Tolerances are percents written with their sign, e.g. 0.1%; a bare number is refused. \
                  Relative to I_max: mesh/compare/engines/plan/gpu-check --tolerance, compare/tradeoff \
                  --solid-tolerance, fit --guard. fit --tolerance is in percentage points of the fit's error. \
                  hausdorff --tolerance is a length in the meshes' unit. Every numeric option takes negative \
                  values as written (--rotate-c -90). compare, tradeoff and engines name the reference the \
                  same way: --against truth|withheld|RECON, and --vs FILE for a second measurement."
)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Print the photometric summary of one file (flux, LOR, beam angles, ...).
    Info(info::InfoArgs),
    /// Analyse every photometry under the paths (.ies, .ldt, TM-33 .xml, .gldf, and files read by content) into one table (Parquet, JSON Lines) and a catalogue page.
    Batch(batch::BatchArgs),
    /// Check files and directories (recursive); exit 1 if any file fails to load.
    Validate(validate::ValidateArgs),
    /// Convert between IES, EULUMDAT and TM-33-23 XML (format from OUT's extension).
    Convert(convert::ConvertArgs),
    /// Write an analytic distribution (isotropic, lambertian, cosine-power, spot, batwing, roadway).
    Synth(synth::SynthArgs),
    /// Render a light distribution texture (5x supersampled float texture) to EXR and PNG.
    Texture(texture::TextureArgs),
    /// Drop measured planes/rows, reconstruct them with each filter, report the errors.
    Holdout(holdout::HoldoutArgs),
    /// Time per sample vs hold-out error of every filter (Pareto rows marked).
    Tradeoff(tradeoff::TradeoffArgs),
    /// Build the photometric solid as a mesh (OBJ, PLY, STL, GLB).
    Mesh(mesh::MeshArgs),
    /// Print the measured grid as JSON or CSV (for independent cross-checks).
    Grid(grid::GridArgs),
    /// Certified Hausdorff distance between two mesh files (PLY, OBJ, STL, GLB).
    Hausdorff(hausdorff::HausdorffArgs),
    /// Run the main job on a built-in example luminaire (no file needed).
    Demo(demo::DemoArgs),
    /// Approximate the luminaire by at most 2 OpenGL lights (spot / point; Zotti et al. 2005).
    Fit(fit::FitArgs),
    /// Render every file with every filter on the GPU and the CPU; exit 1 if any texel differs by more than 1e-5 of I_max or the clamped texels differ beyond those within that of 0.
    GpuCheck(gpu_check::GpuCheckArgs),
    /// Compare reconstructions (and other files): Hausdorff distance, radial errors, speed; HTML report.
    Compare(compare::CompareArgs),
    /// Illuminance of a scene (TOML: luminaires, receivers, occluders) at every receiver point; isolux maps.
    Scene(scene::SceneArgs),
    /// Per luminaire of a scene, the cheapest representation within a tolerance, measured on the scene.
    Plan(scene::PlanArgs),
    /// Road lighting of a scene's [road] table (EN 13201-3): luminance, U_o, U_l, TI, R_EI, illuminance per lane.
    Road(road::RoadArgs),
    /// Write one renderer's light-profile layout (pbrt, ue5, ue4, unity-point, unity-spot, threejs, babylon, blender, gltf, godot).
    Export(export::ExportArgs),
    /// How far each renderer's lookup is from the file: trade-table metrics per engine, defect rows.
    Engines(engines::EnginesArgs),
}

/// The command line: [`Cli`] with every option that takes a value accepting a
/// value that starts with `-` when it is a number (`--rotate-c -90`,
/// `--tilt -5`, `--front -45`), on every subcommand, so no option needs the
/// `=` form for a negative number.
pub fn command() -> clap::Command {
    fn negatives(cmd: clap::Command) -> clap::Command {
        cmd.mut_args(|a| {
            if a.get_action().takes_values() && !a.is_positional() {
                a.allow_negative_numbers(true)
            } else {
                a
            }
        })
        .mut_subcommands(negatives)
    }
    negatives(<Cli as clap::CommandFactory>::command())
}

/// Parse the process's arguments with [`command`] (usage errors exit 2).
pub fn parse() -> Cli {
    use clap::FromArgMatches;
    let matches = command().get_matches();
    Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit())
}

/// Reader options shared by every command that loads files.
#[derive(Args, Debug, Clone)]
pub struct ReadArgs {
    /// Repair duplicate or unsorted angle lists (sort, drop duplicates) with a warning, instead of failing.
    #[arg(long)]
    repair: bool,
    /// Rotation sense of Type A/B horizontal angles: ccw (C90 = +y, default) or cw.
    #[arg(long, value_enum, default_value = "ccw")]
    handedness: choice::HandednessArg,
    /// EULUMDAT with several lamp sets: cd/klm refer to the first set's flux (default) or the sum.
    #[arg(long, value_enum, default_value = "first")]
    lamp_sets: choice::LampSetsArg,
    /// The luminaire's front: the C angle (degrees, the file's own frame) at the middle of its
    /// forward half, instead of its format's convention (IES and TM-33: C0; EULUMDAT: C90).
    /// BUG's forward half, `road`'s street side and `convert`'s warnings use it.
    #[arg(long, value_name = "DEG", allow_negative_numbers = true, value_parser = choice::parse_angle_deg)]
    front: Option<f64>,
}

impl ReadArgs {
    /// The library's reader options.
    fn options(&self) -> ReadOptions {
        ReadOptions {
            repair: self.repair,
            handedness: self.handedness.into(),
            lamp_set_flux: self.lamp_sets.into(),
            front_c_deg: self.front,
        }
    }
}

/// Output options of the commands that print a table and can write a report
/// folder (compare, tradeoff, engines).
#[derive(Args, Debug, Clone)]
pub struct ReportArgs {
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Write index.html, report.md, report.json and the plots (PNG) into DIR.
    #[arg(long)]
    report: Option<PathBuf>,
}

impl ReportArgs {
    /// Check `--report DIR` before any work ([`check_report_dir`]).
    fn check(&self) -> anyhow::Result<()> {
        self.report
            .as_deref()
            .map_or(Ok(()), |d| check_report_dir("--report", d))
    }

    /// Print `value` as JSON or `text`; then, with `--report DIR`, write the
    /// report folder with `write` and say where it is.
    fn emit<T: serde::Serialize, R>(
        &self,
        value: &T,
        text: &str,
        write: impl FnOnce(&T, &std::path::Path) -> photosolid::Result<R>,
    ) -> anyhow::Result<()> {
        emit(self.json, value, text)?;
        if let Some(dir) = &self.report {
            write(value, dir)?;
            say_report_written(self.json, dir)?;
        }
        Ok(())
    }
}

/// Load one file with the reader options (its luminaire, format header and
/// container declarations), as an anyhow error naming it.
fn load(path: &PathBuf, read: &ReadArgs) -> anyhow::Result<photosolid::formats::Document> {
    Ok(photosolid::formats::load_document_with(path, &read.options())?)
}

/// Run a parsed command line; returns the exit code.
pub fn run(cli: Cli) -> anyhow::Result<i32> {
    match cli.command {
        Command::Info(a) => info::run(a),
        Command::Batch(a) => batch::run(a),
        Command::Validate(a) => validate::run(a),
        Command::Convert(a) => convert::run(a),
        Command::Synth(a) => synth::run(a),
        Command::Texture(a) => texture::run(a),
        Command::Holdout(a) => holdout::run(a),
        Command::Tradeoff(a) => tradeoff::run(a),
        Command::Mesh(a) => mesh::run(a),
        Command::Grid(a) => grid::run(a),
        Command::Hausdorff(a) => hausdorff::run(a),
        Command::Demo(a) => demo::run(a),
        Command::Fit(a) => fit::run(a),
        Command::GpuCheck(a) => gpu_check::run(a),
        Command::Compare(a) => compare::run(a),
        Command::Scene(a) => scene::run_scene(a),
        Command::Plan(a) => scene::run_plan(a),
        Command::Road(a) => road::run_road(a),
        Command::Export(a) => export::run(a),
        Command::Engines(a) => engines::run(a),
    }
}

/// Check, before any work, that an output file can be created where it is
/// asked for: its folder exists and is a folder, and the path is not itself a
/// folder. `flag` names the option in the message (`-o`, `--jsonl`).
fn check_output(flag: &str, path: &std::path::Path) -> anyhow::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => std::path::Path::new("."),
    };
    if path.is_dir() {
        anyhow::bail!("{flag} {}: is a folder; give a file name", path.display());
    }
    if !dir.is_dir() {
        let what = if dir.exists() {
            "is not a folder"
        } else {
            "does not exist"
        };
        anyhow::bail!(
            "{flag} {}: the folder {} {what} (nothing was computed; create it first)",
            path.display(),
            dir.display()
        );
    }
    check_writable(flag, path, dir)
}

/// Check, before any work, that a report folder can be written: `dir` is a
/// folder or does not exist yet, and the nearest folder that exists above it
/// (where it will be created) is a folder this process can write in.
fn check_report_dir(flag: &str, dir: &std::path::Path) -> anyhow::Result<()> {
    if dir.exists() && !dir.is_dir() {
        anyhow::bail!(
            "{flag} {}: is a file, and a report is a folder; give a folder name (nothing was computed)",
            dir.display()
        );
    }
    let mut existing = dir;
    while !existing.exists() {
        existing = match existing.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => std::path::Path::new("."),
        };
    }
    if !existing.is_dir() {
        anyhow::bail!(
            "{flag} {}: {} is not a folder (nothing was computed)",
            dir.display(),
            existing.display()
        );
    }
    check_writable(flag, dir, existing)
}

/// Whether a file can be created in the existing folder `dir` (for `path`,
/// named by `flag` in the message): a probe file is created and removed, so
/// permissions, read-only mounts and full disks all show before the work.
fn check_writable(flag: &str, path: &std::path::Path, dir: &std::path::Path) -> anyhow::Result<()> {
    let probe = dir.join(format!(".photosolid-write-check-{}", std::process::id()));
    match std::fs::OpenOptions::new().write(true).create_new(true).open(&probe) {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
            Ok(())
        }
        // Left over by a crashed run with this process id: the folder is writable.
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(()),
        Err(e) => anyhow::bail!(
            "{flag} {}: cannot write in {}: {e} (nothing was computed)",
            path.display(),
            dir.display()
        ),
    }
}

/// A walk that found nothing photometric (`validate`, `batch`): say so on
/// stderr with the walk's notes (what was skipped and why), `suffix` after
/// the first line; the exit code 1.
fn nothing_found(paths: &[PathBuf], notes: &[String], suffix: &str) -> i32 {
    eprintln!("photosolid: nothing photometric found in {}{suffix}", list_paths(paths));
    for n in notes {
        eprintln!("{n}");
    }
    1
}

/// Paths as a user typed them, comma-separated (for messages).
fn list_paths(paths: &[PathBuf]) -> String {
    paths
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

/// A usage error found after parsing (a value valid alone but not with
/// another argument, e.g. a `--range` outside its `--maximize` key's
/// values): `main` exits 2 on it, as on clap's.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct UsageError(pub String);

/// Print `value` as pretty JSON, or `text` as it is.
fn emit(json: bool, value: &impl serde::Serialize, text: &str) -> anyhow::Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    if json {
        serde_json::to_writer_pretty(&mut out, value)?;
        writeln!(out)?;
    } else {
        write!(out, "{text}")?;
    }
    Ok(())
}

/// Say where a report was written: on stdout after a text table, on stderr
/// after JSON (so stdout stays one JSON document).
fn say_report_written(json: bool, dir: &std::path::Path) -> anyhow::Result<()> {
    let msg = format!("report written to {}", dir.join("index.html").display());
    if json {
        eprintln!("{msg}");
        Ok(())
    } else {
        emit(false, &(), &format!("{msg}\n"))
    }
}

/// Print `report` as pretty JSON, or as `FILE` followed by its text form.
fn print_report(json: bool, file: &std::path::Path, report: &impl serde::Serialize, text: &str) -> anyhow::Result<()> {
    emit(json, report, &format!("{}\n{text}", file.display()))
}

/// A progress bar on stderr for work that may take over a second (hidden
/// when stderr is not a terminal).
fn progress_bar(what: &str) -> indicatif::ProgressBar {
    let b = indicatif::ProgressBar::new(0);
    b.set_style(
        indicatif::ProgressStyle::with_template(&format!("{{bar:40}} {{pos}}/{{len}} {what} {{elapsed}} {{msg}}"))
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    b
}

/// Run `f` with a library progress callback that moves a bar on stderr
/// (labelled `what`), cleared when `f` returns.
fn with_progress<T>(what: &str, f: impl FnOnce(&photosolid::compare::Progress<'_>) -> T) -> T {
    let bar = progress_bar(what);
    let out = f(&progress_fn(&bar));
    bar.finish_and_clear();
    out
}

/// A library progress callback `(done, total, what)` that moves `bar`.
fn progress_fn(bar: &indicatif::ProgressBar) -> impl Fn(usize, usize, &str) + Sync + '_ {
    move |done, total, what| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
        bar.set_message(what.to_string());
    }
}

/// Value parsers of numeric arguments: clap applies them while parsing, so a
/// bad value is a usage error (exit 2) naming the flag, before any file is loaded.
pub(crate) mod parse {
    fn number<T: std::str::FromStr>(s: &str) -> Result<T, String> {
        s.trim().parse().map_err(|_| format!("`{s}` is not a number"))
    }
    /// An integer, or the reason it is not one: a negative number or a
    /// fraction gets "must be a positive integer" rather than "not a number".
    fn integer<T: std::str::FromStr>(s: &str) -> Result<T, String> {
        s.trim().parse().map_err(|_| match s.trim().parse::<f64>() {
            Ok(x) if x.is_finite() => format!("must be a positive integer (1, 2, 3, ...), got {s}"),
            _ => format!("`{s}` is not a number"),
        })
    }
    /// An integer >= 1 (a factor, a step, a count).
    pub fn at_least_one(s: &str) -> Result<usize, String> {
        match integer::<usize>(s)? {
            0 => Err("must be a positive integer (1, 2, 3, ...), got 0".into()),
            n => Ok(n),
        }
    }
    /// A supersampling factor of a texture: 1 to 32.
    pub fn texture_factor(s: &str) -> Result<u32, String> {
        match integer::<u32>(s).map_err(|e| e.replace("(1, 2, 3, ...)", "from 1 to 32"))? {
            n @ 1..=32 => Ok(n),
            n => Err(format!("{n} is outside 1..=32")),
        }
    }
    /// A finite number > 0.
    pub fn positive(s: &str) -> Result<f64, String> {
        let x = number::<f64>(s)?;
        if x.is_finite() && x > 0.0 {
            Ok(x)
        } else {
            Err(format!("{x} must be a finite number > 0"))
        }
    }
    /// A finite number >= 0.
    pub fn non_negative(s: &str) -> Result<f64, String> {
        let x = number::<f64>(s)?;
        if x.is_finite() && x >= 0.0 {
            Ok(x)
        } else {
            Err(format!("{x} must be a finite number >= 0"))
        }
    }
    pub use photosolid::numfmt::{short, PctOfPeak};

    /// A percent of I_max > 0% (`0.1%`); a bare number is refused with a hint
    /// ([`PctOfPeak::parse`], the library's one reading of a percent).
    pub fn pct_of_peak(s: &str) -> Result<PctOfPeak, String> {
        PctOfPeak::parse(s, false).map_err(|e| e.to_string())
    }
    /// A percent of I_max >= 0% (`0%` allowed); a bare number is refused with a hint.
    pub fn pct_of_peak_or_zero(s: &str) -> Result<PctOfPeak, String> {
        PctOfPeak::parse(s, true).map_err(|e| e.to_string())
    }
    /// A percent >= 0 of a quantity other than I_max (`fit --tolerance 1%`: percentage
    /// points of the fit's error), as the percent; a bare number is refused with a hint.
    pub fn percentage_points(s: &str) -> Result<f64, String> {
        photosolid::numfmt::parse_percentage_points(s).map_err(|e| e.to_string())
    }
    /// A finite number (an angle, an offset).
    pub fn finite(s: &str) -> Result<f64, String> {
        let x = number::<f64>(s)?;
        if x.is_finite() {
            Ok(x)
        } else {
            Err(format!("{x} must be a finite number"))
        }
    }
}

/// A private `XDG_RUNTIME_DIR` for the GPU drivers when the environment has none.
pub(crate) mod runtime_dir {
    use std::path::PathBuf;

    /// Removes the directory it created when dropped.
    pub struct Guard(Option<PathBuf>);

    impl Drop for Guard {
        fn drop(&mut self) {
            if let Some(d) = self.0.take() {
                let _ = std::fs::remove_dir_all(d);
            }
        }
    }

    /// When `XDG_RUNTIME_DIR` is unset or not a directory, create a fresh
    /// directory only this user can enter (mode 0700, a new name: never one
    /// that someone else made) and point the variable at it. Called at the
    /// start of `main`, before any thread exists, so setting the variable is sound.
    pub fn ensure() -> Guard {
        if std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|d| PathBuf::from(d).is_dir()) {
            return Guard(None);
        }
        for attempt in 0..8u32 {
            let dir = std::env::temp_dir().join(format!("photosolid-runtime-{}-{attempt}", std::process::id()));
            let mut builder = std::fs::DirBuilder::new();
            #[cfg(unix)]
            std::os::unix::fs::DirBuilderExt::mode(&mut builder, 0o700);
            if builder.create(&dir).is_ok() {
                std::env::set_var("XDG_RUNTIME_DIR", &dir);
                return Guard(Some(dir));
            }
        }
        Guard(None)
    }

    #[cfg(test)]
    mod tests {
        /// Unset: a fresh 0700 directory is set and removed again by the guard.
        #[test]
        fn sets_a_private_directory_when_unset() {
            std::env::remove_var("XDG_RUNTIME_DIR");
            let guard = super::ensure();
            let dir = std::path::PathBuf::from(std::env::var_os("XDG_RUNTIME_DIR").expect("set"));
            assert!(dir.is_dir());
            #[cfg(unix)]
            {
                use std::os::unix::fs::PermissionsExt;
                assert_eq!(std::fs::metadata(&dir).unwrap().permissions().mode() & 0o777, 0o700);
            }
            // Set and valid: left alone.
            assert!(super::ensure().0.is_none());
            drop(guard);
            assert!(!dir.exists());
        }
    }
}

#[cfg(test)]
mod tests {
    /// Every option that takes a value, on every subcommand, reads `-90` as a value.
    #[test]
    fn every_option_takes_negative_numbers() {
        fn check(cmd: &clap::Command, path: &str, missing: &mut Vec<String>) {
            for a in cmd.get_arguments() {
                if a.get_action().takes_values() && !a.is_positional() && !a.is_allow_negative_numbers_set() {
                    missing.push(format!("{path} --{}", a.get_id()));
                }
            }
            for sub in cmd.get_subcommands() {
                check(sub, &format!("{path} {}", sub.get_name()), missing);
            }
        }
        let cmd = super::command();
        cmd.clone().debug_assert();
        let mut missing = Vec::new();
        check(&cmd, "photosolid", &mut missing);
        assert!(missing.is_empty(), "{missing:?}");
        let m = cmd.try_get_matches_from(["photosolid", "convert", "a.ies", "b.ldt", "--rotate-c", "-90"]);
        assert!(m.is_ok(), "{m:?}");
    }
}
