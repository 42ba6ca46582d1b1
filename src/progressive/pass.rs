//! A pass as every sweep begins and ends it, whatever device traces it: the snapshot an
//! anti-aliasing round compares with, the grid of the pass's pixels, the control told of the
//! pass, and its statistics at the end.

use std::time::Instant;

use super::control::{PassStats, RenderControl};
use super::plan::{Pass, PassGrid, take_snapshot};
use crate::film::Film;
use crate::stats::RayCounts;

/// A pass begun: its grid and its size in grid rows and columns.
pub(crate) struct PassStart<'a> {
    pub grid: PassGrid<'a>,
    pub rows: u32,
    pub columns: u32,
    started: Instant,
    rays_before: RayCounts,
}

impl<'a> PassStart<'a> {
    /// Begins `pass` over `film` of a render that started at `start_block`, its anti-aliasing
    /// rounds comparing pixels against `threshold` with the film as `shown` when they start.
    pub fn new(
        pass: Pass,
        film: &'a Film,
        shown: &'a mut Vec<[u8; 3]>,
        (start_block, threshold): (u32, f32),
        control: &RenderControl,
    ) -> PassStart<'a> {
        let started = Instant::now();
        if let Pass::Refine(_) = pass {
            take_snapshot(film, shown);
        }
        let grid = PassGrid::new(pass, start_block, film, shown, threshold);
        let step = pass.step();
        let (rows, columns) = (film.height().div_ceil(step), film.width().div_ceil(step));
        control.start_pass(step, pass.samples(), rows);
        PassStart {
            grid,
            rows,
            columns,
            started,
            rays_before: control.rays(),
        }
    }

    /// The pass's statistics, once it traced `pixels` pixels.
    pub fn finish(self, control: &RenderControl, pixels: u64) -> PassStats {
        PassStats {
            pass: self.grid.pass,
            pixels,
            rays: control.rays() - self.rays_before,
            time: self.started.elapsed(),
        }
    }
}
