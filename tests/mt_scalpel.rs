//! Progressive scalpel cuts on the MT (issue 7, item 4): a blade moved in time steps, each
//! step cutting only the area it swept. Incisions that turn, a blade that tilts as it
//! moves (non-planar sweeps, two triangles per step), an incision that ends inside the
//! body and is extended later, and new incisions meeting an earlier one (T) or crossing it
//! (X), and a blade in an axis-aligned plane. A sweep whose two triangles the MT refuses
//! is cut as another split of it where the MT takes one. A blade tilting at steeper angles
//! between steps is still refused at some steps (the refusal tests below use it), and so
//! is a turning blade ending inside pinion and liver (an ignored test).
//! After every step the MT is valid, the finest and coarsest meshes keep their volume, and
//! extractions at 10 thresholds (and focus regions at some steps) are valid meshes that no
//! polygon applied so far crosses.

mod blades;
mod cut_common;
mod mt_common;
mod mtcut_common;

use blades::{on_arc, random_path, shallow_path, shallow_turning, tilting, tilting_in};
use mtcut::cut::{
    Blade, Components, CutError, CutOptions, Cutter, MtCutter, Scalpel, ScalpelError,
};
use mtcut::geom::{
    Aabb, CutPolygon, DVec3, SWEEP_PLANARITY, Tolerance, scalpel_sweep, scalpel_sweep_splits,
};
use mtcut::mt::{BuildOptions, Mt};
use mtcut_common::*;

struct Run {
    name: &'static str,
    cutter: MtCutter,
    volumes: (f64, f64),
    polygons: Vec<CutPolygon>,
    steps: usize,
}

impl Run {
    fn new(name: &'static str) -> Run {
        let mt = mt_common::built(name).1.clone();
        let volumes = extreme_volumes(&mt);
        let options = MtCutter::DEFAULT_OPTIONS;
        Run {
            name,
            cutter: MtCutter::new(mt, options).expect("options"),
            volumes,
            polygons: Vec::new(),
            steps: 0,
        }
    }

    fn bounds(&self) -> Aabb {
        Aabb::from_points(self.cutter.mt().positions())
    }

    /// Moves the blade through `path`, one sweep per consecutive pair, checking after each.
    fn sweep(&mut self, what: &str, path: &[Blade]) {
        for w in path.windows(2) {
            let sweep = scalpel_sweep(w[0], w[1], Tolerance { relative: 1e-9 })
                .unwrap_or_else(|e| panic!("{} {what}: sweep: {e}", self.name));
            for polygon in sweep {
                self.cutter
                    .cut(&polygon)
                    .unwrap_or_else(|e| panic!("{} {what}: cut refused: {e}", self.name));
                self.polygons.push(polygon);
            }
            self.steps += 1;
            let regions = usize::from(self.steps % 4 == 0);
            let req = requests(self.cutter.mt(), 10, regions, &mut Rng(self.steps as u64));
            if let Err(m) = check_after_cut(&self.cutter, self.volumes, &self.polygons, &req) {
                panic!("{} {what}, step {}: {m}", self.name, self.steps);
            }
        }
    }

    fn components(&self) -> usize {
        self.cutter.mt().nb_components()
    }
}

/// An incision that turns by 8° per step (each sweep planar, consecutive ones at an angle)
/// and stops inside the body: each step begins where the last one's crack ended, at an
/// angle to it, on every level (`mt_cut`'s turning tips).
#[test]
fn a_turning_incision_stopped_inside_keeps_every_level_valid() {
    for name in mt_common::MESHES {
        turning_incision(name, false);
    }
}

/// The turning incision, later extended until it leaves the body, on every shared mesh:
/// it cuts a corner off each, as the plain-mesh engine's does (tests/cut_scalpel.rs).
#[test]
fn a_turning_incision_stopped_inside_then_extended() {
    for name in mt_common::MESHES {
        let run = turning_incision(name, true);
        assert_eq!(
            run.components(),
            2,
            "{name}: the incision left the body in one part"
        );
    }
}

/// The turning incision of the tests above on `name`: six blade positions turning by 8°,
/// the body still one part; with `extend`, ten more from the last, until it leaves.
fn turning_incision(name: &'static str, extend: bool) -> Run {
    let mut run = Run::new(name);
    let b = run.bounds();
    let at = |deg: f64| on_arc(&b, deg);
    let first: Vec<Blade> = (0..6).map(|k| at(-8.0 + 8.0 * k as f64)).collect();
    run.sweep("first part", &first);
    assert_eq!(
        run.components(),
        1,
        "{name}: a partial incision separated the body"
    );
    if extend {
        let rest: Vec<Blade> = (5..16).map(|k| at(-8.0 + 8.0 * k as f64)).collect();
        run.sweep("extension", &rest);
    }
    run
}

