//! Blade positions shared by the scalpel tests of plain meshes (tests/cut_scalpel.rs) and of
//! the MT (tests/mt_scalpel.rs), so both move the same blades through the same bodies.
#![allow(dead_code)] // each test binary uses its own subset

use mtcut::cut::Blade;
use mtcut::geom::{Aabb, DVec3, SWEEP_PLANARITY, scalpel_sweep};

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

/// A blade from above the body down to 45 % of its height, on [`on_arc`] turning by `deg`
/// degrees per step from -8°: a shallow turning incision, its blade's edge inside the
/// body; 17 steps.
pub fn shallow_turning(b: &Aabb, deg: f64) -> Vec<Blade> {
    let depth = b.min.z + 0.45 * (b.max.z - b.min.z);
    (0..18)
        .map(|k| {
            let [_, top] = on_arc(b, -8.0 + deg * k as f64);
            [top, DVec3::new(top.x, top.y, depth)]
        })
        .collect()
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

/// A random scalpel path through `b`, drawn by `unit` (uniform in (0, 1)): a blade whose
/// centre starts outside the box and moves towards it along a heading that turns by a
/// random rate, the blade's direction (mostly along z, leaning to one side by a random
/// angle that drifts) and its half-length (spanning the body's depth, or stopping inside
/// it) random; steps of a random length between 0.2% and 5% of the diagonal, each divided
/// into as few equal steps as keep its sweep from folding over itself.
pub fn random_path(b: &Aabb, mut unit: impl FnMut() -> f64) -> Vec<Blade> {
    use std::f64::consts::PI;
    let mut range = |a: f64, b: f64| a + (b - a) * unit();
    let (c, d) = (b.center(), b.max - b.min);
    let diag = b.diagonal();
    let heading0 = range(0.0, 2.0 * PI);
    let start = c - DVec3::new(heading0.cos(), heading0.sin(), 0.0) * (0.6 * diag);
    let turn = range(-8.0, 8.0).to_radians();
    let step = diag * range(0.002, 0.05);
    let half = if range(0.0, 1.0) < 0.5 {
        0.7 * d.z
    } else {
        0.3 * d.z
    };
    // The lean drifts slowly enough for the blade's ends to move forwards at every step
    // (a sweep folding over itself is refused).
    let (lean0, drift) = (range(-0.3, 0.3), range(-0.3, 0.3) * step / half);
    let side = range(0.0, 2.0 * PI);
    let steps = ((1.3 * diag / step) as usize).clamp(8, 120);
    let (mut p, mut heading, mut lean) = (start, heading0, lean0);
    let coarse: Vec<Blade> = (0..=steps)
        .map(|_| {
            // Leaning towards a fixed side (not turning with the heading, which would swing
            // the blade's ends about its middle: a sweep folding over itself).
            let axis = DVec3::new(lean.sin() * side.cos(), lean.sin() * side.sin(), lean.cos());
            let blade = [
                p + axis * half,
                p - axis * half + DVec3::new(0.0, 0.0, 0.2 * d.z),
            ];
            p += DVec3::new(heading.cos(), heading.sin(), 0.0) * step;
            heading += turn;
            lean = (lean + drift).clamp(-0.5, 0.5);
            blade
        })
        .collect();
    let mut path = vec![coarse[0]];
    for w in coarse.windows(2) {
        path.extend(unfolded(w[0], w[1]).into_iter().skip(1));
    }
    path
}

/// The blade positions from `a` to `b` in as few equal steps (1, 2, 4, ...) as keep every
/// sweep from folding over itself (which the sweep refuses: "use smaller steps").
fn unfolded(a: Blade, b: Blade) -> Vec<Blade> {
    let lerp = |t: f64| [a[0].lerp(b[0], t), a[1].lerp(b[1], t)];
    for n in [1usize, 2, 4, 8, 16] {
        let path: Vec<Blade> = (0..=n).map(|k| lerp(k as f64 / n as f64)).collect();
        if path
            .windows(2)
            .all(|w| scalpel_sweep(w[0], w[1], SWEEP_PLANARITY).is_ok())
        {
            return path;
        }
    }
    panic!("a blade step that folds however finely it is divided: {a:?} -> {b:?}");
}
