//! `photosolid mesh FILE [--filter F | --measured] [--tolerance PCT% | --factor K] [--units cd|peak|klm|flux] [--color] -o solid.{obj,ply,stl,glb}`.

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;
use photosolid::jobs::{self, Loaded, MeshSettings};
use photosolid::registry::Recon;
use photosolid::solid::adaptive::AdaptiveGrid;
use photosolid::solid::{export, topology, Mesh, MeshTopology, SanityReport, Units, UnitsName};

use super::ReadArgs;

#[derive(Args, Debug)]
pub struct MeshArgs {
    /// A photometric file: .ies, .ldt, TM-33 .xml, or a GLDF photometry (FILE.gldf#ID; FILE.gldf when it holds one).
    file: PathBuf,
    /// Reconstruct with this filter (nearest, bilinear, catmull-rom, mitchell[:B,C], bspline, pchip)
    /// or the fitted OpenGL lights (`fitted-gl`), on a grid `--factor` times denser than the file's.
    #[arg(long, conflicts_with = "measured")]
    filter: Option<Recon>,
    /// With a filter: build the solid from the filter's rendered float texture (`--factor`
    /// times supersampled, texel centres as vertices, as the GPU path produces it)
    /// instead of sampling the filter on the refined measurement grid.
    #[arg(long, requires = "filter")]
    texture: bool,
    /// The measured points alone, Delaunay-triangulated (no interpolation).
    #[arg(long)]
    measured: bool,
    /// A fixed grid for a filtered solid: each measured interval cut into this many steps
    /// (with --texture: the render factor, default 5). Default: the adaptive grid of --tolerance.
    #[arg(long, value_parser = super::parse::at_least_one, allow_negative_numbers = true)]
    factor: Option<usize>,
    /// Adaptive grid of a filtered solid: C planes and gamma rows are added where the mesh
    /// deviates from the filter's field by more than PCT of I_max (radially, at the tested
    /// points: edge midpoints and triangle centres), a percent with its sign (`0.1%`; a bare
    /// number is refused) [default: 0.1%].
    #[arg(long, value_name = "PCT%", value_parser = super::parse::pct_of_peak, allow_hyphen_values = true, conflicts_with_all = ["factor", "texture"])]
    tolerance: Option<super::parse::PctOfPeak>,
    /// Units of the vertex coordinates: cd (1 unit = 1 cd), peak (I_max = 1), klm (cd per 1000 lm
    /// of the file's lamp flux, as in EULUMDAT; not for absolute photometry), flux (cd per 1000 lm of
    /// the computed luminaire flux: solids of equal flux).
    #[arg(long, value_enum, default_value = "cd")]
    units: UnitsName,
    /// Per-vertex colour from the viridis map of intensity (not in STL).
    #[arg(long)]
    color: bool,
    /// Output: .obj, .ply (binary), .stl (binary) or .glb.
    #[arg(short, long)]
    output: PathBuf,
    /// Print the solid's numbers as JSON (vertices, triangles, volume, area, topology).
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    read: ReadArgs,
}

pub fn run(a: MeshArgs) -> anyhow::Result<i32> {
    // Check the arguments before loading anything.
    let recon = match (a.measured, a.filter) {
        (true, _) => Recon::Measured,
        (false, Some(r)) => r,
        (false, None) => {
            anyhow::bail!("choose --filter F (reconstructed solid) or --measured (measured points only)")
        }
    };
    if export::MeshFormat::from_path(&a.output).is_none() {
        return Err(anyhow::Error::from(export::MeshFormat::unknown_extension(&a.output)).context("-o"));
    }
    super::check_output("-o", &a.output)?;
    let file = Loaded::load(&a.file, &a.read.options())?;
    let settings = MeshSettings {
        recon,
        texture: a.texture,
        factor: a.factor,
        tolerance: a.tolerance,
        units: a.units,
        color: a.color,
    };
    let built = super::with_progress("adaptive solid", |progress| {
        jobs::mesh(file.named(), &settings, progress)
    })
    .with_context(|| a.file.display().to_string())?;
    let (mesh, adaptive, units) = (built.mesh, built.adaptive, built.units);
    let report = mesh
        .sanity_check()
        .map_err(|e| anyhow::anyhow!("the solid failed its sanity check: {e}"))?;
    export::write(&mesh, &a.output)?;
    // What a reader of the file gets: read it back, merge vertices by position, check.
    let written = export::read(&a.output)?;
    let solid = Written {
        mesh: &mesh,
        report: &report,
        written: &written,
        topo: topology(written.positions(), written.triangles()),
        adaptive: adaptive.as_ref(),
        units,
        tolerance_pct: settings.tolerance_pct(),
    };
    if a.json {
        outln!("{}", serde_json::to_string_pretty(&solid.json(&a))?);
    } else {
        solid.print(&a)?;
    }
    Ok(0)
}

