//! `photosolid engines FILE [--engines ...] [--against ...] [--json] [--report DIR] [--tolerance PCT%]`:
//! each engine's emulated lookup against the reference, with the trade-table metrics; one row per
//! documented loader defect. JSON keys: `photosolid::engines::EnginesReport`.

use std::fmt::Write as _;
use std::path::PathBuf;

use clap::Args;
use photosolid::compare::Against;
use photosolid::engines::{Engine, EnginesReport};
use photosolid::jobs::{self, EnginesSettings, Loaded};
use photosolid::reconstruct::Filter;

use super::{ReadArgs, ReportArgs};

#[derive(Args, Debug)]
pub struct EnginesArgs {
    /// A photometric file: .ies, .ldt, TM-33 .xml, or a GLDF photometry (FILE.gldf#ID; FILE.gldf when it holds one).
    file: PathBuf,
    /// Engines (comma separated). Default: all.
    #[arg(long, value_delimiter = ',')]
    engines: Option<Vec<Engine>>,
    /// The reference: truth (the closed form a synth file records) or a reconstruction of FILE
    /// (a filter, measured, fitted-gl). Default: catmull-rom on the native grid.
    #[arg(long)]
    against: Option<Against>,
    /// Deprecated spelling of --against.
    #[arg(long, hide = true, conflicts_with = "against")]
    reference: Option<Against>,
    /// Resolution search: for each engine whose resolution is a choice, the smallest power of two
    /// whose certified Hausdorff distance (plus its bound) is within PCT, a percent of I_max with
    /// its sign (`1%`; a bare number is refused).
    #[arg(long, value_name = "PCT%", value_parser = super::parse::pct_of_peak, allow_hyphen_values = true)]
    tolerance: Option<super::parse::PctOfPeak>,
    /// Resolution of the engines where it is a choice (pbrt, unity-point, unity-spot, godot).
    #[arg(long)]
    resolution: Option<usize>,
    /// Filter of pbrt's and godot's bakes.
    #[arg(long, default_value = "catmull-rom")]
    filter: Filter,
    /// Refinement factor of the solids' grid.
    #[arg(long, default_value_t = 3, value_parser = super::parse::at_least_one, allow_negative_numbers = true)]
    factor: usize,
    // --json, --report DIR (the plots: error maps next to the reference).
    #[command(flatten)]
    out: ReportArgs,
    #[command(flatten)]
    read: ReadArgs,
}

pub fn run(a: EnginesArgs) -> anyhow::Result<i32> {
    a.out.check()?;
    let against = match (a.against, a.reference) {
        (Some(r), _) => Some(r),
        (None, Some(r)) => {
            eprintln!("warning: [deprecated-option] engines --reference is deprecated: write --against {r}");
            Some(r)
        }
        (None, None) => None,
    };
    let file = Loaded::load(&a.file, &a.read.options())?;
    let settings = EnginesSettings {
        engines: a.engines.clone(),
        against,
        tolerance: a.tolerance,
        resolution: a.resolution,
        filter: a.filter,
        factor: a.factor,
        plots: a.out.report.is_some(),
    };
    let r = jobs::engines(file.named(), &settings)?;
    for w in r
        .warnings
        .iter()
        .filter(|w| w.code == photosolid::error::WarningCode::LayoutLimit)
    {
        eprintln!("warning: {w}");
    }
    a.out
        .emit(&r, &text(&r), photosolid::report::engines_report::write_report)?;
    Ok(0)
}

/// The table as text.
fn text(r: &EnginesReport) -> String {
    let mut s = format!(
        "{}\nreference: {} (I_max {:.4} cd); {} directions; radial max: {}; solids refined x{}\n",
        r.file, r.reference, r.i_max_cd, r.directions, r.radial_max_method, r.factor
    );
    let _ = writeln!(
        s,
        "{:<34} {:>6} {:>10} {:>10} {:>10} {:>9} {:>9}  against",
        "row", "res", "H %", "rad max %", "rad rms %", "flux %", "misplaced"
    );
    for row in &r.rows {
        let m = &row.metrics;
        let _ = writeln!(
            s,
            "{:<34} {:>6} {:>10.4} {:>10.4} {:>10.4} {:>+9.4} {:>9.5}  {}",
            row.name,
            row.resolution.map_or("-".into(), |n| n.to_string()),
            m.hausdorff_pct,
            m.radial_max_pct,
            m.radial_rms_pct,
            m.flux_error_pct,
            m.misplaced_flux,
            row.against
        );
    }
    for row in &r.rows {
        let _ = writeln!(s, "  {} emulates: {}", row.name, row.engine_version);
    }
    for row in r.rows.iter().filter(|x| x.source.is_some()) {
        let _ = writeln!(s, "  {}: {}", row.name, row.source.as_deref().unwrap_or(""));
    }
    for sk in &r.skipped {
        let _ = writeln!(s, "{} skipped: {}", sk.engine, sk.reason);
    }
    for search in &r.resolutions {
        let tried: Vec<String> = search
            .tried
            .iter()
            .map(|t| format!("{}: {:.4}%", t.resolution, t.hausdorff_pct + t.hausdorff_bound_pct))
            .collect();
        let _ = writeln!(
            s,
            "{} within {}% of I_max: {} (tried {})",
            search.engine,
            search.tolerance_pct,
            search
                .resolution
                .map_or("none up to the largest".into(), |n| n.to_string()),
            tried.join(", ")
        );
    }
    s
}
