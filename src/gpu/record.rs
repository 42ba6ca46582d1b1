//! The records: the plain structs the GPU reads and writes, each the twin of a WGSL struct of
//! the same name without `Gpu` (`GpuObject` is WGSL's `Object`). `gpu_record!` defines one
//! and records its fields' names and offsets, which the tests compare with naga's layout of
//! the WGSL struct.

/// A struct Rust and WGSL share: its fields' names and byte offsets, as Rust lays it out.
pub trait GpuRecord: bytemuck::Pod {
    /// The Rust struct's name (its WGSL twin's is [`wgsl_name`] of it).
    const NAME: &'static str;

    /// Each field's name and byte offset, in order.
    fn fields() -> Vec<(&'static str, usize)>;
}

/// The name of a record's WGSL twin: the Rust name without `Gpu`.
pub fn wgsl_name<T: GpuRecord>() -> &'static str {
    T::NAME.strip_prefix("Gpu").unwrap_or(T::NAME)
}

/// Defines a record: a `#[repr(C)]` struct of plain bytes, with [`GpuRecord`] written from its
/// fields.
macro_rules! gpu_record {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            $( $(#[$field_meta:meta])* $field_vis:vis $field:ident : $ty:ty ),* $(,)?
        }
    ) => {
        $(#[$meta])*
        #[repr(C)]
        #[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
        pub struct $name {
            $( $(#[$field_meta])* $field_vis $field: $ty ),*
        }

        impl $crate::gpu::record::GpuRecord for $name {
            const NAME: &'static str = stringify!($name);

            fn fields() -> Vec<(&'static str, usize)> {
                vec![$((stringify!($field), std::mem::offset_of!($name, $field))),*]
            }
        }
    };
}

pub(crate) use gpu_record;