/// The turning incision of `a_turning_incision_stopped_inside_then_extended`, each step
/// cut by a new cutter made of the MT as saved after the step before (`.mt` bytes, loaded
/// again): the MT carries what a step continuing the last at an angle needs (its cut
/// record), so every step is taken and the MT is, step by step, the one a single cutter
/// makes (canonical forms compared), the same bytes when saved, and valid.
#[test]
fn a_scalpel_resumed_from_saved_models_cuts_as_one_cutter() {
    for name in mt_common::MESHES {
        let mt = mt_common::built(name).1.clone();
        let b = Aabb::from_points(mt.positions());
        let mut one = MtCutter::new(mt.clone(), MtCutter::DEFAULT_OPTIONS).expect("options");
        let mut saved = mt.to_bytes();
        let path = blades::turning_by_8(&b, 15);
        for (k, w) in path.windows(2).enumerate() {
            for polygon in scalpel_sweep(w[0], w[1], Tolerance { relative: 1e-9 }).expect("sweep") {
                let loaded = Mt::from_bytes(&saved).expect("load");
                let mut fresh = MtCutter::new(loaded, MtCutter::DEFAULT_OPTIONS).expect("options");
                fresh
                    .cut(&polygon)
                    .unwrap_or_else(|e| panic!("{name} step {k}: resumed from saved: {e}"));
                one.cut(&polygon)
                    .unwrap_or_else(|e| panic!("{name} step {k}: one cutter: {e}"));
                assert!(
                    fresh.mt().canonical_form() == one.mt().canonical_form(),
                    "{name} step {k}: the resumed cut differs from the single cutter's"
                );
                saved = fresh.mt().to_bytes();
                assert!(
                    saved == one.mt().to_bytes(),
                    "{name} step {k}: the resumed MT saves to other bytes"
                );
            }
        }
        let report = one.mt().validate();
        assert!(report.is_valid(), "{name}: {report:?}");
        assert_eq!(
            one.mt().nb_components(),
            2,
            "{name}: the incision did not separate"
        );
    }
}

/// A blade turning by 30° per step (five steps of a sixth of a turn around a centre off
/// the body) cuts a corner off each shared mesh.
#[test]
fn a_sharply_turning_incision_cuts_a_corner_off() {
    for name in mt_common::MESHES {
        let mut run = Run::new(name);
        let b = run.bounds();
        let path: Vec<Blade> = (0..6)
            .map(|k| on_arc(&b, -30.0 + 30.0 * k as f64))
            .collect();
        run.sweep("turning by 30°", &path);
        assert_eq!(
            run.components(),
            2,
            "{name}: the incision left the body in one part"
        );
    }
}

/// A blade turning by 8° per step whose edge ends inside the body (from above it down to
/// mid-depth), 17 steps: its crack's lower edge ends inside too, and each step meets the
/// last one's there as well as along the blade. Valid at every step on fandisk, and in as
/// many parts as the plain-mesh engine leaves it (two: fandisk's corner is shallower than
/// the blade).
#[test]
fn a_shallow_turning_incision_on_fandisk() {
    shallow_turning_incision("fandisk");
}

