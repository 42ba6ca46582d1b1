//! Comparing an image with raylab's, as a course grades a student's ray tracer against the
//! renders of its own: both images as 8-bit sRGB levels ([`crate::srgb_image`]), the figures
//! of their [`difference`] and a heat map of it, the [`regions`] where they differ, the common
//! [`mistakes`] of a student's tracer, one pixel's difference [`explain`]ed from raylab's ray
//! tree, what the image shows when no mistake accounts for it ([`evidence`]), and all of it
//! together in [`check`], against raylab's images of the scene traced once ([`traces`]).

pub mod check;
pub mod difference;
pub mod evidence;
pub mod explain;
pub mod mistakes;
pub mod regions;
pub mod traces;
