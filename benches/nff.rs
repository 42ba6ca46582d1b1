//! The NFF reader on a large file: SPD's `rings` at size factor 12, about 39,000 primitives, read
//! from text into a scene (the claim that tens of thousands of primitives parse in well under a
//! second; `tests/library/nff.rs` checks that they all arrive).

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use raylab::formats::nff::{NffLighting, parse_nff};
use raylab::formats::spd::Database;

fn nff(c: &mut Criterion) {
    let text = Database::Rings
        .generate(12)
        .expect("SPD's rings generate")
        .to_nff_string();
    c.bench_function("parse rings-12.nff (39,000 primitives)", |b| {
        b.iter(|| {
            parse_nff(
                black_box(&text),
                Path::new("rings-12.nff"),
                NffLighting::Readme,
            )
        })
    });
}

criterion_group!(benches, nff);
criterion_main!(benches);
