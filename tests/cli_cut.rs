//! `mtcut cut`: polygons applied in order, whole or separated output read back and checked
//! (validity, volume, components), JSON keys, and every bad-polygon class (non-zero exit,
//! a message naming the polygon and the problem, no panic, no file written).

mod cli_support;
mod common;

use cli_support::{close, fails, has_keys, json, ok, read_valid, s, stderr};
use common::{data, mtcut, scratch};
use mtcut::geom::DVec3;
use mtcut::mesh::TetMesh;
use serde_json::Value;

/// A square polygon `"x,y,z;..."` of half-side `r` around `c`, in the plane through `c`
/// normal to `axis` (0, 1, 2).
fn square(c: DVec3, axis: usize, r: f64) -> String {
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    [(-r, -r), (r, -r), (r, r), (-r, r)]
        .iter()
        .map(|&(a, b)| {
            let mut p = c;
            p[u] += a;
            p[v] += b;
            format!("{:?},{:?},{:?}", p.x, p.y, p.z)
        })
        .collect::<Vec<_>>()
        .join(";")
}

fn input(name: &str) -> TetMesh {
    mtcut::io::read_mesh(data(name)).unwrap().0
}

/// The horizontal plane through the liver's box centre, as the demo cuts it.
fn through_liver() -> String {
    let b = input("liver.node").bbox();
    square(b.center(), 2, b.diagonal())
}

fn sum(j: &Value) -> f64 {
    j.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .sum()
}

#[test]
fn cut_straight_through_separates_two_parts() {
    let dir = scratch("cli_cut through");
    let out = dir.join("parts.vtu");
    let before = input("liver.node");
    let j = json(&[
        "cut",
        s(&data("liver.node")),
        "--polygon",
        &through_liver(),
        "-o",
        s(&out),
        "--separate",
        "--json",
    ]);
    has_keys(
        &j,
        &[
            "input",
            "scheme",
            "input_tets",
            "input_vertices",
            "volume_before",
            "cuts",
            "tets",
            "vertices",
            "volume",
            "components",
            "component_tets",
            "component_volumes",
            "valid",
            "problems",
            "outputs",
            "seconds",
        ],
    );
    let cut = &j["cuts"][0];
    has_keys(
        cut,
        &[
            "polygon",
            "points",
            "scheme",
            "tets_tested",
            "tets_cut",
            "tets_cut_by_case",
            "tets_created",
            "vertices_added",
            "tets_after",
            "vertices_after",
            "components",
            "time_s",
        ],
    );
    assert!(cut["tets_cut"].as_u64().unwrap() > 100, "{cut}");
    assert_eq!(j["scheme"], "lut");
    assert_eq!(j["valid"], true);
    assert_eq!(j["components"], 2);
    assert_eq!(j["input_tets"], before.nb_tets());
    assert!(close(j["volume"].as_f64().unwrap(), before.volume(), 1e-12));
    assert!(close(sum(&j["component_volumes"]), before.volume(), 1e-12));
    assert_eq!(
        sum(&j["component_tets"]) as u64,
        j["tets"].as_u64().unwrap()
    );
    // Each part in its own file, read back: valid, one component, the reported size.
    let outputs = j["outputs"].as_array().unwrap();
    assert_eq!(outputs.len(), 2);
    let mut volume = 0.0;
    for (k, o) in outputs.iter().enumerate() {
        let path = dir.join(format!("parts-{k}.vtu"));
        assert_eq!(o.as_str().unwrap(), s(&path));
        let part = read_valid(&path);
        assert_eq!(
            part.nb_tets() as u64,
            j["component_tets"][k].as_u64().unwrap()
        );
        assert_eq!(mtcut::cut::Components::of(&part).count, 1);
        volume += part.volume();
        // A part lies on one side of the plane, up to the snapping distance (a fraction of
        // the local edge length): every tet whose centroid is farther from the plane than
        // its longest edge is on the part's side.
        let z = before.bbox().center().z;
        let (mut above, mut below) = (0, 0);
        for t in 0..part.nb_tets() {
            let p = part.tet_positions(mtcut::mesh::TetId::from_usize(t));
            let d = (p[0].z + p[1].z + p[2].z + p[3].z) / 4.0 - z;
            let longest = (0..4)
                .flat_map(|a| (a + 1..4).map(move |b| (a, b)))
                .map(|(a, b)| p[a].distance(p[b]))
                .fold(0.0, f64::max);
            if d > longest {
                above += 1;
            } else if d < -longest {
                below += 1;
            }
        }
        assert!(
            above == 0 || below == 0,
            "part {k} has {above} tets clearly above the plane and {below} clearly below"
        );
    }
    assert!(close(volume, before.volume(), 1e-12));
    assert!(!out.exists(), "--separate writes only the parts");
}

