//! A scalpel moved in steps through a plain mesh (issue 4's sequences of cuts crossing
//! earlier cuts; issue 7's progressive scalpel on the simulation's mesh): each step cuts
//! the area the blade swept since the last, with [`CutOptions::SCALPEL`], and must continue
//! the crack the earlier steps made. After every step the mesh is valid and keeps its
//! volume; a blade that crosses the body leaves exactly two parts (no bridge of material
//! left at a step boundary, no chip cut loose between two steps); one that stops inside
//! leaves one. Straight, turning and tilting blades, steps of every length (7 to 100 steps
//! across the body: from many tets per step to less than one), an incision stopped inside
//! and extended, and incisions meeting (T) or crossing (X) an earlier one, on the three
//! shared meshes; and seeded random paths (turning, leaning, through or stopping inside,
//! steps of 0.2% to 5% of the diagonal) with no cut refused.

mod blades;
mod cut_common;

use blades::{random_path, shallow_path, tilting, vertical};
use cut_common::{MESHES, mesh};
use mtcut::cut::{
    Blade, Components, CutOptions, Cutter, Incision, MIN_FACE_POINT_MARGIN, ScalpelError,
    blade_advance,
};
use mtcut::geom::{Aabb, CutPolygon, DVec3, Tolerance, scalpel_sweep};

struct Run {
    name: &'static str,
    cutter: Cutter,
    volume: f64,
    steps: usize,
}

impl Run {
    fn new(name: &'static str, options: CutOptions) -> Run {
        let input = mesh(name);
        Run {
            name,
            cutter: Cutter::new(input.clone(), options.with_count_components(false))
                .expect("options"),
            volume: input.volume(),
            steps: 0,
        }
    }

    fn bounds(&self) -> Aabb {
        self.cutter.mesh().bbox()
    }

    /// Moves the blade through `path`, one sweep per consecutive pair, checking the mesh
    /// after each.
    fn sweep(&mut self, what: &str, path: &[Blade]) {
        for w in path.windows(2) {
            let sweep = scalpel_sweep(w[0], w[1], Tolerance { relative: 1e-9 })
                .unwrap_or_else(|e| panic!("{} {what}: sweep: {e}", self.name));
            for polygon in &sweep {
                self.cutter
                    .cut(polygon)
                    .unwrap_or_else(|e| panic!("{} {what}: cut refused: {e}", self.name));
            }
            self.steps += 1;
            self.check(&format!("{what}, step {}", self.steps));
        }
    }

    /// The mesh is valid and keeps its volume.
    fn check(&self, what: &str) {
        let report = self.cutter.mesh().validate();
        assert!(report.is_valid(), "{} {what}: {report}", self.name);
        let v = self.cutter.mesh().volume();
        assert!(
            (v - self.volume).abs() <= 1e-12 * self.volume,
            "{} {what}: volume {v}, was {}",
            self.name,
            self.volume
        );
    }

    /// The parts, found through faces and (as the cutter counts them) through vertices
    /// alike.
    fn parts(&self) -> usize {
        let parts = Components::of(self.cutter.mesh());
        assert!(
            Components::through_vertices(self.cutter.mesh()) == parts,
            "{}: the components through vertices differ from those through faces",
            self.name
        );
        parts.count
    }
}

/// A slightly tilted blade (its plane leans in y) crossing the body in x in `steps` steps.
fn straight_path(b: &Aabb, steps: usize) -> Vec<Blade> {
    let (c, d) = (b.center(), b.max - b.min);
    (0..=steps)
        .map(|k| {
            let x = b.min.x - 0.01 * d.x + 1.02 * d.x * k as f64 / steps as f64;
            [
                DVec3::new(x, c.y + 0.013 * d.y, b.min.z - 0.1 * d.z),
                DVec3::new(x, c.y - 0.011 * d.y, b.max.z + 0.1 * d.z),
            ]
        })
        .collect()
}

#[test]
fn a_straight_blade_crossing_in_steps_of_any_length_leaves_two_parts() {
    for name in MESHES {
        for steps in [7, 30, 100] {
            let mut run = Run::new(name, CutOptions::SCALPEL);
            let path = straight_path(&run.bounds(), steps);
            run.sweep(&format!("{steps} steps"), &path);
            assert_eq!(run.parts(), 2, "{name}, {steps} steps");
        }
    }
}