/// A written solid and what was checked of it: the mesh's own sanity report
/// and the topology of the file as read back.
struct Written<'a> {
    mesh: &'a Mesh,
    report: &'a SanityReport,
    written: &'a Mesh,
    topo: MeshTopology,
    adaptive: Option<&'a AdaptiveGrid>,
    units: Units,
    /// The adaptive grid's tolerance, % of I_max.
    tolerance_pct: f64,
}

impl Written<'_> {
    /// `mesh --json`.
    fn json(&self, a: &MeshArgs) -> serde_json::Value {
        let (mesh, report, written, topo, adaptive) = (self.mesh, self.report, self.written, &self.topo, self.adaptive);
        serde_json::json!({
            "path": a.output.display().to_string(),
            "units": self.units.name(),
            "vertices": written.positions().len(),
            "triangles": written.triangles().len(),
            "volume": mesh.volume(),
            "area": mesh.area(),
            "edges": report.edges,
            "euler_characteristic": report.euler_characteristic,
            "components": topo.components,
            "origin_sheets": report.origin_sheets,
            "pinch_vertices": report.pinch_vertices,
            "watertight": topo.watertight,
            "manifold": topo.manifold,
            "file_topology": topo,
            "tolerance_cd": adaptive.map(|f| f.tolerance_cd),
            "tolerance_pct": adaptive.map(|_| self.tolerance_pct),
            "tested_deviation_cd": adaptive.map(|f| f.tested_deviation_cd),
            "tolerance_reached": adaptive.map(|f| f.reached),
            "stopped_by": adaptive.map(|f| f.stop),
        })
    }

    /// The text summary: each number once, the file's vertices and triangles
    /// (as read back), the solid's volume and area, then the adaptive grid.
    fn print(&self, a: &MeshArgs) -> std::io::Result<()> {
        let (mesh, report, written, topo) = (self.mesh, self.report, self.written, &self.topo);
        let count = photosolid::error::count;
        outln!(
            "{}: {}, {}, {}, χ = {}, {} at the origin; volume {} {u}³, area {} {u}²; as read back: {}, {}, {}",
            a.output.display(),
            count(written.positions().len(), "vertex", "vertices"),
            count(written.triangles().len(), "triangle", "triangles"),
            count(report.edges, "edge", "edges"),
            report.euler_characteristic,
            count(report.origin_sheets, "sheet", "sheets"),
            photosolid::numfmt::trimmed(mesh.volume(), 6),
            photosolid::numfmt::trimmed(mesh.area(), 6),
            if topo.watertight {
                "watertight"
            } else {
                "NOT watertight"
            },
            if topo.manifold { "manifold" } else { "NOT manifold" },
            count(topo.components, "component", "components"),
            // A compound unit in parentheses: (cd/klm)³, not cd/klm³.
            u = match self.units.name() {
                n if n.contains('/') => format!("({n})"),
                n => n.to_string(),
            },
        );
        if let Some(f) = self.adaptive {
            outln!(
                "adaptive grid {} C x {} gamma: largest tested deviation {:.4} cd, tolerance {}% of I_max = {:.4} cd{}",
                f.grid.c_angles_deg().len(),
                f.grid.gamma_angles_deg().len(),
                f.tested_deviation_cd,
                super::parse::short(self.tolerance_pct),
                f.tolerance_cd,
                if f.reached {
                    String::new()
                } else {
                    format!(" (NOT reached: {})", f.stop)
                }
            );
        }
        Ok(())
    }
}
