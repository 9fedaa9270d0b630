//! `mtcut info MESH|MODEL.mt [--json]`: a mesh's numbers and validity, or an MT model's
//! summary (a file is taken as a model when it starts with the `.mt` magic bytes or is
//! named `*.mt`).

use crate::CliResult;
use mtcut::geom::Aabb;
use mtcut::io::read_mesh;
use mtcut::mesh::{ImportReport, QualitySummary, Severity, TetMesh};
use mtcut::mt::{MT_FILE_VERSION, MT_MAGIC, Mt, MtSummary};
use serde_json::{Value, json};
use std::io::Read;
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
pub struct Args {
    /// The mesh (.vtu, .node/.ele, .mesh) or model (.mt).
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

    pub fn print_text(&self) -> crate::CliResult {
        let q = &self.quality;
        let (lo, hi) = (self.bbox.min, self.bbox.max);
        out!(
            "vertices   {} ({} unused)",
            self.vertices,
            self.report.unused_vertices
        );
        out!(
            "tets       {} ({} re-oriented on reading)",
            self.tets,
            self.report.reoriented_tets
        );
        out!("bbox       {}", bbox_text(lo, hi));
        out!("volume     {}", crate::number(self.volume));
        out!(
            "boundary   {} faces, area {}",
            self.boundary_faces,
            crate::number(self.boundary_area)
        );
        out!("components {}", self.components);
        out!(
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
            out!("valid      yes");
        } else {
            out!("valid      NO");
            for p in &self.problems {
                out!("  problem: {p}");
            }
        }
        for w in &self.warnings {
            out!("  warning: {w}");
        }
        Ok(())
    }
}

/// Whether `path` is to be read as an `.mt` model: by its first bytes, or by its name when
/// it cannot be read (so a missing `x.mt` is reported by the model loader).
pub fn is_model(path: &Path) -> bool {
    let mut head = [0u8; 8];
    match std::fs::File::open(path).and_then(|mut f| f.read_exact(&mut head)) {
        Ok(()) if head == MT_MAGIC => true,
        _ => path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("mt")),
    }
}

/// The format version in the header of the model file at `path` (one `Mt::load` read).
fn file_version(path: &Path) -> std::io::Result<u32> {
    let mut head = [0u8; 12];
    std::fs::File::open(path).and_then(|mut f| f.read_exact(&mut head))?;
    Ok(u32::from_le_bytes([head[8], head[9], head[10], head[11]]))
}

/// Everything `info` reports about a model: a loaded one, which loading validated
/// exhaustively (`Mt::load` refuses an invalid model; `run_model` reports that).
struct ModelInfo {
    summary: MtSummary,
    file_version: u32,
}

impl ModelInfo {
    fn of(mt: &Mt, file_version: u32) -> ModelInfo {
        ModelInfo {
            summary: mt.summary(),
            file_version,
        }
    }

    fn to_json(&self) -> Value {
        let mut j = self.summary.to_json();
        if let Some(o) = j.as_object_mut() {
            o.insert("kind".into(), json!("mt"));
            o.insert("file_version".into(), json!(self.file_version));
            o.insert("valid".into(), json!(true));
            o.insert("problems".into(), json!([]));
        }
        j
    }

    fn print_text(&self) -> crate::CliResult {
        let s = &self.summary;
        let i = &s.info;
        let (lo, hi) = (s.bbox.min, s.bbox.max);
        out!(
            "format     mtcut model, file version {}{}",
            self.file_version,
            if self.file_version < MT_FILE_VERSION {
                format!(" (written before version {MT_FILE_VERSION}: no cut record)")
            } else {
                String::new()
            }
        );
        out!("vertices   {}", s.vertices);
        out!(
            "tets       {} over all levels (plus {} ghost tets), {} arcs",
            s.pool_tets,
            s.ghost_tets,
            s.arcs
        );
        out!(
            "fragments  {} (DAG depth {}), {} component(s)",
            s.fragments,
            s.dag_depth,
            s.components
        );
        out!(
            "finest     {} tets; coarsest {} tets ({:.1}%)",
            s.finest_tets,
            s.coarsest_tets,
            100.0 * s.coarsest_tets as f64 / s.finest_tets.max(1) as f64
        );
        out!(
            "error      {} metric, collapse errors {:e} .. {:e}",
            i.error_metric,
            s.min_error,
            s.max_error
        );
        out!(
            "build      boundary tolerance {} of the diagonal, features {} (angle {}°)",
            i.boundary_tolerance,
            if i.preserve_features {
                "kept"
            } else {
                "not kept"
            },
            i.feature_angle_degrees
        );
        out!("bbox       {}", bbox_text(lo, hi));
        let cuts = &i.cuts;
        if cuts.cut_vertices_from() < s.vertices {
            out!(
                "cuts       vertices {}.. made by cuts; the last {} recorded (a cut \
                 continuing one at an angle reads them); {} crack plane(s) (a cut close to \
                 one is made in it)",
                cuts.cut_vertices_from(),
                cuts.cuts_kept(),
                cuts.planes_kept()
            );
        } else {
            out!("cuts       none");
        }
        out!(
            "memory     {} bytes ({:.1} per input tet)",
            s.heap_bytes,
            s.bytes_per_input_tet
        );
        out!("valid      yes (every invariant checked on loading)");
        Ok(())
    }
}

fn run_model(args: &Args) -> CliResult {
    let mt = match Mt::load(&args.mesh) {
        Ok(mt) => mt,
        Err(e) => {
            if args.json {
                out!("{}", json!({"valid": false, "problems": [e.to_string()]}));
            }
            return Err(e.into());
        }
    };
    let info = ModelInfo::of(&mt, file_version(&args.mesh)?);
    if args.json {
        out!("{}", info.to_json());
    } else {
        out!("model      {}", args.mesh.display());
        info.print_text()?;
    }
    Ok(())
}

pub fn run(args: Args) -> CliResult {
    if is_model(&args.mesh) {
        return run_model(&args);
    }
    let (mesh, report) = match read_mesh(&args.mesh) {
        Ok(x) => x,
        Err(e) => {
            if args.json {
                // Scripts get a verdict on stdout too; the exit code still says failure.
                out!("{}", json!({"valid": false, "problems": [e.to_string()]}));
            }
            return Err(e.into());
        }
    };
    let info = MeshInfo::of(&mesh, report);
    if args.json {
        out!("{}", info.to_json());
    } else {
        out!("mesh       {}", args.mesh.display());
        info.print_text()?;
    }
    if info.problems.is_empty() {
        Ok(())
    } else {
        Err(format!("{} is not a valid mesh", args.mesh.display()).into())
    }
}

/// `[x, y, z] .. [x, y, z]`, as both reports print a box.
fn bbox_text(lo: mtcut::geom::DVec3, hi: mtcut::geom::DVec3) -> String {
    let [a, b, c, d, e, f] = [lo.x, lo.y, lo.z, hi.x, hi.y, hi.z].map(crate::number);
    format!("[{a}, {b}, {c}] .. [{d}, {e}, {f}]")
}
