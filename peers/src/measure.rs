//! Timing one tracer on one mesh: its build and each ray set at 1 and 2 threads, medians of
//! `reps` runs, its answers checked against Embree's and its nodes visited per ray.

use std::time::Instant;

use rayon::ThreadPool;
use rayon::prelude::*;

use crate::anchor::{AnchorMesh, RaySet};
use crate::tracer::{Tracer, WalkCost};

/// The thread counts compared.
pub const THREADS: [usize; 2] = [1, 2];

/// Rays per task handed to a thread.
const CHUNK: usize = 4096;

/// Rays of a tile, traced together by a packet tracer.
const PACKET: usize = 64;

/// Every this many rays one is traced again, untimed, counting nodes and triangles (counting all
/// would take long).
const NODE_SAMPLE_STRIDE: usize = 16;

/// One ray set traced by one tracer.
pub struct SetResult {
    pub set: String,
    pub rays: usize,
    /// Median Mrays/s per entry of [`THREADS`].
    pub mrays: [f64; 2],
    /// Rays whose answer differs from Embree's.
    pub mismatches: usize,
    /// Mean interior nodes visited and triangles tested per ray, over a sample of the rays.
    pub cost_per_ray: Option<(f64, f64)>,
}

/// Everything measured of one tracer on one mesh.
pub struct TracerReport {
    pub name: &'static str,
    /// Median build milliseconds per entry of [`THREADS`].
    pub build_ms: [f64; 2],
    pub sets: Vec<SetResult>,
}

/// Builds `T` over `mesh` and traces all its ray sets; `pools` has one pool per [`THREADS`].
pub fn measure<T: Tracer>(
    mesh: &AnchorMesh,
    pools: &[ThreadPool; 2],
    reps: usize,
) -> Result<TracerReport, String> {
    let mut build_ms = [0.0; 2];
    let mut tracer = None;
    for (k, pool) in pools.iter().enumerate() {
        let mut times = Vec::with_capacity(reps);
        for _ in 0..reps {
            drop(tracer.take()); // free the last tree before building the next
            let start = Instant::now();
            tracer = Some(pool.install(|| T::build(mesh))?);
            times.push(start.elapsed().as_secs_f64() * 1e3);
        }
        build_ms[k] = median(times);
    }
    let tracer = tracer.ok_or("no repetitions")?;
    let sets = mesh
        .ray_sets
        .iter()
        .map(|set| trace_set(&tracer, set, pools, reps))
        .collect();
    Ok(TracerReport {
        name: T::NAME,
        build_ms,
        sets,
    })
}

fn trace_set<T: Tracer>(
    tracer: &T,
    set: &RaySet,
    pools: &[ThreadPool; 2],
    reps: usize,
) -> SetResult {
    let mut mrays = [0.0; 2];
    let mut answers = Vec::new();
    for (k, pool) in pools.iter().enumerate() {
        let mut times = Vec::with_capacity(reps);
        for _ in 0..reps {
            let start = Instant::now();
            answers = pool.install(|| {
                if set.in_tiles {
                    let mut answers = vec![0; set.rays.len()];
                    answers
                        .par_chunks_mut(PACKET)
                        .zip(set.rays.par_chunks(PACKET))
                        .with_min_len(CHUNK / PACKET)
                        .for_each(|(answers, rays)| tracer.closest_in_packet(rays, answers));
                    answers
                } else {
                    set.rays
                        .par_iter()
                        .with_min_len(CHUNK)
                        .map(|ray| tracer.answer(ray, set.query))
                        .collect::<Vec<i32>>()
                }
            });
            times.push(start.elapsed().as_secs_f64());
        }
        mrays[k] = set.rays.len() as f64 / median(times) / 1e6;
    }
    let mismatches = answers
        .iter()
        .zip(&set.embree)
        .filter(|(ours, embree)| ours != embree)
        .count();
    let sample: Option<Vec<WalkCost>> = set
        .rays
        .iter()
        .step_by(NODE_SAMPLE_STRIDE)
        .map(|ray| tracer.cost(ray, set.query))
        .collect();
    let cost_per_ray = sample.map(|costs| {
        let n = costs.len().max(1) as f64;
        let sum = |f: fn(&WalkCost) -> u32| costs.iter().map(|c| f64::from(f(c))).sum::<f64>() / n;
        (sum(|c| c.nodes), sum(|c| c.triangles))
    });
    SetResult {
        set: set.name.clone(),
        rays: set.rays.len(),
        mrays,
        mismatches,
        cost_per_ray,
    }
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        values[n / 2]
    } else {
        (values[n / 2 - 1] + values[n / 2]) / 2.0
    }
}