#[test]
fn polygons_are_applied_in_order() {
    let dir = scratch("cli_cut order");
    let out = dir.join("two.vtu");
    let b = input("liver.node").bbox();
    let first = through_liver();
    // A small vertical square around the centre, crossing the first cut and ending inside
    // the body: a partial cut.
    let second = square(b.center(), 0, 0.1 * b.diagonal());
    let j = json(&[
        "cut",
        s(&data("liver.node")),
        "--polygon",
        &first,
        "--polygon",
        &second,
        "-o",
        s(&out),
        "--json",
    ]);
    let cuts = j["cuts"].as_array().unwrap();
    assert_eq!(cuts.len(), 2);
    for (i, (c, text)) in cuts.iter().zip([&first, &second]).enumerate() {
        assert_eq!(c["polygon"], i);
        let first_corner: Vec<f64> = text
            .split(';')
            .next()
            .unwrap()
            .split(',')
            .map(|x| x.parse().unwrap())
            .collect();
        assert_eq!(c["points"][0].as_array().unwrap().len(), 3);
        // (serde_json's default parser may be off by an ulp; the writer is exact.)
        for (a, b) in c["points"][0].as_array().unwrap().iter().zip(first_corner) {
            assert!(close(a.as_f64().unwrap(), b, 1e-15), "{a} vs {b}");
        }
        assert!(c["tets_cut"].as_u64().unwrap() > 0, "polygon {i}: {c}");
    }
    // The second cut starts from the first's result.
    assert!(cuts[1]["tets_after"].as_u64() > cuts[0]["tets_after"].as_u64());
    assert_eq!(cuts[1]["tets_after"], j["tets"]);
    assert_eq!(j["valid"], true);
    let mesh = read_valid(&out);
    assert_eq!(mesh.nb_tets() as u64, j["tets"].as_u64().unwrap());
    assert!(close(mesh.volume(), input("liver.node").volume(), 1e-12));
    // The reported parts are the written mesh's (at least the first cut's two: where the
    // body is thin, the slit may cut off a small piece between itself and the first cut).
    let parts = mtcut::cut::Components::of(&mesh);
    assert_eq!(j["components"], parts.count);
    assert!(parts.count >= 2);
    assert_eq!(j["cuts"][1]["components"], parts.count);
    let cut_column = mesh
        .cell_data
        .get(mtcut::cut::CUT_COLUMN)
        .expect("cut column");
    let max = cut_column.values.iter().fold(0.0f64, |m, &x| m.max(x));
    assert_eq!(max, 2.0, "tets of the second cut are marked 2");
}

#[test]
fn text_output_and_tetgen_parts() {
    let dir = scratch("cli_cut text");
    let out = dir.join("p.node");
    let text = ok(&[
        "cut",
        s(&data("liver.node")),
        "--polygon",
        &through_liver(),
        "-o",
        s(&out),
        "--separate",
    ]);
    for needle in ["polygon 0", "tets cut", "components 2", "wrote", "time"] {
        assert!(text.contains(needle), "lacks '{needle}': {text}");
    }
    for k in 0..2 {
        read_valid(&dir.join(format!("p-{k}.node")));
        assert!(dir.join(format!("p-{k}.ele")).exists());
    }
}

