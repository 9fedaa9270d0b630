//! Parsers for the numbers and points given on the command line. Each error names the
//! text it could not use and what was expected; clap prefixes the option's name.

use mtcut::geom::DVec3;

/// One number: anything Rust's `f64` parser accepts (so also `inf` and `nan`, which the
/// callers then judge).
fn number(text: &str) -> Result<f64, String> {
    let t = text.trim();
    t.parse::<f64>()
        .map_err(|_| format!("'{t}' is not a number"))
}

/// An error threshold: a number ≥ 0, `inf` allowed (the coarsest mesh).
pub fn threshold(text: &str) -> Result<f64, String> {
    let x = number(text)?;
    if x >= 0.0 {
        Ok(x)
    } else {
        // NaN lands here too: it is not ≥ 0.
        Err(format!(
            "{x} is not a valid error threshold (expected a number ≥ 0)"
        ))
    }
}

/// A scalpel's `--min-advance`: a finite number ≥ 0 (of median edge lengths).
pub fn min_advance(text: &str) -> Result<f64, String> {
    let x = number(text)?;
    if x.is_finite() && x >= 0.0 {
        Ok(x)
    } else {
        Err(format!(
            "{x} is not a valid advance (expected a finite number ≥ 0 of median edge lengths)"
        ))
    }
}

/// A positive whole number (a tet count).
pub fn count(text: &str) -> Result<usize, String> {
    let t = text.trim();
    match t.parse::<usize>() {
        Ok(0) => Err("0 tets: expected at least 1".to_string()),
        Ok(n) => Ok(n),
        Err(_) => Err(format!("'{t}' is not a whole number ≥ 1")),
    }
}

/// A relative tolerance: a finite number ≥ 0.
pub fn tolerance(text: &str) -> Result<f64, String> {
    let x = number(text)?;
    if x.is_finite() && x >= 0.0 {
        Ok(x)
    } else {
        Err(format!(
            "{x} is not a valid tolerance (expected a finite number ≥ 0)"
        ))
    }
}

/// `x,y,z`, exactly three comma-separated numbers (not checked for finiteness: the polygon
/// check reports NaN and infinite coordinates with the point's index).
pub fn point(text: &str) -> Result<DVec3, String> {
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() != 3 {
        return Err(format!(
            "'{}' has {} coordinate(s), expected 3 as x,y,z",
            text.trim(),
            parts.len()
        ));
    }
    let mut c = [0.0; 3];
    for (k, p) in parts.iter().enumerate() {
        c[k] = number(p)?;
    }
    Ok(DVec3::from_array(c))
}

/// A focus sphere `x,y,z,r`: finite centre, finite radius ≥ 0.
#[derive(Clone, Copy, Debug)]
pub struct Sphere {
    pub center: DVec3,
    pub radius: f64,
}

/// Exactly `n` comma-separated numbers; `layout` says what they are, for the error.
fn numbers(text: &str, n: usize, layout: &str) -> Result<Vec<f64>, String> {
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() != n {
        return Err(format!(
            "'{}' has {} number(s), expected {n} as {layout}",
            text.trim(),
            parts.len()
        ));
    }
    parts.iter().map(|p| number(p)).collect()
}

pub fn sphere(text: &str) -> Result<Sphere, String> {
    let v = numbers(text, 4, "x,y,z,r (centre and radius)")?;
    let center = DVec3::new(v[0], v[1], v[2]);
    let radius = v[3];
    if !center.is_finite() {
        return Err(format!("centre {center} is not finite"));
    }
    if !(radius.is_finite() && radius >= 0.0) {
        return Err(format!("radius {radius} (expected a finite number ≥ 0)"));
    }
    Ok(Sphere { center, radius })
}

/// A sphere bounding a region of interest: as [`sphere`], with a radius above 0 (a focus
/// sphere of radius 0 is a point; a region of radius 0 holds nothing).
pub fn region_sphere(text: &str) -> Result<Sphere, String> {
    let s = sphere(text)?;
    if s.radius > 0.0 {
        Ok(s)
    } else {
        Err(format!("radius {} (a region needs a radius > 0)", s.radius))
    }
}

/// A box `x0,y0,z0,x1,y1,z1`: six numbers, the min and max corners (whether it is
/// finite and not empty is judged by the caller, which names the box).
pub fn aabb(text: &str) -> Result<mtcut::geom::Aabb, String> {
    let v = numbers(text, 6, "x0,y0,z0,x1,y1,z1 (min and max corners)")?;
    Ok(mtcut::geom::Aabb {
        min: DVec3::new(v[0], v[1], v[2]),
        max: DVec3::new(v[3], v[4], v[5]),
    })
}

/// A polygon `x,y,z;x,y,z;...`: its corners, in order. Errors name the 0-based point.
pub fn corners(text: &str) -> Result<Vec<DVec3>, String> {
    let mut out = Vec::new();
    for (i, p) in text.split(';').enumerate() {
        if p.trim().is_empty() {
            return Err(format!(
                "point {i} is empty (corners are x,y,z separated by ';')"
            ));
        }
        out.push(point(p).map_err(|e| format!("point {i}: {e}"))?);
    }
    Ok(out)
}

/// Checks, before any work is done, that `path` names a mesh format `write_mesh` writes
/// (.vtu or .node/.ele), so a long build or cut does not end in "unknown format".
pub fn mesh_output(path: &std::path::Path) -> Result<(), String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "vtu" | "node" | "ele" => in_a_directory(path),
        _ => Err(format!(
            "{}: unknown output format (expected .vtu, or .node/.ele)",
            path.display()
        )),
    }
}

/// Checks that a model is not about to be written under a mesh's name: `.mt` files are
/// mtcut's own format, and a `.vtu` (or `.node`, `.ele`, `.mesh`) name would make it look
/// like a mesh to other tools.
pub fn model_output(path: &std::path::Path) -> Result<(), String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "vtu" | "node" | "ele" | "mesh" => Err(format!(
            "{}: a model is written in mtcut's own format, not as a .{ext} mesh: name it .mt \
             (use `mtcut extract` for meshes)",
            path.display()
        )),
        _ => in_a_directory(path),
    }
}

/// Checks that the folder an output goes to exists, so that a long run (a scalpel's
/// hundred steps) does not end in "No such file or directory".
fn in_a_directory(path: &std::path::Path) -> Result<(), String> {
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() && !dir.is_dir() => Err(format!(
            "{}: the folder {} does not exist",
            path.display(),
            dir.display()
        )),
        _ => Ok(()),
    }
}

/// Checks, before any work is done, that `dir` can be the folder of a run's outputs: a
/// folder, or nothing yet (it is then created, with its parents). A file there would make
/// the run fail only when it writes, after all its work, with the system's "File exists".
pub fn output_folder(dir: &std::path::Path) -> Result<(), String> {
    if dir.exists() && !dir.is_dir() {
        return Err(format!(
            "{}: exists and is not a folder (the outputs go into a folder; give a new name \
             or an existing folder)",
            dir.display()
        ));
    }
    std::fs::create_dir_all(dir)
        .map_err(|e| format!("{}: cannot create the folder: {e}", dir.display()))
}

/// An `.mt` model: loading validates it ([`mtcut::mt::Mt::validate`]), so commands that
/// write from a model never start from a broken one.
pub fn valid_model(path: &std::path::Path) -> Result<mtcut::mt::Mt, Box<dyn std::error::Error>> {
    Ok(mtcut::mt::Mt::load(path)?)
}
