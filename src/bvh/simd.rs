//! The instruction sets the traversal can use, chosen when the program runs. A release build
//! targets the baseline of its architecture (SSE2 on x86-64), so that it runs on any machine;
//! the traversal is compiled once more for each wider instruction set and the widest the
//! processor has is picked by CPU detection ([`Simd::best`]).
//!
//! The box test of an eight-wide node works on [`Lanes`]: eight `f32`s, one per child. Each
//! instruction set has its own lane type with the same arithmetic in the same order, so every
//! path gives exactly the same answers (the tests run every path the machine has and compare).

use strum::{IntoEnumIterator, VariantNames};

/// Lanes of the box test: one per child of a node.
pub const LANES: usize = 8;

/// An instruction set the traversal is compiled for, narrowest first. `RAYLAB_SIMD` and
/// `raylab bench` name it in lower case (`avx2`).
#[derive(
    Clone,
    Copy,
    Debug,
    Default,
    PartialEq,
    Eq,
    Hash,
    strum::Display,
    strum::EnumString,
    strum::EnumIter,
    strum::VariantNames,
)]
#[strum(serialize_all = "lowercase", parse_err_ty = String, parse_err_fn = unknown_simd)]
pub enum Simd {
    /// Plain scalar code, the same on every architecture: the reference the others must match.
    #[default]
    Portable,
    /// x86-64's baseline: two four-lane SSE registers per eight lanes.
    Sse,
    /// One eight-lane AVX2 register.
    Avx2,
    /// AVX2's registers with AVX-512's comparisons into mask registers (AVX-512 F and VL).
    Avx512,
}

impl Simd {
    /// Whether this processor can run the path.
    pub fn is_supported(self) -> bool {
        match self {
            Simd::Portable => true,
            #[cfg(target_arch = "x86_64")]
            Simd::Sse => true,
            #[cfg(target_arch = "x86_64")]
            Simd::Avx2 => std::arch::is_x86_feature_detected!("avx2"),
            #[cfg(target_arch = "x86_64")]
            Simd::Avx512 => {
                std::arch::is_x86_feature_detected!("avx512f")
                    && std::arch::is_x86_feature_detected!("avx512vl")
            }
            #[cfg(not(target_arch = "x86_64"))]
            _ => false,
        }
    }

    /// The paths this processor can run, narrowest first.
    pub fn supported() -> impl Iterator<Item = Simd> {
        Simd::iter().filter(|simd| simd.is_supported())
    }

    /// The path a new BVH uses: the one named by the environment variable `RAYLAB_SIMD`
    /// (`portable`, `sse`, `avx2`, `avx512`) when set and supported, else the widest supported.
    pub fn best() -> Simd {
        static BEST: std::sync::OnceLock<Simd> = std::sync::OnceLock::new();
        *BEST.get_or_init(|| {
            let widest = Simd::supported().last().unwrap_or(Simd::Portable);
            match std::env::var("RAYLAB_SIMD") {
                Ok(name) => match name.parse::<Simd>() {
                    Ok(simd) if simd.is_supported() => simd,
                    _ => {
                        eprintln!(
                            "warning: RAYLAB_SIMD={name} is not a path this processor runs \
                             (one of: {}); using {widest}",
                            Simd::supported()
                                .map(|simd| simd.to_string())
                                .collect::<Vec<_>>()
                                .join(", "),
                        );
                        widest
                    }
                },
                Err(_) => widest,
            }
        })
    }
}

/// Why `s` is no path's name.
fn unknown_simd(s: &str) -> String {
    format!("`{s}` is not one of {}", Simd::VARIANTS.join(", "))
}

/// A traversal written once for any lane type and compiled once per instruction set:
/// [`dispatch`] runs it with the lanes of the path chosen. `run` must be `#[inline(always)]`,
/// so that it is compiled into each path's function with that path's instruction set.
pub(super) trait Kernel {
    type Output;
    fn run<L: Lanes>(self) -> Self::Output;
}