#[test]
fn bielser17_makes_more_tets_and_says_it_is_not_conforming() {
    let dir = scratch("cli_cut bielser");
    let p = through_liver();
    let lut = json(&[
        "cut",
        s(&data("liver.node")),
        "--polygon",
        &p,
        "-o",
        s(&dir.join("lut.vtu")),
        "--json",
    ]);
    let b17 = json(&[
        "cut",
        s(&data("liver.node")),
        "--polygon",
        &p,
        "--scheme",
        "bielser17",
        "-o",
        s(&dir.join("b17.vtu")),
        "--json",
    ]);
    assert_eq!(b17["scheme"], "bielser17");
    let per_cut = |j: &Value| {
        j["cuts"][0]["tets_created"].as_f64().unwrap() / j["cuts"][0]["tets_cut"].as_f64().unwrap()
    };
    assert_eq!(per_cut(&b17), 17.0);
    assert!(
        per_cut(&lut) < 0.5 * 17.0,
        "tables: {} per cut tet",
        per_cut(&lut)
    );
    assert!(close(
        b17["volume"].as_f64().unwrap(),
        b17["volume_before"].as_f64().unwrap(),
        1e-12
    ));
    assert_eq!(b17["valid"], false, "the 1:17 scheme is not conforming");
    assert!(dir.join("b17.vtu").exists());
}

#[test]
fn a_polygon_missing_the_mesh_changes_nothing_and_warns() {
    let dir = scratch("cli_cut miss");
    let out = dir.join("same.vtu");
    let far = square(DVec3::new(1e4, 1e4, 1e4), 2, 1.0);
    let o = mtcut(&[
        "cut",
        s(&data("pinion-coarse.node")),
        "--polygon",
        &far,
        "-o",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("polygon 0 does not cut the mesh"),
        "{}",
        stderr(&o)
    );
    let mesh = read_valid(&out);
    assert_eq!(mesh.nb_tets(), input("pinion-coarse.node").nb_tets());
}

/// A polygon lying exactly on an interior face of pinion-coarse (nodes 198, 199, 223)
/// cuts no tet but opens faces (their vertices are copied), which separates a part: no
/// "does not cut" warning (found probing the CLI: it warned).
#[test]
fn a_polygon_along_faces_separates_them_without_a_warning() {
    let dir = scratch("cli_cut along faces");
    let out = dir.join("opened.vtu");
    let polygon = "0.270867,-0.145307,-0.691252;-0.556875,-0.459357,-0.226262;\
                   -0.530377,-0.501178,-0.207338";
    let input = data("pinion-coarse.node");
    let o = mtcut(&["cut", s(&input), "--polygon", polygon, "-o", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("does not cut"), "{}", stderr(&o));
    let args = [
        "cut",
        s(&input),
        "--polygon",
        polygon,
        "-o",
        s(&out),
        "--json",
    ];
    let j = json(&args);
    assert_eq!(j["cuts"][0]["tets_cut"], 0, "{j}");
    assert!(j["cuts"][0]["vertex_copies"].as_u64() > Some(0), "{j}");
    assert_eq!(j["components"], 2, "{j}");
    read_valid(&out);
}

// ---- bad input ----

#[test]
fn bad_polygons_are_named_and_nothing_is_written() {
    let dir = scratch("cli_cut bad polygons");
    let out = dir.join("never.vtu");
    let good = "0,0,0;1,0,0;0,1,0";
    let mesh = data("pinion-coarse.node");
    let cases: &[(&str, &[&str])] = &[
        ("0,0,0;1,0,0", &["at least 3 points, got 2"]),
        ("0,0,0", &["at least 3 points, got 1"]),
        ("0,0,0;1,0,0;2,0,0", &["degenerate"]),
        ("0,0,0;1,1,1;2,2,2;3,3,3", &["degenerate"]),
        ("0,0,0;1,0,0;1,1,0.5;0,1,0", &["not planar"]),
        ("0,0,0;1,0,0;0.2,0.2,0;0,1,0", &["not convex at point 2"]),
        ("0,0,0;1,1,0;1,0,0;0,1,0", &["degenerate"]),
        (
            "0,1,0;-0.588,-0.809,0;0.951,0.309,0;-0.951,0.309,0;0.588,-0.809,0",
            &["not convex", "winds more than once"],
        ),
        ("0,0,0;nan,0,0;0,1,0", &["point 1", "NaN"]),
        ("0,0,0;1,0,0;0,inf,0", &["point 2", "infinite"]),
        ("0,0,0;1,0;0,1,0", &["point 1", "expected 3"]),
        ("0,0,0;1,0,0,4;0,1,0", &["point 1", "expected 3"]),
        ("0,0,0;1,x,0;0,1,0", &["point 1", "'x' is not a number"]),
        ("", &["point 0 is empty"]),
        ("0,0,0;1,0,0;0,1,0;", &["point 3 is empty"]),
        ("0,0,0;0,0,0;0,1,0", &["points 0 and 1 are the same"]),
    ];
    for (bad, needles) in cases {
        // The bad polygon second: the message must name it, not the good one.
        let args = [
            "cut",
            s(&mesh),
            "--polygon",
            good,
            "--polygon",
            bad,
            "-o",
            s(&out),
        ];
        let err = fails(&args, needles);
        assert!(err.contains("polygon 1 (2nd of 2"), "{bad:?}: {err}");
        assert!(err.contains(&format!("\"{bad}\"")), "{bad:?}: {err}");
        assert!(!out.exists(), "{bad:?} wrote {}", out.display());
        let mut json_args = args.to_vec();
        json_args.push("--json");
        fails(&json_args, needles);
        assert!(!out.exists());
        let mut sep = args.to_vec();
        sep.push("--separate");
        fails(&sep, needles);
        assert!(!dir.join("never-0.vtu").exists());
    }
    // The first polygon bad: named as such.
    fails(
        &[
            "cut",
            s(&data("pinion-coarse.node")),
            "--polygon",
            "1,2",
            "-o",
            s(&out),
        ],
        &["polygon 0 (1st of 1, \"1,2\")", "expected 3"],
    );
    // Too many corners: the message quotes the start of the text, not all of it.
    let many: Vec<String> = (0..5000)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 5000.0;
            format!("{:.6},{:.6},0.1", a.cos(), a.sin())
        })
        .collect();
    let err = fails(
        &["cut", s(&mesh), "--polygon", &many.join(";"), "-o", s(&out)],
        &["at most 4096 points, got 5000", "characters)"],
    );
    assert!(err.len() < 400, "{err}");
    // Text that is not numbers is bad usage (2), numbers that are no polygon bad input (1).
    for (bad, code) in [
        ("a,b,c;1,0,0;0,1,0", 2),
        ("1,2", 2),
        ("0,0,0;1,0,0;2,0,0", 1),
    ] {
        let o = mtcut(&["cut", s(&mesh), "--polygon", bad, "-o", s(&out)]);
        assert_eq!(o.status.code(), Some(code), "{bad}: {}", stderr(&o));
    }
}

