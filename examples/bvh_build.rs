//! Times the BVH build and prints the built tree's SAH cost, without criterion:
//!
//! ```sh
//! cargo run --release --example bvh_build -- [MESH] [--threads N] [--reps N]
//! ```
//!
//! MESH is `bumpy:N` (the generated bumpy sphere of `raylab bench`, N triangles; the default is
//! `bumpy:1000000`), the `NAME_vertices.f32` file of a mesh dumped by `embree_anchor.py --dump`
//! (its `NAME_indices.u32` beside it), e.g. the 1M-triangle soup that BENCHMARKS.md compares
//! with Embree, or any scene `raylab render` reads (a file, `spd:NAME:SIZE`). Each repetition builds the whole [`Bvh`] on a pool of N threads (default 2);
//! the median is printed with the SAH cost of the binary tree the builder made
//! (`Bvh::binary_tree_cost`).

use std::path::Path;
use std::time::Instant;

use glam::Vec3;
use raylab::bvh::Bvh;
use raylab::formats::load_any;
use raylab::large_mesh::bumpy_sphere;
use raylab::mesh::Mesh;
use raylab::primitive::Geometry;

const USAGE: &str =
    "usage: bvh_build [bumpy:N | NAME_vertices.f32 | SCENE] [--threads N] [--reps N]";

fn main() {
    if let Err(e) = run() {
        eprintln!("bvh_build: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), String> {
    let (mut mesh_name, mut threads, mut reps) = ("bumpy:1000000".to_string(), 2, 5);
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut number = |name: &str| -> Result<usize, String> {
            args.next()
                .and_then(|v| v.parse().ok())
                .filter(|&n| n > 0)
                .ok_or(format!("{name} needs a positive whole number\n{USAGE}"))
        };
        match arg.as_str() {
            "--threads" => threads = number("--threads")?,
            "--reps" => reps = number("--reps")?,
            _ if arg.starts_with("--") => return Err(format!("unknown option {arg}\n{USAGE}")),
            _ => mesh_name = arg,
        }
    }
    let geometry = load(&mesh_name)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| e.to_string())?;
    let mut ms: Vec<f64> = (0..reps)
        .map(|_| {
            let start = Instant::now();
            let bvh = pool.install(|| Bvh::build(&geometry));
            let elapsed = start.elapsed().as_secs_f64() * 1e3;
            drop(bvh);
            elapsed
        })
        .collect();
    let times: Vec<String> = ms.iter().map(|t| format!("{t:.1}")).collect();
    ms.sort_by(f64::total_cmp);
    let (cost, nodes) = pool.install(|| Bvh::binary_tree_cost(&geometry));
    println!(
        "{mesh_name}: {} primitives, {threads} threads, build ms {} (median {:.1}), \
         binary nodes {}, SAH cost {:.3}",
        geometry.len(),
        times.join(" "),
        ms[ms.len() / 2],
        nodes,
        cost,
    );
    Ok(())
}

/// The generated bumpy sphere, a mesh dumped by `embree_anchor.py --dump`, or a scene's
/// primitives.
fn load(name: &str) -> Result<Geometry, String> {
    let mesh = if let Some(n) = name.strip_prefix("bumpy:") {
        let n = n
            .parse()
            .map_err(|_| format!("`{name}`: expected bumpy:N"))?;
        bumpy_sphere(n)
    } else if let Some(stem) = name.strip_suffix("_vertices.f32") {
        dumped_mesh(name, &format!("{stem}_indices.u32"))?
    } else {
        return Ok(load_any(name).map_err(|e| e.to_string())?.geometry);
    };
    mesh.validate().map_err(|e| e.to_string())?;
    let mut geometry = Geometry::default();
    geometry.add_mesh(mesh);
    Ok(geometry)
}

/// A mesh as `embree_anchor.py --dump` writes it: vertices and triangles' indices.
fn dumped_mesh(vertices: &str, indices: &str) -> Result<Mesh, String> {
    let words = |path: &str| -> Result<Vec<u32>, String> {
        let bytes = std::fs::read(Path::new(path)).map_err(|e| format!("{path}: {e}"))?;
        Ok(bytes
            .chunks_exact(4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect())
    };
    let positions = words(vertices)?
        .chunks_exact(3)
        .map(|p| {
            Vec3::new(
                f32::from_bits(p[0]),
                f32::from_bits(p[1]),
                f32::from_bits(p[2]),
            )
        })
        .collect();
    let faces = words(indices)?
        .chunks_exact(3)
        .map(|f| [f[0], f[1], f[2]])
        .collect();
    Ok(Mesh {
        positions,
        faces,
        ..Mesh::default()
    })
}
