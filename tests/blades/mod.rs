//! Blade positions shared by the scalpel tests of plain meshes (tests/cut_scalpel.rs) and of
//! the MT (tests/mt_scalpel.rs), so both move the same blades through the same bodies.
#![allow(dead_code)] // each test binary uses its own subset

use mtcut::cut::Blade;
use mtcut::geom::{Aabb, DVec3};

/// A blade spanning the body in z (with margin) at (x, y).
pub fn vertical(b: &Aabb, x: f64, y: f64) -> Blade {
    let d = b.max - b.min;
    [
        DVec3::new(x, y, b.min.z - 0.1 * d.z),
        DVec3::new(x, y, b.max.z + 0.1 * d.z),
    ]
}

/// A vertical blade on an arc around a centre off the body (entering it from -x), `deg`
/// degrees along it: an incision turning by 8° per step takes `deg` = -8, 0, 8, ...
pub fn on_arc(b: &Aabb, deg: f64) -> Blade {
    let (c, d) = (b.center(), b.max - b.min);
    let r = 0.6 * d.x.max(d.y);
    let centre = DVec3::new(b.min.x - 0.1 * d.x, c.y - r, c.z);
    let a = (90.0 - deg).to_radians();
    let p = centre + DVec3::new(r * a.cos(), r * a.sin(), 0.0);
    vertical(b, p.x, p.y)
}

/// The blade of [`on_arc`] turning by 8° per step from -8°: `steps` sweeps, `steps + 1`
/// positions.
pub fn turning_by_8(b: &Aabb, steps: usize) -> Vec<Blade> {
    (0..=steps)
        .map(|k| on_arc(b, -8.0 + 8.0 * k as f64))
        .collect()
}

/// A blade cutting from above the body down to mid-depth, moved along `from`→`to` in steps.
pub fn shallow_path(b: &Aabb, from: (f64, f64), to: (f64, f64), steps: usize) -> Vec<Blade> {
    let d = b.max - b.min;
    let depth = b.min.z + 0.45 * d.z;
    (0..=steps)
        .map(|k| {
            let t = k as f64 / steps as f64;
            let (x, y) = (from.0 + t * (to.0 - from.0), from.1 + t * (to.1 - from.1));
            [
                DVec3::new(x, y, b.max.z + 0.1 * d.z),
                DVec3::new(x, y, depth),
            ]
        })
        .collect()
}

/// A blade crossing the body in x in ten steps, leaning a little more or less at each
/// step (by up to 6% of the body's y extent), so every sweep is non-planar (two triangles)
/// and continues the last at an angle. (More lean folds a sweep over itself on pinion.)
pub fn tilting(b: &Aabb, k: usize) -> Blade {
    tilting_in(b, k, 10)
}

/// The blade of [`tilting`] crossing in `steps` steps, leaning as much per step: more
/// steps meet at steeper angles (the MT cut refuses some of 20, see tests/mt_scalpel.rs).
pub fn tilting_in(b: &Aabb, k: usize, steps: usize) -> Blade {
    let (c, d) = (b.center(), b.max - b.min);
    let x = b.min.x - 0.05 * d.x + 1.1 * d.x * k as f64 / steps as f64;
    let tilt = 0.06 * d.y * ((k as f64) * 0.9).sin();
    [
        DVec3::new(x, c.y + tilt, b.min.z - 0.1 * d.z),
        DVec3::new(x, c.y - tilt + 0.01 * d.y, b.max.z + 0.1 * d.z),
    ]
}