#[test]
fn cut_rejects_bad_usage_and_files() {
    let dir = scratch("cli_cut bad usage");
    let out = dir.join("never.vtu");
    let o = s(&out);
    let m = data("pinion-coarse.node");
    let good = "0,0,0;1,0,0;0,1,0";
    fails(&["cut", s(&m), "-o", o], &["--polygon"]);
    fails(&["cut", s(&m), "--polygon", good], &["--output"]);
    fails(
        &["cut", s(&m), "--polygon", good, "--scheme", "1:17", "-o", o],
        &["--scheme", "1:17"],
    );
    fails(
        &["cut", s(&dir.join("none.node")), "--polygon", good, "-o", o],
        &["none.node"],
    );
    fails(
        &["cut", s(&m), "--polygon", good, "-o", s(&dir.join("x.obj"))],
        &["x.obj", "unknown output format"],
    );
    assert!(!out.exists());
    fails(
        &[
            "cut",
            s(&m),
            "--polygon",
            good,
            "-o",
            s(&dir.join("no/dir/x.vtu")),
        ],
        &["x.vtu"],
    );
}

#[test]
fn cut_of_an_extracted_level_keeps_the_mt_data() {
    // A mesh extracted from a model can be cut like any mesh; its cell data are inherited.
    let dir = scratch("cli_cut extracted");
    let model = dir.join("p.mt");
    ok(&[
        "build",
        s(&data("pinion-coarse.node")),
        "-o",
        s(&model),
        "--quiet",
    ]);
    let level = dir.join("level.vtu");
    ok(&["extract", s(&model), "--level", "coarsest", "-o", s(&level)]);
    let b = read_valid(&level).bbox();
    let out = dir.join("cut.vtu");
    let j = json(&[
        "cut",
        s(&level),
        "--polygon",
        &square(b.center(), 0, b.diagonal()),
        "-o",
        s(&out),
        "--json",
    ]);
    assert_eq!(j["valid"], true);
    let mesh = read_valid(&out);
    assert!(mesh.cell_data.get(mtcut::mt::CELL_FRAGMENT).is_some());
    assert!(close(
        mesh.volume(),
        j["volume_before"].as_f64().unwrap(),
        1e-12
    ));
}

