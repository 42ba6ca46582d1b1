//! What colour a pixel sample gets, on either sweep: the trait [`SampleColoring`] (the
//! shaded image, [`Shaded`], or a debug view), which the CPU sweep calls for each packet of eye
//! rays and the GPU sweep for the samples its driver cuts short.

use crate::color::Color;
use crate::item_buffer::Item;
use crate::ray::Ray;
use crate::stats::RayCounts;
use crate::whitted::Tracer;

/// What the renderer writes for the pixel samples whose eye rays it traces: the shaded image
/// ([`Shaded`]) or another view of the scene.
pub trait SampleColoring: Sync {
    /// The colours of the neighbouring eye rays `rays` (up to [`crate::bvh::packet::PACKET_SIZE`]), into `colors`,
    /// counting the rays traced into `counts`. `items` holds each ray's pixel's item from the
    /// tracer's item buffer (`None` without one).
    fn shade(
        &self,
        tracer: &Tracer,
        rays: &[Ray],
        items: &[Option<Item>],
        colors: &mut [Color],
        counts: &mut RayCounts,
    );
}

/// The shaded image: the Whitted colour of each eye ray, the eye rays traced as one packet
/// ([`Tracer::trace_eye_packet`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Shaded;

impl SampleColoring for Shaded {
    #[inline]
    fn shade(
        &self,
        tracer: &Tracer,
        rays: &[Ray],
        items: &[Option<Item>],
        colors: &mut [Color],
        counts: &mut RayCounts,
    ) {
        tracer.trace_eye_packet(rays, items, colors, counts);
    }
}
