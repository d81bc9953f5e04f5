//! `photosolid tradeoff FILE [--json]`: the speed/accuracy trade of each filter.
//!
//! For each filter and a few factors: the time per output sample of a CPU
//! render (measured in-process, median of repeats, both cores) and the
//! filter's hold-out error (keep every 2nd C-plane and γ row). A row is
//! Pareto-optimal when no other row is both faster and more accurate.

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use photosolid::reconstruct::{holdout, render, Filter, HoldoutSpec, LightTexture};
use serde::Serialize;

use super::ReadArgs;

#[derive(Args, Debug)]
pub struct TradeoffArgs {
    /// An .ies or .ldt file.
    file: PathBuf,
    /// Factors to time (comma separated).
    #[arg(long, value_delimiter = ',', default_value = "1,5,10", value_parser = super::parse::texture_factor)]
    factors: Vec<u32>,
    /// Timing repeats per row (the median is reported).
    #[arg(long, default_value_t = 7, value_parser = super::parse::at_least_one)]
    repeats: usize,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    read: ReadArgs,
}

/// One row of the trade-off table.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    filter: Filter,
    factor: u32,
    samples: usize,
    time_per_sample_ns: f64,
    samples_per_second: f64,
    holdout_rms_pct: f64,
    holdout_max_pct: f64,
    pareto: bool,
}

pub fn run(a: TradeoffArgs) -> anyhow::Result<i32> {
    let lum = super::load(&a.file, &a.read)?;
    let tex = LightTexture::new(&lum.distribution)?;
    let filters = Filter::ALL;
    let spec = HoldoutSpec {
        c_step: 2,
        gamma_step: 2,
    };
    // Hold-out needs something to drop on each axis; fall back to γ only for single-plane data.
    let errors = holdout(&lum.distribution, spec, &filters).or_else(|_| {
        holdout(
            &lum.distribution,
            HoldoutSpec {
                c_step: 1,
                gamma_step: 2,
            },
            &filters,
        )
    })?;
    let mut rows = Vec::new();
    for (k, &f) in filters.iter().enumerate() {
        for &factor in &a.factors {
            let mut times = Vec::with_capacity(a.repeats.max(1));
            let mut samples = 0;
            for _ in 0..a.repeats.max(1) {
                let t0 = Instant::now();
                let r = render(&tex, f, factor)?;
                times.push(t0.elapsed().as_secs_f64());
                samples = r.data.len();
            }
            times.sort_by(f64::total_cmp);
            let median = times[times.len() / 2];
            rows.push(Row {
                filter: f,
                factor,
                samples,
                time_per_sample_ns: 1e9 * median / samples.max(1) as f64,
                samples_per_second: samples as f64 / median.max(1e-12),
                holdout_rms_pct: errors[k].rms_percent,
                holdout_max_pct: errors[k].max_percent,
                pareto: false,
            });
        }
    }
    let dominated = |r: &Row| {
        rows.iter().any(|o| {
            o.time_per_sample_ns <= r.time_per_sample_ns
                && o.holdout_rms_pct <= r.holdout_rms_pct
                && (o.time_per_sample_ns < r.time_per_sample_ns || o.holdout_rms_pct < r.holdout_rms_pct)
        })
    };
    let flags: Vec<bool> = rows.iter().map(|r| !dominated(r)).collect();
    for (r, p) in rows.iter_mut().zip(flags) {
        r.pareto = p;
    }
    let mut out = std::io::stdout().lock();
    if a.json {
        serde_json::to_writer_pretty(&mut out, &rows)?;
        writeln!(out)?;
        return Ok(0);
    }
    writeln!(
        out,
        "{}: CPU render time vs hold-out error (keep every 2nd plane/row)",
        a.file.display()
    )?;
    writeln!(
        out,
        "{:<16} {:>6} {:>10} {:>10} {:>10} {:>9} {:>9}  pareto",
        "filter", "factor", "samples", "ns/sample", "Msamples/s", "rms %", "max %"
    )?;
    for r in &rows {
        writeln!(
            out,
            "{:<16} {:>6} {:>10} {:>10.2} {:>10.1} {:>9.3} {:>9.3}  {}",
            r.filter.to_string(),
            r.factor,
            r.samples,
            r.time_per_sample_ns,
            r.samples_per_second / 1e6,
            r.holdout_rms_pct,
            r.holdout_max_pct,
            if r.pareto { "*" } else { "" }
        )?;
    }
    Ok(0)
}