/// The shallow turning incision on pinion and liver.
#[test]
#[ignore = "KNOWN FAILURE (issue 7 open): the MT cut refuses some steps on pinion and \
            liver (MtInconsistent: near the lower corner where two steps' cracks end, a \
            coarse level needs a tip whole that a finer level needs split, which one copy \
            per tip cannot give)"]
fn a_shallow_turning_incision_on_pinion_and_liver() {
    for name in ["pinion", "liver"] {
        shallow_turning_incision(name);
    }
}

fn shallow_turning_incision(name: &'static str) {
    let mut run = Run::new(name);
    let path = shallow_turning(&run.bounds(), 8.0);
    run.sweep("shallow, turning", &path);
    assert_eq!(
        run.components(),
        plain_parts(name, &path),
        "{name}: not in as many parts as the plain-mesh engine leaves the finest mesh"
    );
}

/// The parts the plain-mesh engine's scalpel leaves the finest mesh in along `path`.
fn plain_parts(name: &str, path: &[Blade]) -> usize {
    let options = CutOptions::SCALPEL.with_count_components(false);
    let mut cutter = Cutter::new(mt_common::built(name).0.clone(), options).expect("options");
    for w in path.windows(2) {
        for polygon in scalpel_sweep(w[0], w[1], Tolerance { relative: 1e-9 }).expect("sweep") {
            cutter.cut(&polygon).expect("plain-mesh cut");
        }
    }
    Components::of(cutter.mesh()).count
}

/// A blade tilting as it moves straight across: every sweep is non-planar (two triangles),
/// each step continuing the last at an angle. Through the whole body: it separates.
#[test]
fn a_tilting_blade_across_the_body_separates_it() {
    for name in mt_common::MESHES {
        let mut run = Run::new(name);
        let b = run.bounds();
        let path: Vec<Blade> = (0..=10).map(|k| tilting(&b, k)).collect();
        run.sweep("tilting", &path);
        assert!(run.components() >= 2, "{name}: the blade did not separate");
    }
}

/// A cut the MT cannot take yet (the blade of the test above tilting in 20 steps, whose
/// steps meet at steeper angles: at some, a fragment's floor and ceiling would disagree
/// where they meet) is refused with an error naming a fragment,
/// and given back: the MT is byte for byte what it was, and the cutter goes on as if the
/// cut had not been tried (a cut elsewhere then gives the same MT as on a twin cutter that
/// never tried it), valid after.
#[test]
fn a_cut_breaking_the_mt_is_refused_and_given_back() {
    let mut refused = 0;
    for name in mt_common::MESHES {
        let mut run = Run::new(name);
        let mut twin = Run::new(name);
        let b = run.bounds();
        let (c, d) = (b.center(), b.max - b.min);
        let path: Vec<Blade> = (0..=20).map(|k| tilting_in(&b, k, 20)).collect();
        let sweeps = path
            .windows(2)
            .flat_map(|w| scalpel_sweep(w[0], w[1], Tolerance { relative: 1e-9 }).expect("sweep"));
        for polygon in sweeps {
            let before = run.cutter.mt().to_bytes();
            match run.cutter.cut(&polygon) {
                Ok(_) => {
                    twin.cutter.cut(&polygon).expect("the twin cuts alike");
                    run.polygons.push(polygon);
                }
                Err(e @ CutError::MtInconsistent { .. }) => {
                    refused += 1;
                    assert!(e.to_string().contains("fragment"), "{name}: {e}");
                    assert!(
                        run.cutter.mt().to_bytes() == before,
                        "{name}: the refused cut changed the MT"
                    );
                    let (x0, x1) = (b.min.x - 0.05 * d.x, b.max.x + 0.05 * d.x);
                    let y = c.y + 0.3 * d.y;
                    for w in shallow_path(&b, (x0, y), (x1, y), 1).windows(2) {
                        for p in
                            scalpel_sweep(w[0], w[1], Tolerance { relative: 1e-9 }).expect("sweep")
                        {
                            run.cutter.cut(&p).unwrap_or_else(|e| panic!("{name}: {e}"));
                            twin.cutter
                                .cut(&p)
                                .unwrap_or_else(|e| panic!("{name}: {e}"));
                            run.polygons.push(p);
                        }
                    }
                    assert!(
                        run.cutter.mt().to_bytes() == twin.cutter.mt().to_bytes(),
                        "{name}: after a refused cut, the next cut differs from the twin's"
                    );
                    let req = requests(run.cutter.mt(), 10, 1, &mut Rng(7));
                    if let Err(m) = check_after_cut(&run.cutter, run.volumes, &run.polygons, &req) {
                        panic!("{name}, after a refused cut and one elsewhere: {m}");
                    }
                    break;
                }
                Err(e) => panic!("{name}: {e}"),
            }
        }
    }
    // When MT cuts learn to take these steps, this test needs another cut they refuse.
    assert!(refused > 0, "no cut of the steep tilting path was refused");
}

/// A step the MT refuses as its sweep's default two triangles is cut as another split of
/// the same sweep (`Scalpel::step`, `scalpel_sweep_splits`): on random path 0 through
/// fandisk's MT (a blade ending inside the body, leaning, so that every sweep is two
/// triangles), step 10's default triangles are refused by a cutter in the scalpel's state,
/// the scalpel takes another split, and the MT is valid after every step, each extraction
/// crossed by none of the polygons cut.
#[test]
fn a_refused_split_of_a_sweep_gives_way_to_another() {
    let model = mt_common::built("fandisk").1.clone();
    let volumes = extreme_volumes(&model);
    let mut rng = cut_common::Rng(0xB1ADE);
    let path = random_path(&Aabb::from_points(model.positions()), || rng.unit());
    let mut scalpel = Scalpel::new(model, path[0]).expect("scalpel");
    let mut applied = Vec::new();
    for (k, &to) in path.iter().enumerate().take(11).skip(1) {
        let from = scalpel.incision().end();
        let default = scalpel_sweep(from, to, SWEEP_PLANARITY).expect("sweep");
        assert_eq!(default.len(), 2, "step {k}: the sweep is not two triangles");
        let twin = (k == 10).then(|| scalpel.mt().clone());
        let step = scalpel
            .step(to)
            .unwrap_or_else(|e| panic!("fandisk, random path 0, step {k}: {e}"));
        let polygons: Vec<CutPolygon> = scalpel_sweep_splits(from, to, SWEEP_PLANARITY)
            .expect("splits")
            .swap_remove(step.split);
        if let Some(mt) = twin {
            assert!(step.split > 0, "step 10 took the default split");
            let mut cutter = MtCutter::new(mt, Scalpel::OPTIONS).expect("cutter");
            let refused = default.iter().try_for_each(|p| cutter.cut(p).map(drop));
            assert!(
                matches!(refused, Err(CutError::MtInconsistent { .. })),
                "step 10's default split was not refused: {refused:?}"
            );
        } else {
            assert_eq!(step.split, 0, "step {k}");
        }
        applied.extend(polygons);
        let req = requests(scalpel.mt(), 10, 1, &mut Rng(k as u64));
        if let Err(m) = check_after_cut(scalpel.cutter(), volumes, &applied, &req) {
            panic!("fandisk, random path 0, step {k}: {m}");
        }
    }
}

/// After a step the MT refuses, `Scalpel::step_after_gap` begins a new crack a tenth of the
/// way into it and cuts from there (a bridge that wide left in the incision): liver's
/// shallow incision turning by 4° per step (a known limit: some steps continuing the last
/// are refused). The crack then ends at the blade, the MT valid, extractions crossed by
/// none of the polygons cut; a gap not strictly between 0 and 1 is refused, the scalpel
/// as it was.
#[test]
fn a_refused_step_is_cut_again_past_a_gap() {
    let model = mt_common::built("liver").1.clone();
    let volumes = extreme_volumes(&model);
    let path = shallow_turning(&Aabb::from_points(model.positions()), 4.0);
    let split = |from: Blade, to: Blade, k: usize| {
        scalpel_sweep_splits(from, to, SWEEP_PLANARITY)
            .expect("sweep")
            .swap_remove(k)
    };
    let mut scalpel = Scalpel::new(model, path[0]).expect("scalpel");
    let mut applied = Vec::new();
    for (k, &to) in path.iter().enumerate().skip(1) {
        let from = scalpel.incision().end();
        match scalpel.step(to) {
            Ok(step) => applied.extend(split(from, to, step.split)),
            Err(ScalpelError::Cut(CutError::MtInconsistent { .. })) => {
                for bad in [0.0, 1.0, -0.5, f64::NAN] {
                    let r = scalpel.step_after_gap(to, bad);
                    assert!(matches!(r, Err(ScalpelError::Gap(_))), "gap {bad}: {r:?}");
                    assert_eq!(scalpel.incision().end(), from);
                }
                let step = scalpel
                    .step_after_gap(to, 0.1)
                    .unwrap_or_else(|e| panic!("step {k}, from a tenth of the way: {e}"));
                assert!(step.tets_cut() > 0, "step {k}");
                assert_eq!(scalpel.incision().end(), to);
                let start = [from[0].lerp(to[0], 0.1), from[1].lerp(to[1], 0.1)];
                applied.extend(split(start, to, step.split));
                let req = requests(scalpel.mt(), 10, 1, &mut Rng(k as u64));
                if let Err(m) = check_after_cut(scalpel.cutter(), volumes, &applied, &req) {
                    panic!("liver, step {k}, from a tenth of the way: {m}");
                }
                return;
            }
            Err(e) => panic!("liver, step {k}: {e}"),
        }
    }
    panic!("no step of the shallow turning incision was refused");
}

/// The random scalpel paths of tests/cut_scalpel.rs (turning, leaning, through the body or
/// stopping inside it), which the plain-mesh engine takes whole, moved through each shared
/// mesh's MT by a [`Scalpel`]: a step the MT refuses is skipped (the MT as it was; the next
/// step cuts from where the crack ends), the MT valid after every step, and no step should
/// be refused. Measured (25 paths per mesh): see the ignore reason and the README's
/// "Scalpel on the MT: random paths".
#[test]
#[ignore = "KNOWN FAILURE (issue 7 open): the MT refuses steps of 6, 7 and 5 of the 25 \
            random paths on fandisk, pinion and liver, however each sweep is split (steps \
            continuing the last at an angle: turning blades, most of all those ending \
            inside the body, and leaning ones, whose sweeps are two triangles)"]
fn random_scalpel_paths_through_the_mt() {
    refused_on_random_paths(|name| mt_common::built(name).1.clone());
}

/// The same paths through an MT of one level, each shared mesh alone (built with a target
/// of as many tets as it has: no collapse): the MT cut then works on the very mesh the
/// plain-mesh engine takes the paths whole on, so what it refuses comes from how it
/// decides a turning tip's copy (one copy per vertex, given by position to the tets
/// outside the wedge between the two cracks: `mtcut::cut::mt_cut`'s `TurnTips`), not
/// from levels that disagree.
#[test]
#[ignore = "KNOWN FAILURE (issue 7 open): on one level the MT still refuses steps of 2 of \
            the 25 paths on liver, however each sweep is split (4, 2 and 4 paths on \
            fandisk, pinion and liver with the first split only: a turning tip's copy \
            given to two fans of tets, and flat children the plain engine avoids with a \
            snap beyond the MT's 1e-4)"]
fn random_scalpel_paths_through_an_mt_of_one_level() {
    refused_on_random_paths(|name| {
        let mesh = &mt_common::built(name).0;
        let options = BuildOptions::DEFAULT.with_target_tets(Some(mesh.nb_tets()));
        let (mt, _) = Mt::build(mesh, &options).expect("build");
        assert_eq!(mt.nb_fragments(), 2, "{name}: a collapse was made");
        mt
    });
}

/// Moves a [`Scalpel`] along 25 random paths through each shared mesh's `mt_of(name)`,
/// the MT valid after every step; fails naming the steps refused.
fn refused_on_random_paths(mt_of: impl Fn(&str) -> Mt) {
    let mut refused: Vec<(&str, u64, usize)> = Vec::new();
    for name in mt_common::MESHES {
        let model = mt_of(name);
        for seed in 0..25 {
            let mt = model.clone();
            let mut rng = cut_common::Rng(0xB1ADE + seed);
            let path = random_path(&Aabb::from_points(mt.positions()), || rng.unit());
            let mut scalpel = Scalpel::new(mt, path[0]).expect("scalpel");
            for (k, &to) in path.iter().enumerate().skip(1) {
                match scalpel.step(to) {
                    Ok(_) => {}
                    Err(ScalpelError::Cut(CutError::MtInconsistent { .. })) => {
                        refused.push((name, seed, k))
                    }
                    Err(e) => panic!("{name}, path {seed}, step {k}: {e}"),
                }
                let report = scalpel.mt().validate();
                assert!(
                    report.is_valid(),
                    "{name}, path {seed}, step {k}: {report:?}"
                );
            }
        }
    }
    let mut paths: Vec<(&str, u64)> = refused.iter().map(|&(n, s, _)| (n, s)).collect();
    paths.dedup();
    assert!(
        refused.is_empty(),
        "{} steps refused on {} paths (mesh, path): {paths:?}",
        refused.len(),
        paths.len()
    );
}

/// The smallest turn found refused (see `mtcut::cut::mt_cut`'s limits): a triangle ending
/// on a vertical line through the body, then a triangle continuing it from that line at
/// an angle, at 12 lines across each shared mesh and 0.5°, 4° and 30°: the MT valid after
/// each, and no continuation should be refused.
#[test]
#[ignore = "KNOWN FAILURE (issue 7 open): refused at 1 of the 12 lines on pinion (at 30°) \
            and 2 on liver (at every angle) (a coarse tet near the first triangle's corner holds tips \
            of two of its edges and joins the wedge to the rest)"]
fn a_triangle_continuing_a_partial_one_at_an_angle() {
    let mut refused = Vec::new();
    for name in mt_common::MESHES {
        let mt = &mt_common::built(name).1;
        let b = Aabb::from_points(mt.positions());
        let (c, d) = (b.center(), b.max - b.min);
        for deg in [0.5f64, 4.0, 30.0] {
            for j in 0..12 {
                let x = c.x + d.x * (-0.3 + 0.05 * j as f64);
                let y = c.y + d.y * 0.013 * (j as f64 - 6.0);
                let top = DVec3::new(x, y, b.max.z + 0.1 * d.z);
                let bottom = DVec3::new(x, y, b.min.z - 0.1 * d.z);
                let back = DVec3::new(x - 0.4 * d.x, y, c.z);
                let a = deg.to_radians();
                let ahead = DVec3::new(x + 0.4 * d.x * a.cos(), y + 0.4 * d.x * a.sin(), c.z);
                let mut cutter =
                    MtCutter::new(mt.clone(), MtCutter::DEFAULT_OPTIONS).expect("cutter");
                let first = CutPolygon::new(&[back, bottom, top]).expect("first");
                cutter
                    .cut(&first)
                    .unwrap_or_else(|e| panic!("{name}, line {j}: {e}"));
                let second = CutPolygon::new(&[top, bottom, ahead]).expect("second");
                match cutter.cut(&second) {
                    Ok(_) => {}
                    Err(CutError::MtInconsistent { .. }) => refused.push((name, j, deg)),
                    Err(e) => panic!("{name}, line {j}, {deg}°: {e}"),
                }
                let report = cutter.mt().validate();
                assert!(report.is_valid(), "{name}, line {j}, {deg}°: {report:?}");
            }
        }
    }
    assert!(
        refused.is_empty(),
        "refused (mesh, line, angle): {refused:?}"
    );
}

/// A shallow incision along x, then a second one starting outside the body and ending on
/// the first (T).
#[test]
fn an_incision_meeting_an_earlier_one() {
    for name in mt_common::MESHES {
        let mut run = Run::new(name);
        let b = run.bounds();
        let (c, d) = (b.center(), b.max - b.min);
        let (x0, x1) = (b.min.x - 0.05 * d.x, b.max.x + 0.05 * d.x);
        let y0 = b.min.y - 0.05 * d.y;
        let ya = c.y + 0.013 * d.y;
        run.sweep("first incision", &shallow_path(&b, (x0, ya), (x1, ya), 8));
        let xt = c.x - 0.21 * d.x;
        run.sweep("T", &shallow_path(&b, (xt, y0), (xt, ya), 6));
    }
}

/// A shallow incision across the whole body in y, in 10 steps, then one crossing it (X).
#[test]
fn an_incision_crossing_an_earlier_one() {
    for name in mt_common::MESHES {
        let mut run = Run::new(name);
        let b = run.bounds();
        let (c, d) = (b.center(), b.max - b.min);
        let (y0, y1) = (b.min.y - 0.05 * d.y, b.max.y + 0.05 * d.y);
        let xx = c.x + 0.17 * d.x;
        run.sweep("first incision", &shallow_path(&b, (xx, y0), (xx, y1), 10));
        let (x0, x1) = (b.min.x - 0.05 * d.x, b.max.x + 0.05 * d.x);
        let ya = c.y + 0.013 * d.y;
        run.sweep("X", &shallow_path(&b, (x0, ya), (x1, ya), 8));
    }
}

/// A blade lying in the axis-aligned plane z = middle + 1.23 % of the height, moved
/// across fandisk in x (a blade moving in its own plane, like the tilted one of
/// tests/mtcut_cut.rs that passes).
#[test]
fn a_blade_in_an_axis_aligned_plane_across_fandisk() {
    let mut run = Run::new("fandisk");
    let b = run.bounds();
    let d = b.max - b.min;
    let (lo, hi) = (b.min - d * 0.05, b.max + d * 0.05);
    let z = b.min.z + 0.5 * d.z + 0.0123 * d.z;
    let path: Vec<Blade> = (0..=8)
        .map(|k| {
            let x = lo.x + (hi.x - lo.x) * k as f64 / 8.0;
            [DVec3::new(x, lo.y, z), DVec3::new(x, hi.y, z)]
        })
        .collect();
    run.sweep("axis-aligned", &path);
    assert!(run.components() >= 2, "fandisk: the blade did not separate");
}

/// Down-closed fragment sets tried per vertex by `pinched_extraction` at most.
const MAX_SETS: usize = 1 << 14;

/// A [`Scalpel`] on `name`'s MT moved along `path`, deferring steps until the blade is
/// `edges` median edges (of the finest mesh) from where its crack ends, then catching up:
/// a deferred step leaves the MT as it was, each cutting step (and the catch-up) leaves it
/// valid, every level as [`Run::sweep`] checks, and every fourth (and the catch-up) no
/// extraction pinched at a vertex the cuts made (`pinched_extraction`: every extraction,
/// not only those sampled). Returns the scalpel, the steps cut and the steps deferred.
fn deferring_scalpel(name: &'static str, path: &[Blade], edges: f64) -> (Scalpel, usize, usize) {
    let run = Run::new(name);
    let finest = run
        .cutter
        .mt()
        .extract(&mtcut::mt::ExtractOptions::FINEST)
        .expect("finest");
    let edge = finest.mesh.median_edge_length().expect("tets");
    let first_cut_vertex = run.cutter.mt().nb_vertices();
    let mut scalpel = Scalpel::new(run.cutter.mt().clone(), path[0]).expect("scalpel");
    scalpel.set_min_advance(edges * edge).expect("a length");
    assert!(scalpel.set_min_advance(f64::NAN).is_err());
    assert_eq!(scalpel.incision().min_advance(), edges * edge);
    let mut polygons: Vec<CutPolygon> = Vec::new();
    let (mut cuts, mut deferred) = (0, 0);
    for (k, &to) in path.iter().enumerate().skip(1) {
        let tets = scalpel.mt().nb_tets();
        let from = scalpel.incision().end();
        let step = scalpel
            .step(to)
            .unwrap_or_else(|e| panic!("{name} step {k}: {e}"));
        if step.deferred {
            deferred += 1;
            assert!(step.cuts.is_empty(), "{name} step {k}");
            assert_eq!(
                scalpel.mt().nb_tets(),
                tets,
                "{name}: deferred step {k} changed the MT"
            );
            continue;
        }
        cuts += 1;
        polygons.extend(scalpel_sweep(from, to, Tolerance { relative: 1e-9 }).unwrap());
        let req = requests(scalpel.mt(), 10, 0, &mut Rng(k as u64));
        check_after_cut(scalpel.cutter(), run.volumes, &polygons, &req)
            .unwrap_or_else(|m| panic!("{name} step {k}: {m}"));
        // Every extraction's star at the vertices cuts made (costly: every fourth cut).
        if cuts % 4 == 0 {
            if let Some(m) = pinched_extraction(scalpel.mt(), first_cut_vertex, MAX_SETS) {
                panic!("{name} step {k}: an extraction is pinched at {m}");
            }
        }
    }
    let from = scalpel.incision().end();
    let rest = scalpel.catch_up().expect("catch up");
    if !rest.cuts.is_empty() {
        polygons
            .extend(scalpel_sweep(from, scalpel.blade(), Tolerance { relative: 1e-9 }).unwrap());
    }
    let req = requests(scalpel.mt(), 10, 1, &mut Rng(path.len() as u64));
    check_after_cut(scalpel.cutter(), run.volumes, &polygons, &req)
        .unwrap_or_else(|m| panic!("{name} caught up: {m}"));
    if let Some(m) = pinched_extraction(scalpel.mt(), first_cut_vertex, MAX_SETS) {
        panic!("{name} caught up: an extraction is pinched at {m}");
    }
    println!(
        "{name} MT, {} steps: {cuts} cut, {deferred} deferred",
        path.len() - 1
    );
    (scalpel, cuts, deferred)
}

/// A blade crossing the fandisk MT in 60 steps of about half a median edge, deferred
/// until it is 1.2 edges from where its crack ends: about one step in three is cut, and
/// catching up after the last step separates the body.
#[test]
fn a_scalpel_deferring_short_steps_cuts_every_few_steps_and_separates_the_body() {
    let b = Run::new("fandisk").bounds();
    let (c, d) = (b.center(), b.max - b.min);
    let path: Vec<Blade> = (0..=60)
        .map(|k| {
            let x = b.min.x - 0.02 * d.x + 1.04 * d.x * k as f64 / 60.0;
            [
                DVec3::new(x, c.y + 0.013 * d.y, b.min.z - 0.1 * d.z),
                DVec3::new(x, c.y - 0.011 * d.y, b.max.z + 0.1 * d.z),
            ]
        })
        .collect();
    let (scalpel, cuts, deferred) = deferring_scalpel("fandisk", &path, 1.2);
    assert!(
        deferred >= 30 && cuts <= 30,
        "{cuts} steps cut, {deferred} deferred"
    );
    assert_eq!(scalpel.mt().nb_components(), 2);
}

/// A vertical blade turning by 0.5° per step (about a sixth of a median edge) for 128
/// steps: cut at every step, the MT refuses it at step 41 on fandisk, 56 on pinion and 42
/// on liver (the levels disagree where a step begins at an angle to the last crack, see
/// `mtcut::cut::scalpel`'s limits; the test below); deferred until the blade is half an edge on (one edge
/// on liver, which refuses step 48 at half an edge), every step goes through and leaves
/// the MT valid.
#[test]
fn a_blade_turning_in_short_steps_goes_through_when_deferred() {
    for (name, edges) in [("fandisk", 0.5), ("pinion", 0.5), ("liver", 1.0)] {
        let b = Run::new(name).bounds();
        let path: Vec<Blade> = (0..=128)
            .map(|k| on_arc(&b, -8.0 + 0.5 * k as f64))
            .collect();
        let (_, cuts, deferred) = deferring_scalpel(name, &path, edges);
        assert!(
            cuts < deferred,
            "{name}: {cuts} steps cut, {deferred} deferred"
        );
    }
}

/// The 0.5° turn of the test above cut at every step, on fandisk: each step is taken,
/// every checked extraction valid after it, until one would leave an extraction between
/// the finest and the coarsest pinched at a crack tip (step 41, measured; before that was
/// checked, the step was taken and the mesh of the 7/9 quantile of fragment errors was
/// pinched): that step is refused, naming the flaw, and the MT is as it was.
#[test]
fn a_blade_turning_in_short_steps_is_refused_before_an_extraction_pinches() {
    let name = "fandisk";
    let mut run = Run::new(name);
    let first_cut_vertex = run.cutter.mt().nb_vertices();
    let b = run.bounds();
    for k in 1..=128 {
        let sweep = scalpel_sweep(
            on_arc(&b, -8.0 + 0.5 * (k - 1) as f64),
            on_arc(&b, -8.0 + 0.5 * k as f64),
            Tolerance { relative: 1e-9 },
        )
        .expect("sweep");
        let [polygon] = &sweep[..] else {
            panic!("a vertical blade sweeps a plane")
        };
        let before = run.cutter.mt().to_bytes();
        match run.cutter.cut(polygon) {
            Ok(_) => {
                run.polygons.push(polygon.clone());
                let req = requests(run.cutter.mt(), 10, 0, &mut Rng(k as u64));
                check_after_cut(&run.cutter, run.volumes, &run.polygons, &req)
                    .unwrap_or_else(|m| panic!("{name} step {k}: {m}"));
                if let Some(m) = pinched_extraction(run.cutter.mt(), first_cut_vertex, MAX_SETS) {
                    panic!("{name} step {k}: an extraction is pinched at {m}");
                }
            }
            Err(e @ CutError::MtInconsistent { .. }) => {
                let m = e.to_string();
                assert!(
                    m.contains("between its finest and coarsest meshes would be pinched"),
                    "{name} step {k}: {m}"
                );
                assert!(
                    run.cutter.mt().to_bytes() == before,
                    "{name}: the refused step changed the MT"
                );
                assert!(run.cutter.mt().validate().is_valid());
                return;
            }
            Err(e) => panic!("{name} step {k}: {e}"),
        }
    }
    panic!("{name}: every step was taken; the refusal this test shows is gone");
}

/// A scalpel step cutting two triangles (a non-planar sweep) whose second triangle the MT
/// refuses, after it took the first, however the sweep is split, is refused whole: the MT
/// is byte for byte what it was before the step and the blade where it was. The scalpel
/// then cuts on as if the step had not been tried (the same MT as a cutter that never
/// tried it), valid after. (Fandisk's blade tilting in 36 steps: its step 15 is such a
/// step; some before it are taken as another split of their sweeps, which the twin cuts
/// too.)
#[test]
fn a_step_whose_second_triangle_is_refused_changes_nothing() {
    let name = "fandisk";
    let mut twin = Run::new(name);
    let b = twin.bounds();
    let path: Vec<Blade> = (0..=36).map(|k| tilting_in(&b, k, 36)).collect();
    let mut scalpel = Scalpel::new(twin.cutter.mt().clone(), path[0]).expect("scalpel");
    let sweep = |from: Blade, to: Blade| scalpel_sweep(from, to, SWEEP_PLANARITY).expect("sweep");
    for k in 1..path.len() {
        let before = scalpel.mt().to_bytes();
        let e = match scalpel.step(path[k]) {
            Ok(step) => {
                let taken = scalpel_sweep_splits(path[k - 1], path[k], SWEEP_PLANARITY)
                    .expect("splits")
                    .swap_remove(step.split);
                for p in taken {
                    twin.cutter.cut(&p).expect("the twin cuts alike");
                    twin.polygons.push(p);
                }
                continue;
            }
            Err(e) => e,
        };
        assert!(
            matches!(e, ScalpelError::Cut(CutError::MtInconsistent { .. })),
            "step {k}: {e}"
        );
        // Every split of the sweep refused, some only at their second triangle, the first
        // alone taken: the step cut it, and gave it back.
        let splits = scalpel_sweep_splits(path[k - 1], path[k], SWEEP_PLANARITY).expect("splits");
        let mut first_taken = 0;
        for split in &splits {
            assert_eq!(split.len(), 2, "step {k}: not a two-triangle step");
            let mut probe =
                MtCutter::new(twin.cutter.mt().clone(), Scalpel::OPTIONS).expect("probe");
            if probe.cut(&split[0]).is_ok() {
                first_taken += 1;
                assert!(probe.cut(&split[1]).is_err(), "step {k}: a split is taken");
            }
        }
        assert!(
            first_taken > 0,
            "step {k}: no split's first triangle is taken"
        );
        assert!(
            scalpel.mt().to_bytes() == before,
            "step {k}: the refused step changed the MT"
        );
        assert_eq!(scalpel.blade(), path[k - 1], "step {k}: the blade moved");
        assert_eq!(scalpel.incision().end(), path[k - 1]);
        // On, from where the blade is, moving as far along x without tilting (a planar
        // sweep): cut alike by the scalpel and by the twin, which never tried the step.
        let shift = DVec3::new(path[k][0].x - path[k - 1][0].x, 0.0, 0.0);
        let to = path[k - 1].map(|p| p + shift);
        let step = scalpel
            .step(to)
            .unwrap_or_else(|e| panic!("step {k}, on: {e}"));
        assert_eq!(step.cuts.len(), 1);
        for p in sweep(path[k - 1], to) {
            twin.cutter.cut(&p).expect("the twin cuts alike");
            twin.polygons.push(p);
        }
        assert!(
            scalpel.mt().to_bytes() == twin.cutter.mt().to_bytes(),
            "step {k}: after the refused step, the next one differs from the twin's"
        );
        let req = requests(twin.cutter.mt(), 10, 1, &mut Rng(k as u64));
        if let Err(m) = check_after_cut(&twin.cutter, twin.volumes, &twin.polygons, &req) {
            panic!("step {k}, after the refused step and one more: {m}");
        }
        return;
    }
    panic!("no step of the 36-step tilt was refused at its second triangle");
}
