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
    /// Certified gap to reach, in mesh units (default: 0.1 % of the larger mesh's largest radius).
    #[arg(long, value_parser = super::parse::positive)]
    tolerance: Option<f64>,
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

pub fn run(a: HausdorffArgs) -> anyhow::Result<i32> {
    let (pa, ta) = read(&a.a)?;
    let (pb, tb) = read(&a.b)?;
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
            triangles: [ta.len(), tb.len()],
            seconds,
        };
        serde_json::to_writer_pretty(&mut out, &o)?;
        writeln!(out)?;
    } else {
        writeln!(
            out,
            "H = {:.6} (+{:.6}); h(A,B) = {:.6}, h(B,A) = {:.6}; mean A->B {:.6}, RMS A->B {:.6}; {} and {} triangles in {:.3} s",
            h.value,
            h.bound,
            h.a_to_b.value,
            h.b_to_a.value,
            h.a_to_b.mean,
            h.a_to_b.rms,
            ta.len(),
            tb.len(),
            seconds
        )?;
        if !(h.a_to_b.converged && h.b_to_a.converged) {
            writeln!(
                out,
                "partial: bound not reached (refinement stopped after {} queries per direction; tolerance {tol})",
                photosolid::metrics::hausdorff::MAX_REFINEMENT_QUERIES
            )?;
        }
    }
    Ok(0)
}