/// A blade crossing fandisk in 300 steps, each a tenth of its median edge: cut at every
/// step, the tets at the crack's front are split again and again (measured: 190,257 tets
/// added, smallest dihedral angle 5e-4°). An [`Incision`] deferring steps until the blade
/// is half an edge from where the crack ends cuts far fewer times, each step leaving a
/// valid mesh, deferred ones leaving it as it was, and catching up at the end leaves two
/// parts.
#[test]
fn a_blade_in_steps_shorter_than_the_edges_cuts_once_it_has_moved_half_an_edge() {
    let name = "fandisk";
    let edge = mesh(name).median_edge_length().expect("tets");
    let mut every_step = Run::new(name, CutOptions::SCALPEL);
    let path = straight_path(&every_step.bounds(), 300);
    assert!(
        blade_advance(path[0], path[1]) < 0.12 * edge,
        "steps shorter than the edges"
    );
    for w in path.windows(2) {
        for polygon in &scalpel_sweep(w[0], w[1], Tolerance { relative: 1e-9 }).unwrap() {
            every_step.cutter.cut(polygon).expect("cut");
        }
    }
    let mut run = Run::new(name, CutOptions::SCALPEL);
    let mut incision = Incision::new(path[0], 0.5 * edge).unwrap();
    let mut cuts = 0;
    for (k, &to) in path.iter().enumerate().skip(1) {
        let tets = run.cutter.mesh().nb_tets();
        let cutter = &mut run.cutter;
        let mut cut = |p: &CutPolygon| -> Result<(), ScalpelError> {
            cutter.cut(p)?;
            Ok(())
        };
        let cut_now = incision
            .step(to, &mut cut)
            .unwrap_or_else(|e| panic!("step {k}: {e}"));
        if !cut_now {
            assert!(incision.is_behind(), "step {k}");
            assert_eq!(run.cutter.mesh().nb_tets(), tets, "a deferred step {k} cut");
            continue;
        }
        cuts += 1;
        run.check(&format!("step {k}"));
    }
    let cutter = &mut run.cutter;
    incision
        .catch_up(|p| -> Result<(), ScalpelError> {
            cutter.cut(p)?;
            Ok(())
        })
        .expect("catch up");
    run.check("caught up");
    assert_eq!(run.parts(), 2);
    let input = mesh(name).nb_tets();
    let (deferred, every) = (
        run.cutter.mesh().nb_tets() - input,
        every_step.cutter.mesh().nb_tets() - input,
    );
    println!("fandisk, 300 steps: {cuts} cuts adding {deferred} tets; cut at every step: {every}");
    assert!(
        cuts <= 75 && 4 * deferred <= every,
        "{cuts} cuts, {deferred} tets added (cut at every step: {every})"
    );
}

/// A vertical blade moving along an arc around a centre off the body's corner, turning by
/// `step_deg` per step, from outside the body (-x side) to outside (-y side): it cuts a
/// corner off. The first `stop` positions make an incision that ends inside the body.
fn arc(b: &Aabb, step_deg: f64) -> impl Fn(usize) -> Blade + '_ {
    let (c, d) = (b.center(), b.max - b.min);
    let r = 0.6 * d.x.max(d.y);
    let centre = DVec3::new(b.min.x - 0.1 * d.x, c.y - r, c.z);
    move |k| {
        let a = (98.0 - step_deg * k as f64).to_radians();
        let p = centre + DVec3::new(r * a.cos(), r * a.sin(), 0.0);
        vertical(b, p.x, p.y)
    }
}

#[test]
fn a_turning_incision_stopped_inside_then_extended_cuts_a_corner_off() {
    for name in MESHES {
        for step_deg in [8.0, 1.0] {
            let mut run = Run::new(name, CutOptions::SCALPEL);
            let b = run.bounds();
            let at = arc(&b, step_deg);
            let n = (128.0 / step_deg) as usize;
            let stop = n * 5 / 16;
            let first: Vec<Blade> = (0..=stop).map(&at).collect();
            run.sweep(&format!("{step_deg}°/step, first part"), &first);
            assert_eq!(
                run.parts(),
                1,
                "{name}: a partial incision separated the body"
            );
            let rest: Vec<Blade> = (stop..=n).map(&at).collect();
            run.sweep(&format!("{step_deg}°/step, extension"), &rest);
            assert_eq!(
                run.parts(),
                2,
                "{name}, {step_deg}°/step: corner not cut off"
            );
        }
    }
}

#[test]
fn a_tilting_blade_across_the_body_leaves_two_parts() {
    // Every sweep is non-planar (two triangles): the blade leans a little more or less at
    // each step, so each step continues the last at an angle.
    for name in MESHES {
        let mut run = Run::new(name, CutOptions::SCALPEL);
        let b = run.bounds();
        let path: Vec<Blade> = (0..=10).map(|k| tilting(&b, k)).collect();
        run.sweep("tilting", &path);
        assert_eq!(run.parts(), 2, "{name}");
    }
}

/// The parts of `name` cut at once by the rectangles a shallow blade sweeps along each
/// straight path (each path is planar: its swept area is one rectangle).
fn parts_cut_at_once(name: &str, paths: &[Vec<Blade>]) -> usize {
    let mut cutter = Cutter::new(mesh(name).clone(), CutOptions::SCALPEL).expect("options");
    for path in paths {
        let (a, z) = (path[0], path[path.len() - 1]);
        let rect = mtcut::geom::CutPolygon::new(&[a[0], a[1], z[1], z[0]]).expect("rectangle");
        cutter.cut(&rect).expect("cut");
    }
    assert!(cutter.mesh().validate().is_valid());
    Components::of(cutter.mesh()).count
}

