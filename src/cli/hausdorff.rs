//! `photosolid hausdorff A B [--tolerance T] [--json]`: certified Hausdorff
//! distance between two mesh files (PLY, OBJ, STL or GLB as photosolid
//! writes them), in the meshes' units.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;
use glam::DVec3;
use photosolid::metrics::{hausdorff, MeshRef};
use photosolid::solid::export;
use serde::Serialize;

#[derive(Args, Debug)]
pub struct HausdorffArgs {
    /// First mesh (.ply, .obj, .stl or .glb).
    a: PathBuf,
    /// Second mesh (.ply, .obj, .stl or .glb).
    b: PathBuf,
    /// Certified gap to reach: an absolute length in the meshes' unit (cd for solids written with
    /// `mesh --units cd`, 1 = I_max with `--units peak`), not a percent
    /// [default: 0.1 % of the larger mesh's largest radius].
    #[arg(long, value_parser = super::parse::positive)]
    tolerance: Option<f64>,
    /// Convert both meshes to candela first, by the scale their headers record
    /// (`mesh --units peak|klm|flux` files record it), so that meshes written
    /// in different units compare. Without it, meshes in different units are refused.
    #[arg(long, value_parser = ["cd"])]
    units: Option<String>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct Out {
    hausdorff: f64,
    bound: f64,
    a_to_b: photosolid::metrics::OneSided,
    b_to_a: photosolid::metrics::OneSided,
    tolerance: f64,
    /// The unit of every length here (`cd`, `peak`, `cd/klm`); null when the files record none.
    units: Option<&'static str>,
    triangles: [usize; 2],
    seconds: f64,
}

/// Vertex positions (f64) and triangles of a mesh file.
type Triangles = (Vec<DVec3>, Vec<[u32; 3]>);

fn read(p: &Path) -> anyhow::Result<Triangles> {
    let mesh = export::read(p)?;
    let pos = mesh.positions_f64();
    Ok((pos, mesh.triangles().to_vec()))
}

/// The units the file at `p` records (none when it cannot be read: the mesh reader says why).
fn units_of(p: &Path) -> export::RecordedUnits {
    std::fs::read(p).map(|b| export::recorded_units(&b)).unwrap_or_default()
}

/// Both meshes in one unit: the recorded units must agree (a file without
/// them is accepted as "units unknown"); with `--units cd` each is scaled to
/// cd by its recorded scale. Returns the common unit.
fn common_units(
    a: &HausdorffArgs,
    pa: &mut [DVec3],
    pb: &mut [DVec3],
) -> anyhow::Result<(Option<&'static str>, Vec<String>)> {
    let (ua, ub) = (units_of(&a.a), units_of(&a.b));
    let mut notes = Vec::new();
    if a.units.is_some() {
        for (path, u, pos) in [(&a.a, &ua, pa), (&a.b, &ub, pb)] {
            let scale = match (u.name, u.units_per_cd) {
                (Some("cd"), _) => 1.0,
                (_, Some(s)) => s,
                _ => anyhow::bail!(
                    "--units cd: {} records no scale (units per cd), so it cannot be converted",
                    path.display()
                ),
            };
            if scale != 1.0 {
                pos.iter_mut().for_each(|p| *p /= scale);
                notes.push(format!(
                    "{} converted from {} to cd (scale {} unit per cd)",
                    path.display(),
                    u.name.unwrap_or("its units"),
                    scale
                ));
            }
        }
        return Ok((Some("cd"), notes));
    }
    Ok(match (ua.name, ub.name) {
        (Some(x), Some(y)) if x != y => anyhow::bail!(
            "{} is in {x} and {} in {y}: a distance between them would mix units; write both with the same \
             `mesh --units`, or pass --units cd to convert both to candela by the scale their headers record",
            a.a.display(),
            a.b.display()
        ),
        (Some(x), Some(_)) => (Some(x), notes),
        (None, None) => {
            notes.push("units unknown: neither file records its units".into());
            (None, notes)
        }
        (Some(x), None) | (None, Some(x)) => {
            let unknown = if ua.name.is_none() { &a.a } else { &a.b };
            notes.push(format!(
                "{} records no units (another tool's mesh?): assumed to be in {x} like the other",
                unknown.display()
            ));
            (Some(x), notes)
        }
    })
}

pub fn run(a: HausdorffArgs) -> anyhow::Result<i32> {
    let (mut pa, ta) = read(&a.a)?;
    let (mut pb, tb) = read(&a.b)?;
    let (units, notes) = common_units(&a, &mut pa, &mut pb)?;
    let unit = units.map_or(String::new(), |u| format!(" {u}"));
    let radius = pa.iter().chain(&pb).map(|p| p.length()).fold(0.0, f64::max);
    let tol = a.tolerance.unwrap_or(1e-3 * radius);
    let t0 = Instant::now();
    let h = hausdorff(
        MeshRef {
            positions: &pa,
            triangles: &ta,
        },
        MeshRef {
            positions: &pb,
            triangles: &tb,
        },
        tol,
    );
    let seconds = t0.elapsed().as_secs_f64();
    let mut out = std::io::stdout().lock();
    if a.json {
        let o = Out {
            hausdorff: h.value,
            bound: h.bound,
            a_to_b: h.a_to_b,
            b_to_a: h.b_to_a,
            tolerance: tol,
            units,
            triangles: [ta.len(), tb.len()],
            seconds,
        };
        serde_json::to_writer_pretty(&mut out, &o)?;
        writeln!(out)?;
    } else {
        writeln!(
            out,
            "H = {}{unit} (+{}{unit}); h(A,B) = {}{unit}, h(B,A) = {}{unit}; mean A->B {}{unit}, RMS A->B {}{unit}; {} and {} in {:.3} s{}",
            sig(h.value),
            sig(h.bound),
            sig(h.a_to_b.value),
            sig(h.b_to_a.value),
            h.a_to_b.mean.map_or("-".into(), sig),
            h.a_to_b.rms.map_or("-".into(), sig),
            photosolid::error::count(ta.len(), "triangle", "triangles"),
            photosolid::error::count(tb.len(), "triangle", "triangles"),
            seconds,
            if units.is_none() { " (units unknown)" } else { "" }
        )?;
        if !(h.a_to_b.converged && h.b_to_a.converged) {
            writeln!(
                out,
                "partial: bound not reached (refinement stopped after {} queries per direction; tolerance {tol}{unit})",
                photosolid::metrics::hausdorff::MAX_REFINEMENT_QUERIES
            )?;
        }
    }
    for n in &notes {
        eprintln!("note: {n}");
    }
    Ok(0)
}

/// A distance with 6 significant digits.
fn sig(x: f64) -> String {
    photosolid::numfmt::trimmed(x, 6)
}
