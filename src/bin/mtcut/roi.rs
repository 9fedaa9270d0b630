//! `mtcut roi MODEL.mt (--box x0,y0,z0,x1,y1,z1 | --sphere x,y,z,r) -o SUB.mt [--json]`:
//! the model restricted to a region of interest (paper §7), everything outside omitted:
//! every level of a copy is cut along the region's bounding planes and the independent
//! components inside are kept ([`mtcut::cut::region_of_interest`]). The input must be a
//! valid model; the sub-model is validated before it is written.

use crate::CliResult;
use crate::parse::{self, Sphere};
use mtcut::cut::{RoiRegion, region_of_interest};
use mtcut::geom::Aabb;
use serde_json::json;
use std::path::PathBuf;
use std::time::Instant;

/// Exactly one region.
#[derive(clap::Args, Debug)]
#[group(required = true, multiple = false)]
pub struct Region {
    /// An axis-aligned box: min corner x0,y0,z0 and max corner x1,y1,z1.
    #[arg(long = "box", value_name = "x0,y0,z0,x1,y1,z1", allow_hyphen_values = true, value_parser = parse::aabb)]
    aabb: Option<Aabb>,
    /// A sphere (centre x,y,z and radius r), bounded by a circumscribing polyhedron of 14
    /// planes: the sub-model also keeps what lies between the sphere and that polyhedron.
    #[arg(long, value_name = "x,y,z,r", allow_hyphen_values = true, value_parser = parse::region_sphere)]
    sphere: Option<Sphere>,
}

#[derive(clap::Args)]
pub struct Args {
    /// The model (.mt).
    model: PathBuf,
    #[command(flatten)]
    region: Region,
    /// The sub-model to write (.mt).
    #[arg(short, long)]
    output: PathBuf,
    /// Print the statistics as one JSON object.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> CliResult {
    parse::model_output(&args.output)?;
    let region = match (args.region.aabb, args.region.sphere) {
        (Some(b), _) => RoiRegion::Box(b),
        (None, Some(s)) => RoiRegion::Sphere {
            center: s.center,
            radius: s.radius,
        },
        (None, None) => return Err("give the region: --box or --sphere".into()),
    };
    let t_load = Instant::now();
    let mt = parse::valid_model(&args.model)?;
    let load_seconds = t_load.elapsed().as_secs_f64();
    let (sub, stats) = region_of_interest(&mt, &region)
        .map_err(|e| format!("{}: {e}; nothing written", args.model.display()))?;
    let t_write = Instant::now();
    sub.save(&args.output)?;
    let write_seconds = t_write.elapsed().as_secs_f64();
    if args.json {
        let mut j = stats.to_json();
        j["input"] = json!(args.model.display().to_string());
        j["output"] = json!(args.output.display().to_string());
        j["components"] = json!(sub.nb_components());
        j["vertices"] = json!(sub.nb_vertices());
        j["valid"] = json!(true);
        j["seconds_load"] = json!(load_seconds);
        j["seconds_write"] = json!(write_seconds);
        out!("{j}");
        return Ok(());
    }
    out!(
        "roi        {} planes, {} cut the model; kept {} component(s), dropped {}",
        stats.planes,
        stats.planes_cut,
        stats.components_kept,
        stats.components_dropped
    );
    out!(
        "sub-model  {} tets in the MT (input {}), {} fragments (input {}), {} vertices, valid",
        stats.tets_after,
        stats.tets_before,
        stats.fragments_after,
        stats.fragments_before,
        sub.nb_vertices()
    );
    out!(
        "time       {:.3} s (load {:.3} s, write {:.3} s) -> {}",
        stats.seconds + load_seconds + write_seconds,
        load_seconds,
        write_seconds,
        args.output.display()
    );
    Ok(())
}
