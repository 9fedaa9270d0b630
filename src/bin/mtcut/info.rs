//! `mtcut info MESH [--json]`.

use crate::CliResult;
use mtcut::geom::Aabb;
use mtcut::io::read_mesh;
use mtcut::mesh::{ImportReport, QualitySummary, Severity, TetMesh};
use serde_json::{Value, json};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// The mesh (.vtu, .node/.ele, .mesh).
    mesh: PathBuf,
    /// Print one JSON object on stdout instead of text.
    #[arg(long)]
    json: bool,
}

/// Everything `info` reports about a mesh, computed once.
pub struct MeshInfo {
    pub vertices: usize,
    pub tets: usize,
    pub bbox: Aabb,
    pub volume: f64,
    pub boundary_faces: usize,
    pub boundary_area: f64,
    pub components: usize,
    pub quality: QualitySummary,
    pub report: ImportReport,
    pub problems: Vec<String>,
    pub warnings: Vec<String>,
}

impl MeshInfo {
    pub fn of(mesh: &TetMesh, report: ImportReport) -> MeshInfo {
        let adj = mesh.adjacency();
        let boundary = mesh.boundary_with(&adj);
        let validation = mesh.validate();
        MeshInfo {
            vertices: mesh.nb_vertices(),
            tets: mesh.nb_tets(),
            bbox: mesh.bbox(),
            volume: mesh.volume(),
            boundary_faces: boundary.triangles.len(),
            boundary_area: boundary.area,
            components: adj.components().0,
            quality: mesh.quality(),
            report,
            problems: validation.lines(Severity::Error),
            warnings: validation.lines(Severity::Warning),
        }
    }

    pub fn to_json(&self) -> Value {
        let q = &self.quality;
        json!({
            "vertices": self.vertices,
            "tets": self.tets,
            "bbox": {"min": self.bbox.min.to_array(), "max": self.bbox.max.to_array()},
            "volume": self.volume,
            "boundary_faces": self.boundary_faces,
            "boundary_area": self.boundary_area,
            "components": self.components,
            "reoriented_tets": self.report.reoriented_tets,
            "unused_vertices": self.report.unused_vertices,
            "quality": {
                "min_dihedral_deg": q.min_dihedral_deg,
                "max_dihedral_deg": q.max_dihedral_deg,
                "min_volume": q.min_volume,
                "max_volume": q.max_volume,
                "mean_volume": q.mean_volume,
                "max_aspect_ratio": q.max_aspect_ratio,
                "mean_aspect_ratio": q.mean_aspect_ratio,
                "tets_below_5deg": q.tets_below_5deg,
            },
            "valid": self.problems.is_empty(),
            "problems": self.problems,
            "warnings": self.warnings,
        })
    }

    pub fn print_text(&self) {
        let q = &self.quality;
        let (lo, hi) = (self.bbox.min, self.bbox.max);
        println!(
            "vertices   {} ({} unused)",
            self.vertices, self.report.unused_vertices
        );
        println!(
            "tets       {} ({} re-oriented on reading)",
            self.tets, self.report.reoriented_tets
        );
        println!(
            "bbox       [{}, {}, {}] .. [{}, {}, {}]",
            lo.x, lo.y, lo.z, hi.x, hi.y, hi.z
        );
        println!("volume     {}", self.volume);
        println!(
            "boundary   {} faces, area {}",
            self.boundary_faces, self.boundary_area
        );
        println!("components {}", self.components);
        println!(
            "quality    dihedral {:.2}°..{:.2}°, {} tets below 5°; aspect ratio mean {:.3}, max {:.3}; volume {:e}..{:e}",
            q.min_dihedral_deg,
            q.max_dihedral_deg,
            q.tets_below_5deg,
            q.mean_aspect_ratio,
            q.max_aspect_ratio,
            q.min_volume,
            q.max_volume
        );
        if self.problems.is_empty() {
            println!("valid      yes");
        } else {
            println!("valid      NO");
            for p in &self.problems {
                println!("  problem: {p}");
            }
        }
        for w in &self.warnings {
            println!("  warning: {w}");
        }
    }
}

pub fn run(args: Args) -> CliResult {
    let (mesh, report) = match read_mesh(&args.mesh) {
        Ok(x) => x,
        Err(e) => {
            if args.json {
                // Scripts get a verdict on stdout too; the exit code still says failure.
                println!("{}", json!({"valid": false, "problems": [e.to_string()]}));
            }
            return Err(e.into());
        }
    };
    let info = MeshInfo::of(&mesh, report);
    if args.json {
        println!("{}", info.to_json());
    } else {
        println!("mesh       {}", args.mesh.display());
        info.print_text();
    }
    if info.problems.is_empty() {
        Ok(())
    } else {
        Err(format!("{} is not a valid mesh", args.mesh.display()).into())
    }
}
