//! Helpers shared by the I/O tests: test data paths, scratch directories, meshes with
//! attribute columns, and the bridge to VTK's Python (`scripts/vtk/vtu_tool.py`).
#![allow(dead_code)] // Each test crate uses its own subset.

use mtcut::io::read_mesh;
use mtcut::mesh::{Attribute, TetMesh};
use std::path::{Path, PathBuf};
use std::process::Command;

pub const MESHES: [&str; 3] = ["fandisk", "pinion", "liver"];

pub fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// A fresh scratch directory, removed when dropped.
pub struct Scratch(pub PathBuf);

impl Scratch {
    pub fn new(tag: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!("mtcut-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }

    pub fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A shared mesh read from its TetGen files.
pub fn tetgen_mesh(name: &str) -> TetMesh {
    read_mesh(data(&format!("{name}.node"))).unwrap().0
}

/// `mesh` with point data (a scalar and a 3-vector) and cell data (a scalar and a 9-tensor)
/// holding awkward doubles: values that need all 17 digits, tiny, huge and subnormal ones,
/// negative zero.
pub fn with_attributes(mut mesh: TetMesh) -> TetMesh {
    let special = [
        0.1,
        -0.0,
        1e-300,
        5e-324,
        f64::MAX,
        -1.0 / 3.0,
        2.0f64.sqrt(),
    ];
    let n = mesh.nb_vertices();
    let m = mesh.nb_tets();
    let temp: Vec<f64> = mesh
        .positions()
        .iter()
        .enumerate()
        .map(|(i, p)| {
            if i < special.len() {
                special[i]
            } else {
                p.x + 2.0 * p.y - p.z / 3.0
            }
        })
        .collect();
    let vel: Vec<f64> = mesh
        .positions()
        .iter()
        .flat_map(|p| [p.y, -p.x, p.z * 1e10])
        .collect();
    let region: Vec<f64> = (0..m).map(|t| (t % 7) as f64).collect();
    let tensor: Vec<f64> = (0..9 * m).map(|k| (k as f64).sin()).collect();
    assert_eq!(temp.len(), n);
    mesh.point_data
        .insert(Attribute::new("temperature", 1, temp).unwrap());
    mesh.point_data
        .insert(Attribute::new("velocity <m/s>", 3, vel).unwrap());
    mesh.cell_data
        .insert(Attribute::new("region", 1, region).unwrap());
    mesh.cell_data
        .insert(Attribute::new("stress", 9, tensor).unwrap());
    mesh
}

/// Asserts two meshes have bitwise-identical positions, identical tets, and identical
/// attribute columns (values compared bit for bit).
pub fn assert_same_mesh(a: &TetMesh, b: &TetMesh, what: &str) {
    assert_eq!(a.nb_vertices(), b.nb_vertices(), "{what}: vertex count");
    for (i, (p, q)) in a.positions().iter().zip(b.positions()).enumerate() {
        assert!(
            p.to_array().map(f64::to_bits) == q.to_array().map(f64::to_bits),
            "{what}: vertex {i}: {p} vs {q}"
        );
    }
    assert_eq!(a.tets(), b.tets(), "{what}: tets");
    for (kind, x, y) in [
        ("point", &a.point_data, &b.point_data),
        ("cell", &a.cell_data, &b.cell_data),
    ] {
        let names =
            |s: &mtcut::mesh::Attributes| s.iter().map(|c| c.name.clone()).collect::<Vec<_>>();
        assert_eq!(names(x), names(y), "{what}: {kind} data names");
        for (c, d) in x.iter().zip(y.iter()) {
            assert_eq!(
                c.components, d.components,
                "{what}: {kind} data '{}'",
                c.name
            );
            assert_same_values(
                &c.values,
                &d.values,
                &format!("{what}: {kind} data '{}'", c.name),
            );
        }
    }
}

pub fn assert_same_values(a: &[f64], b: &[f64], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: length");
    if let Some(k) = (0..a.len()).find(|&k| a[k].to_bits() != b[k].to_bits()) {
        panic!("{what}: value {k}: {} vs {}", a[k], b[k]);
    }
}

// ---- VTK's Python ------------------------------------------------------------------

pub const VTK_PYTHON: &str = "/usr/bin/python3";

/// Whether VTK's Python is usable. When it is not: under CI the test fails, otherwise it
/// prints why it is skipped and the caller returns.
pub fn vtk_available() -> bool {
    let ok = Command::new(VTK_PYTHON)
        .args(["-c", "import vtk, numpy"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        assert!(
            std::env::var_os("CI").is_none(),
            "VTK Python not found ({VTK_PYTHON} -c 'import vtk, numpy' failed) and CI is set"
        );
        eprintln!("skipped: VTK Python not found ({VTK_PYTHON} with vtk and numpy)");
    }
    ok
}

pub fn vtu_tool() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/vtk/vtu_tool.py")
}

/// Runs `vtu_tool.py ARGS`, panicking with its stderr on failure.
pub fn run_vtu_tool(args: &[&str]) -> String {
    let out = Command::new(VTK_PYTHON)
        .arg(vtu_tool())
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "vtu_tool.py {args:?} failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// What VTK read from one file, as dumped by `vtu_tool.py dump`.
pub struct VtkDump {
    pub points: Vec<f64>,
    pub points_type: String,
    pub connectivity: Vec<i64>,
    pub offsets: Vec<i64>,
    pub types: Vec<u8>,
    pub point_data: Vec<(String, usize, Vec<f64>)>,
    pub cell_data: Vec<(String, usize, Vec<f64>)>,
}

fn read_f64(path: &Path) -> Vec<f64> {
    std::fs::read(path)
        .unwrap()
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

fn read_i64(path: &Path) -> Vec<i64> {
    std::fs::read(path)
        .unwrap()
        .chunks_exact(8)
        .map(|c| i64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

impl VtkDump {
    pub fn load(dir: &Path) -> VtkDump {
        let manifest: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.join("manifest.json")).unwrap()).unwrap();
        let arrays = |key: &str| -> Vec<(String, usize, Vec<f64>)> {
            manifest[key]
                .as_array()
                .unwrap()
                .iter()
                .map(|a| {
                    (
                        a["name"].as_str().unwrap().to_string(),
                        a["components"].as_u64().unwrap() as usize,
                        read_f64(&dir.join(a["file"].as_str().unwrap())),
                    )
                })
                .collect()
        };
        VtkDump {
            points: read_f64(&dir.join("points.f64")),
            points_type: manifest["points_type"].as_str().unwrap().to_string(),
            connectivity: read_i64(&dir.join("connectivity.i64")),
            offsets: read_i64(&dir.join("offsets.i64")),
            types: std::fs::read(dir.join("types.u8")).unwrap(),
            point_data: arrays("point_data"),
            cell_data: arrays("cell_data"),
        }
    }

    /// Asserts that `mesh` holds exactly what VTK read: same points (bitwise), same cells
    /// (all tetrahedra, same vertex order except for the `reoriented` tets mtcut turned
    /// positive by swapping their last two vertices), same data arrays (bitwise, as f64).
    pub fn assert_matches(&self, mesh: &TetMesh, reoriented: usize, what: &str) {
        let flat: Vec<f64> = mesh.positions().iter().flat_map(|p| p.to_array()).collect();
        assert_same_values(&flat, &self.points, &format!("{what}: points"));
        assert_eq!(
            self.connectivity.len(),
            4 * mesh.nb_tets(),
            "{what}: connectivity length"
        );
        let mut swapped = 0;
        for (t, (ours, theirs)) in mesh
            .tets()
            .iter()
            .zip(self.connectivity.chunks_exact(4))
            .enumerate()
        {
            let ours = ours.map(|v| v.0 as i64);
            if ours != theirs {
                assert_eq!(
                    ours,
                    [theirs[0], theirs[1], theirs[3], theirs[2]],
                    "{what}: cell {t}"
                );
                swapped += 1;
            }
        }
        assert_eq!(swapped, reoriented, "{what}: re-oriented tets");
        let offsets: Vec<i64> = (1..=mesh.nb_tets() as i64).map(|k| 4 * k).collect();
        assert_eq!(offsets, self.offsets, "{what}: offsets");
        assert!(self.types.iter().all(|&t| t == 10), "{what}: cell types");
        assert_eq!(self.types.len(), mesh.nb_tets(), "{what}: cell count");
        for (kind, ours, theirs) in [
            ("point", &mesh.point_data, &self.point_data),
            ("cell", &mesh.cell_data, &self.cell_data),
        ] {
            assert_eq!(
                ours.iter().count(),
                theirs.len(),
                "{what}: number of {kind} arrays"
            );
            for (name, comps, values) in theirs {
                let a = ours
                    .get(name)
                    .unwrap_or_else(|| panic!("{what}: no {kind} data '{name}' in mtcut's mesh"));
                assert_eq!(
                    a.components, *comps,
                    "{what}: {kind} data '{name}' components"
                );
                assert_same_values(&a.values, values, &format!("{what}: {kind} data '{name}'"));
            }
        }
    }
}