/// Runs `kernel` on the `simd` path, which the processor must support ([`Simd::is_supported`];
/// [`super::Bvh::set_simd`] makes sure of it).
#[inline(always)]
pub(super) fn dispatch<K: Kernel>(simd: Simd, kernel: K) -> K::Output {
    match simd {
        #[cfg(target_arch = "x86_64")]
        Simd::Sse => kernel.run::<Sse>(),
        // SAFETY: a BVH's path is one that CPU detection found the processor supports.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2 => unsafe { x86::run_avx2(kernel) },
        #[cfg(target_arch = "x86_64")]
        Simd::Avx512 => unsafe { x86::run_avx512(kernel) },
        _ => kernel.run::<Portable>(),
    }
}

/// Eight `f32` lanes and the few operations the box test needs. `min` and `max` follow the
/// x86 rule (`a < b ? a : b`, so a NaN in either gives `b`), which every implementation keeps.
///
/// # Safety
/// The methods are `unsafe` because those of the AVX lane types are compiled for AVX2 or
/// AVX-512 (`#[target_feature]`, so that they are inlined into their path's kernel as single
/// instructions): call them only inside a kernel run by [`dispatch`], which runs each lane type
/// only on a processor that has its instructions.
pub(super) trait Lanes: Copy {
    unsafe fn load(values: &[f32; LANES]) -> Self;
    unsafe fn splat(value: f32) -> Self;
    unsafe fn sub(self, other: Self) -> Self;
    unsafe fn mul(self, other: Self) -> Self;
    unsafe fn min(self, other: Self) -> Self;
    unsafe fn max(self, other: Self) -> Self;
    /// Bit k set where lane k of `self` ≤ lane k of `other`.
    unsafe fn le_mask(self, other: Self) -> u32;
    /// Lane k of `self` where it is ≤ lane k of `other`, else lane k of `otherwise`.
    unsafe fn le_or(self, other: Self, otherwise: Self) -> Self;
    unsafe fn to_array(self) -> [f32; LANES];
}

/// The scalar reference.
#[derive(Clone, Copy)]
pub(super) struct Portable([f32; LANES]);

impl Lanes for Portable {
    #[inline(always)]
    unsafe fn load(values: &[f32; LANES]) -> Self {
        Portable(*values)
    }
    #[inline(always)]
    unsafe fn splat(value: f32) -> Self {
        Portable([value; LANES])
    }
    #[inline(always)]
    unsafe fn sub(self, other: Self) -> Self {
        Portable(std::array::from_fn(|k| self.0[k] - other.0[k]))
    }
    #[inline(always)]
    unsafe fn mul(self, other: Self) -> Self {
        Portable(std::array::from_fn(|k| self.0[k] * other.0[k]))
    }
    #[inline(always)]
    unsafe fn min(self, other: Self) -> Self {
        Portable(std::array::from_fn(|k| {
            if self.0[k] < other.0[k] {
                self.0[k]
            } else {
                other.0[k]
            }
        }))
    }
    #[inline(always)]
    unsafe fn max(self, other: Self) -> Self {
        Portable(std::array::from_fn(|k| {
            if self.0[k] > other.0[k] {
                self.0[k]
            } else {
                other.0[k]
            }
        }))
    }
    #[inline(always)]
    unsafe fn le_mask(self, other: Self) -> u32 {
        (0..LANES).fold(0, |mask, k| mask | u32::from(self.0[k] <= other.0[k]) << k)
    }
    #[inline(always)]
    unsafe fn le_or(self, other: Self, otherwise: Self) -> Self {
        Portable(std::array::from_fn(|k| {
            if self.0[k] <= other.0[k] {
                self.0[k]
            } else {
                otherwise.0[k]
            }
        }))
    }
    #[inline(always)]
    unsafe fn to_array(self) -> [f32; LANES] {
        self.0
    }
}

#[cfg(target_arch = "x86_64")]
use x86::Sse;

/// The x86-64 lane types. Their methods are only called from functions compiled with the
/// matching `#[target_feature]` (see `traverse`), into which they are inlined.
#[cfg(target_arch = "x86_64")]
mod x86 {
    use std::arch::x86_64::*;