#[test]
fn scalpel_sweeps_continue_their_crack() {
    // A vertical blade moving along an arc through the liver, 8° per step, from outside
    // the body to outside: its sweeps given in order with --scalpel cut a corner off (two
    // parts, the mesh valid); a model refuses --scalpel.
    use mtcut::geom::{Tolerance, scalpel_sweep};
    let dir = scratch("cli_cut scalpel");
    let b = input("liver.node").bbox();
    let (c, d) = (b.center(), b.max - b.min);
    let r = 0.6 * d.x.max(d.y);
    let centre = DVec3::new(b.min.x - 0.1 * d.x, c.y - r, c.z);
    let blade = |k: usize| {
        let a = (98.0 - 8.0 * k as f64).to_radians();
        let p = centre + DVec3::new(r * a.cos(), r * a.sin(), 0.0);
        [
            DVec3::new(p.x, p.y, b.min.z - 0.1 * d.z),
            DVec3::new(p.x, p.y, b.max.z + 0.1 * d.z),
        ]
    };
    let mut polygons: Vec<String> = Vec::new();
    for k in 0..16 {
        for p in scalpel_sweep(blade(k), blade(k + 1), Tolerance { relative: 1e-9 }).unwrap() {
            let corners: Vec<String> = p
                .points()
                .iter()
                .map(|q| format!("{:?},{:?},{:?}", q.x, q.y, q.z))
                .collect();
            polygons.push(corners.join(";"));
        }
    }
    let (out, liver) = (dir.join("scalpel.vtu"), data("liver.node"));
    let mut args = vec!["cut", s(&liver)];
    for p in &polygons {
        args.extend_from_slice(&["--polygon", p]);
    }
    args.extend_from_slice(&["--scalpel", "-o", s(&out), "--json"]);
    let j = json(&args);
    assert_eq!(j["valid"], true);
    assert_eq!(j["components"], 2, "the corner did not come off");
    let mesh = read_valid(&out);
    assert_eq!(mtcut::cut::Components::of(&mesh).count, 2);
    assert!(close(mesh.volume(), input("liver.node").volume(), 1e-12));

    let model = dir.join("liver.mt");
    ok(&["build", s(&data("liver.node")), "-o", s(&model), "--quiet"]);
    fails(
        &[
            "cut",
            s(&model),
            "--polygon",
            &polygons[0],
            "--scalpel",
            "-o",
            s(&dir.join("cut.mt")),
        ],
        &["--scalpel", "mtcut scalpel", "nothing written"],
    );
    assert!(!dir.join("cut.mt").exists());
}

/// `--separate` writes all parts or none: a part that cannot be written (here its name is
/// taken by a folder) leaves none of the others behind (part 0 was left before).
#[test]
fn separate_parts_are_written_all_or_none() {
    let dir = scratch("cli_cut separate all or none");
    let out = dir.join("part.vtu");
    std::fs::create_dir(dir.join("part-1.vtu")).unwrap();
    let through = square(DVec3::new(0.0, 0.0, 0.1), 2, 2.0);
    let input = data("pinion-coarse.node");
    let args = [
        "cut",
        s(&input),
        "--polygon",
        &through,
        "-o",
        s(&out),
        "--separate",
    ];
    fails(&args, &["part-1.vtu"]);
    assert!(!dir.join("part-0.vtu").exists(), "part 0 was written");
    std::fs::remove_dir(dir.join("part-1.vtu")).unwrap();
    ok(&args);
    for k in 0..2 {
        read_valid(&dir.join(format!("part-{k}.vtu")));
    }
}
