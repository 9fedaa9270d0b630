//! Prints the split tables of the cut engine as Rust source:
//! `cargo run --example gen_cut_tables > src/cut/tables_generated.rs`.
//! With `--summary`, prints per-case statistics instead (to stderr-friendly text).

use mtcut::cut::table_gen::{generate, render};

fn main() {
    let entries = generate();
    if std::env::args().any(|a| a == "--summary") {
        let mut by_case: std::collections::BTreeMap<String, (usize, usize, usize)> =
            Default::default();
        for e in &entries {
            let r = by_case
                .entry(e.case.name().to_string())
                .or_insert((0, usize::MAX, 0));
            r.0 += 1;
            r.1 = r.1.min(e.children.len());
            r.2 = r.2.max(e.children.len());
        }
        for (case, (n, lo, hi)) in by_case {
            println!("{case:>15}: {n:4} configurations, {lo}..={hi} children");
        }
        return;
    }
    print!("{}", render(&entries));
}