    use super::{Kernel, LANES, Lanes};

    /// `kernel` compiled for AVX2.
    #[target_feature(enable = "avx2")]
    pub(super) fn run_avx2<K: Kernel>(kernel: K) -> K::Output {
        kernel.run::<Avx2>()
    }

    /// `kernel` compiled for AVX-512 (F and VL), on AVX2's eight lanes.
    #[target_feature(enable = "avx2,avx512f,avx512vl")]
    pub(super) fn run_avx512<K: Kernel>(kernel: K) -> K::Output {
        kernel.run::<Avx512>()
    }

    /// Two SSE registers: lanes 0–3 and 4–7.
    #[derive(Clone, Copy)]
    pub(in crate::bvh) struct Sse(__m128, __m128);

    // SAFETY (all `unsafe` blocks of `Sse`): SSE is part of every x86-64 processor.
    impl Lanes for Sse {
        #[inline(always)]
        unsafe fn load(values: &[f32; LANES]) -> Self {
            let p = values.as_ptr();
            unsafe { Sse(_mm_loadu_ps(p), _mm_loadu_ps(p.add(4))) }
        }
        #[inline(always)]
        unsafe fn splat(value: f32) -> Self {
            unsafe { Sse(_mm_set1_ps(value), _mm_set1_ps(value)) }
        }
        #[inline(always)]
        unsafe fn sub(self, o: Self) -> Self {
            unsafe { Sse(_mm_sub_ps(self.0, o.0), _mm_sub_ps(self.1, o.1)) }
        }
        #[inline(always)]
        unsafe fn mul(self, o: Self) -> Self {
            unsafe { Sse(_mm_mul_ps(self.0, o.0), _mm_mul_ps(self.1, o.1)) }
        }
        #[inline(always)]
        unsafe fn min(self, o: Self) -> Self {
            unsafe { Sse(_mm_min_ps(self.0, o.0), _mm_min_ps(self.1, o.1)) }
        }
        #[inline(always)]
        unsafe fn max(self, o: Self) -> Self {
            unsafe { Sse(_mm_max_ps(self.0, o.0), _mm_max_ps(self.1, o.1)) }
        }
        #[inline(always)]
        unsafe fn le_mask(self, o: Self) -> u32 {
            unsafe {
                let low = _mm_movemask_ps(_mm_cmple_ps(self.0, o.0)) as u32;
                let high = _mm_movemask_ps(_mm_cmple_ps(self.1, o.1)) as u32;
                low | high << 4
            }
        }
        #[inline(always)]
        unsafe fn le_or(self, o: Self, otherwise: Self) -> Self {
            // SSE2 has no blend: (self and mask) or (otherwise and not mask).
            let pick = |a: __m128, b: __m128, or: __m128| unsafe {
                let mask = _mm_cmple_ps(a, b);
                _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, or))
            };
            Sse(
                pick(self.0, o.0, otherwise.0),
                pick(self.1, o.1, otherwise.1),
            )
        }
        #[inline(always)]
        unsafe fn to_array(self) -> [f32; LANES] {
            let mut out = [0.0; LANES];
            unsafe {
                _mm_storeu_ps(out.as_mut_ptr(), self.0);
                _mm_storeu_ps(out.as_mut_ptr().add(4), self.1);
            }
            out
        }
    }

    /// One AVX register.
    #[derive(Clone, Copy)]
    pub(in crate::bvh) struct Avx2(__m256);

    // SAFETY (all `unsafe` blocks of `Avx2` and `Avx512`): only reached from functions compiled
    // with `target_feature(enable = "avx2")` (and "avx512f,avx512vl" for `Avx512`), which the
    // dispatch calls only after CPU detection found the features.
    impl Lanes for Avx2 {
        #[inline]
        #[target_feature(enable = "avx2")]
        unsafe fn load(values: &[f32; LANES]) -> Self {
            unsafe { Avx2(_mm256_loadu_ps(values.as_ptr())) }
        }
        #[inline]
        #[target_feature(enable = "avx2")]
        unsafe fn splat(value: f32) -> Self {
            Avx2(_mm256_set1_ps(value))
        }
        #[inline]
        #[target_feature(enable = "avx2")]
        unsafe fn sub(self, o: Self) -> Self {
            Avx2(_mm256_sub_ps(self.0, o.0))
        }
        #[inline]
        #[target_feature(enable = "avx2")]
        unsafe fn mul(self, o: Self) -> Self {
            Avx2(_mm256_mul_ps(self.0, o.0))
        }
        #[inline]
        #[target_feature(enable = "avx2")]
        unsafe fn min(self, o: Self) -> Self {
            Avx2(_mm256_min_ps(self.0, o.0))
        }
        #[inline]
        #[target_feature(enable = "avx2")]
        unsafe fn max(self, o: Self) -> Self {
            Avx2(_mm256_max_ps(self.0, o.0))
        }
        #[inline]
        #[target_feature(enable = "avx2")]
        unsafe fn le_mask(self, o: Self) -> u32 {
            _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(self.0, o.0)) as u32
        }
        #[inline]
        #[target_feature(enable = "avx2")]
        unsafe fn le_or(self, o: Self, otherwise: Self) -> Self {
            let mask = _mm256_cmp_ps::<_CMP_LE_OQ>(self.0, o.0);
            Avx2(_mm256_blendv_ps(otherwise.0, self.0, mask))
        }
        #[inline]
        #[target_feature(enable = "avx2")]
        unsafe fn to_array(self) -> [f32; LANES] {
            let mut out = [0.0; LANES];
            unsafe { _mm256_storeu_ps(out.as_mut_ptr(), self.0) };
            out
        }
    }

    /// An AVX register whose comparison writes an AVX-512 mask register directly.
    #[derive(Clone, Copy)]
    pub(in crate::bvh) struct Avx512(Avx2);

    impl Lanes for Avx512 {
        #[inline]
        #[target_feature(enable = "avx2,avx512f,avx512vl")]
        unsafe fn load(values: &[f32; LANES]) -> Self {
            Avx512(unsafe { Avx2::load(values) })
        }
        #[inline]
        #[target_feature(enable = "avx2,avx512f,avx512vl")]
        unsafe fn splat(value: f32) -> Self {
            Avx512(unsafe { Avx2::splat(value) })
        }
        #[inline]
        #[target_feature(enable = "avx2,avx512f,avx512vl")]
        unsafe fn sub(self, o: Self) -> Self {
            Avx512(unsafe { self.0.sub(o.0) })
        }
        #[inline]
        #[target_feature(enable = "avx2,avx512f,avx512vl")]
        unsafe fn mul(self, o: Self) -> Self {
            Avx512(unsafe { self.0.mul(o.0) })
        }
        #[inline]
        #[target_feature(enable = "avx2,avx512f,avx512vl")]
        unsafe fn min(self, o: Self) -> Self {
            Avx512(unsafe { self.0.min(o.0) })
        }
        #[inline]
        #[target_feature(enable = "avx2,avx512f,avx512vl")]
        unsafe fn max(self, o: Self) -> Self {
            Avx512(unsafe { self.0.max(o.0) })
        }
        #[inline]
        #[target_feature(enable = "avx2,avx512f,avx512vl")]
        unsafe fn le_mask(self, o: Self) -> u32 {
            u32::from(_mm256_cmp_ps_mask::<_CMP_LE_OQ>(self.0.0, o.0.0))
        }
        #[inline]
        #[target_feature(enable = "avx2,avx512f,avx512vl")]
        unsafe fn le_or(self, o: Self, otherwise: Self) -> Self {
            let mask = _mm256_cmp_ps_mask::<_CMP_LE_OQ>(self.0.0, o.0.0);
            Avx512(Avx2(_mm256_mask_blend_ps(mask, otherwise.0.0, self.0.0)))
        }
        #[inline]
        #[target_feature(enable = "avx2,avx512f,avx512vl")]
        unsafe fn to_array(self) -> [f32; LANES] {
            unsafe { self.0.to_array() }
        }
    }
}
