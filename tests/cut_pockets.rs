//! Cuts straight through leave no single tet floating in the crack where its neighbours
//! all lie on one side (`mtcut::cut::pockets`): seeded random planes through liver, whose
//! long edges make tets with all four vertices snapped common. Before the rule these 300
//! cuts left 58 single-tet parts; with it 9 (tets lying in the cut next to another one,
//! or with neighbours on both sides: the module's limits). Every result is valid.

mod cut_common;

use cut_common::*;
use mtcut::cut::{Components, CutOptions, Cutter};
use mtcut::geom::DVec3;

#[test]
fn random_cuts_through_liver_leave_few_single_tet_parts() {
    let mesh = mesh("liver");
    let b = mesh.bbox();
    let options = CutOptions::DEFAULT.with_count_components(false);
    let prepared = Cutter::new(mesh.clone(), options).expect("cutter");
    let mut rng = Rng(13);
    let mut single = Vec::new();
    for k in 0..300 {
        let offset = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let origin = b.center() + (b.max - b.min) * 0.3 * offset;
        let polygon = square(origin, rng.direction(), 2.0 * b.diagonal());
        let mut cutter = prepared.clone();
        cutter.cut(&polygon).expect("a cut through");
        let report = cutter.mesh().validate();
        assert!(report.is_valid(), "cut {k}: {report}");
        let parts = Components::of(cutter.mesh());
        single.extend(parts.sizes().iter().filter(|&&n| n == 1).map(|_| k));
    }
    println!(
        "single-tet parts over 300 cuts: {} (cuts {single:?})",
        single.len()
    );
    assert!(
        single.len() <= 9,
        "{} single-tet parts (cuts {single:?}); 9 measured when the rule was made, 58 before it",
        single.len()
    );
}