#[test]
fn incisions_meeting_and_crossing_an_earlier_one_keep_the_mesh_valid() {
    for name in MESHES {
        // T: a shallow incision along x, then one from outside the body ending on it.
        let mut run = Run::new(name, CutOptions::SCALPEL);
        let b = run.bounds();
        let (c, d) = (b.center(), b.max - b.min);
        let (x0, x1) = (b.min.x - 0.05 * d.x, b.max.x + 0.05 * d.x);
        let (y0, y1) = (b.min.y - 0.05 * d.y, b.max.y + 0.05 * d.y);
        let ya = c.y + 0.013 * d.y;
        let first = shallow_path(&b, (x0, ya), (x1, ya), 8);
        run.sweep("first incision", &first);
        let xt = c.x - 0.21 * d.x;
        let t = shallow_path(&b, (xt, y0), (xt, ya), 6);
        run.sweep("T", &t);
        // As many parts as the two swept rectangles cut at once give.
        assert_eq!(
            run.parts(),
            parts_cut_at_once(name, &[first.clone(), t]),
            "{name}: T"
        );

        // X: a shallow incision across the body in y, then one across it in x.
        let mut run = Run::new(name, CutOptions::SCALPEL);
        let xx = c.x + 0.17 * d.x;
        let across = shallow_path(&b, (xx, y0), (xx, y1), 10);
        run.sweep("first incision", &across);
        run.sweep("X", &first);
        assert_eq!(
            run.parts(),
            parts_cut_at_once(name, &[across, first]),
            "{name}: X"
        );
    }
}

#[test]
fn a_blade_swept_with_the_default_options_keeps_the_mesh_valid() {
    // The default snap (0.2) bends a crack through the vertices near it; a later step in
    // the same plane then meets the earlier lips' vertices, each with a copy per lip at
    // the same place. A vertex that cannot be separated is left unsnapped, and its copies
    // with it: unsnapped alone, one lip's edges from it were cut and the other's not (on
    // fandisk, step 27: a crack tip inside the coincident face of the other lip, a
    // hanging vertex). The sweep still chips the body (hence CutOptions::SCALPEL).
    for name in MESHES {
        let mut run = Run::new(name, CutOptions::DEFAULT);
        let path = straight_path(&run.bounds(), 100);
        run.sweep("default options", &path);
    }
}

#[test]
fn with_the_default_snap_a_step_that_would_make_a_flat_tet_is_refused() {
    // The default snap (0.2) is meant for independent cuts: with the smallest face-point
    // margin and swept in many steps, a blade's crack tips land next to snapped vertices
    // and some step would make a flat tet. The cut checks every child's orientation exactly before it changes
    // the mesh: such a step is refused, naming the tet, and the mesh stays as it was; no
    // step leaves a tet that is not positively oriented. (Such sweeps chip the body: hence
    // CutOptions::SCALPEL.)
    let mut refused = 0;
    for name in MESHES {
        let input = mesh(name);
        let options = CutOptions::DEFAULT.with_face_point_margin(MIN_FACE_POINT_MARGIN);
        let mut cutter = Cutter::new(input.clone(), options).expect("options");
        for w in straight_path(&input.bbox(), 100).windows(2) {
            for polygon in scalpel_sweep(w[0], w[1], Tolerance { relative: 1e-9 }).expect("sweep") {
                let before = cutter.mesh().clone();
                match cutter.cut(&polygon) {
                    Ok(_) => {}
                    Err(e @ mtcut::cut::CutError::FlatChild { .. }) => {
                        refused += 1;
                        assert!(e.to_string().contains("flat or inverted"), "{e}");
                        assert_eq!(
                            cutter.mesh(),
                            &before,
                            "{name}: a refused cut changed the mesh"
                        );
                    }
                    Err(e) => panic!("{name}: {e}"),
                }
                let m = cutter.mesh();
                let inverted = m.tets().iter().position(|t| {
                    let [a, b, c, d] = t.map(|v| m.position(v));
                    mtcut::geom::orient3d(a, b, c, d) != mtcut::geom::Sign::Positive
                });
                assert_eq!(inverted, None, "{name}: a tet is flat or inverted");
            }
        }
    }
    assert!(
        refused > 0,
        "no step was refused: this test no longer shows the check"
    );
}

/// Random paths (`paths` per mesh, seeded): every step valid and volume kept, and no cut
/// refused.
fn random_paths(paths: u64) {
    for name in MESHES {
        for seed in 0..paths {
            let mut run = Run::new(name, CutOptions::SCALPEL);
            let mut rng = cut_common::Rng(0xB1ADE + seed);
            let path = random_path(&run.bounds(), || rng.unit());
            run.sweep(&format!("random path {seed}"), &path);
        }
    }
}

#[test]
fn random_scalpel_paths_keep_the_mesh_valid() {
    random_paths(6);
}

#[test]
#[ignore = "long: 100 random paths per mesh; cargo test --release --test cut_scalpel -- --ignored"]
fn random_scalpel_paths_long() {
    random_paths(100);
}
