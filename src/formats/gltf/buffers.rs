//! The bytes behind a glTF file's accessors: its buffers (the GLB's binary chunk, `data:` URIs,
//! or files beside the model), and reading an accessor's elements out of them. Every range an
//! accessor names (its view in its buffer, its elements in its view, the sparse parts) is
//! checked with checked arithmetic before a byte is read, so a file that lies about its sizes
//! gets an error naming the accessor, never a read past the end.

use std::borrow::Cow;
use std::path::Path;

use base64::Engine;
use gltf::accessor::{DataType, Dimensions};
use gltf::buffer::Source;

use crate::formats::SceneFiles;

/// Reads every buffer of `document`, in order: `blob` for the GLB's binary chunk, the others
/// from their URIs, relative to `folder`. Each is cut to its declared `byteLength`, which it
/// must hold.
pub(super) fn load_buffers<'a>(
    document: &gltf::Document,
    blob: Option<&'a [u8]>,
    folder: &Path,
    files: SceneFiles<'a>,
) -> Result<Vec<Cow<'a, [u8]>>, String> {
    let mut buffers = Vec::with_capacity(document.buffers().len());
    for buffer in document.buffers() {
        let what = format!("buffer {}", buffer.index());
        let bytes: Cow<'a, [u8]> = match buffer.source() {
            Source::Bin => Cow::Borrowed(blob.ok_or_else(|| {
                format!("{what} is the GLB's binary chunk, but the file has none")
            })?),
            Source::Uri(uri) => read_uri(uri, folder, files).map_err(|e| format!("{what}: {e}"))?,
        };
        let length = buffer.length();
        if bytes.len() < length {
            return Err(format!(
                "{what} holds {} bytes, fewer than its byteLength of {length}",
                bytes.len()
            ));
        }
        buffers.push(match bytes {
            Cow::Borrowed(b) => Cow::Borrowed(&b[..length]),
            Cow::Owned(mut b) => {
                b.truncate(length);
                Cow::Owned(b)
            }
        });
    }
    Ok(buffers)
}

/// The bytes a URI names: a base64 `data:` URI, or a file relative to `folder` (with `%20`-style
/// escapes decoded). Network addresses are refused: a model file fetches nothing.
pub(super) fn read_uri<'a>(
    uri: &str,
    folder: &Path,
    files: SceneFiles<'a>,
) -> Result<Cow<'a, [u8]>, String> {
    if let Some(data) = uri.strip_prefix("data:") {
        let (header, payload) = data
            .split_once(',')
            .ok_or("a data: URI without a `,` before its data")?;
        if !header.ends_with(";base64") {
            return Err("a data: URI that is not base64".to_string());
        }
        return base64::engine::general_purpose::STANDARD
            .decode(payload)
            .map(Cow::Owned)
            .map_err(|e| format!("its data: URI is not valid base64 ({e})"));
    }
    if uri.contains("://") {
        return Err(format!(
            "`{uri}` is a network address; raylab reads only files beside the model"
        ));
    }
    let name = percent_decoded(uri)?;
    let path = folder.join(&name);
    files
        .read(&path)
        .map_err(|e| format!("cannot read `{}`: {e}", path.display()))
}

/// `uri` with its `%XX` escapes decoded (a space is `%20` in a URI).
fn percent_decoded(uri: &str) -> Result<String, String> {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("`{uri}` has a `%` not followed by two hex digits"))?;
            out.push(hex);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| format!("`{uri}` does not decode to UTF-8"))
}

/// What an accessor must be to be read as one kind of data.
pub(super) struct Wanted {
    /// The data's name in messages (`POSITION`).
    pub what: &'static str,
    pub dimensions: &'static [Dimensions],
    /// Component types and whether each must be `normalized` (colours and texture coordinates
    /// stored as integers are fractions of the type's largest value).
    pub types: &'static [(DataType, bool)],
}

pub(super) const POSITIONS: Wanted = Wanted {
    what: "POSITION",
    dimensions: &[Dimensions::Vec3],
    types: &[(DataType::F32, false)],
};
pub(super) const NORMALS: Wanted = Wanted {
    what: "NORMAL",
    dimensions: &[Dimensions::Vec3],
    types: &[(DataType::F32, false)],
};
pub(super) const TEX_COORDS: Wanted = Wanted {
    what: "TEXCOORD_0",
    dimensions: &[Dimensions::Vec2],
    types: &[
        (DataType::F32, false),
        (DataType::U8, true),
        (DataType::U16, true),
    ],
};
pub(super) const COLORS: Wanted = Wanted {
    what: "COLOR_0",
    dimensions: &[Dimensions::Vec3, Dimensions::Vec4],
    types: &[
        (DataType::F32, false),
        (DataType::U8, true),
        (DataType::U16, true),
    ],
};
pub(super) const INDICES: Wanted = Wanted {
    what: "indices",
    dimensions: &[Dimensions::Scalar],
    types: &[
        (DataType::U8, false),
        (DataType::U16, false),
        (DataType::U32, false),
    ],
};

/// The components of an accessor's elements, `count × dimensions` floats in element order (an
/// integer index is exact up to 2^24, so indices are read with [`read_indices`]).
pub(super) fn read_floats(
    accessor: &gltf::Accessor,
    buffers: &[Cow<[u8]>],
    wanted: &Wanted,
) -> Result<Vec<f32>, String> {
    read_components(accessor, buffers, wanted, |bytes, data_type| {
        let normalized = accessor.normalized();
        match data_type {
            DataType::U8 if normalized => f32::from(bytes[0]) / 255.0,
            DataType::U16 if normalized => {
                f32::from(u16::from_le_bytes([bytes[0], bytes[1]])) / 65535.0
            }
            _ => f32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]),
        }
    })
}

/// The vertex indices of an `indices` accessor.
pub(super) fn read_indices(
    accessor: &gltf::Accessor,
    buffers: &[Cow<[u8]>],
) -> Result<Vec<u32>, String> {
    read_components(accessor, buffers, &INDICES, |bytes, data_type| {
        unsigned(bytes, data_type)
    })
}

/// An unsigned integer component of `data_type` at the start of `bytes`.
fn unsigned(bytes: &[u8], data_type: DataType) -> u32 {
    match data_type {
        DataType::U8 => u32::from(bytes[0]),
        DataType::U16 => u32::from(u16::from_le_bytes([bytes[0], bytes[1]])),
        _ => u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]),
    }
}

/// Reads every component of `accessor` with `read` (given the component's bytes, which are
/// as many as its type takes), after checking it is what `wanted` allows and every range it
/// names lies inside its buffers; sparse substitutions are applied.
fn read_components<T: Copy + Default>(
    accessor: &gltf::Accessor,
    buffers: &[Cow<[u8]>],
    wanted: &Wanted,
    read: impl Fn(&[u8], DataType) -> T,
) -> Result<Vec<T>, String> {
    let what = format!("accessor {} ({})", accessor.index(), wanted.what);
    let (data_type, dimensions) = (accessor.data_type(), accessor.dimensions());
    if !wanted.dimensions.contains(&dimensions) {
        return Err(format!(
            "{what} holds {dimensions:?} elements; expected {:?}",
            wanted.dimensions
        ));
    }
    if !wanted
        .types
        .iter()
        .any(|&(t, normalized)| t == data_type && (!normalized || accessor.normalized()))
    {
        return Err(format!(
            "{what} holds {data_type:?} components{}; expected one of {:?} (integers normalized)",
            if accessor.normalized() {
                ", normalized"
            } else {
                ""
            },
            wanted.types.iter().map(|(t, _)| t).collect::<Vec<_>>()
        ));
    }
    let component = data_type.size();
    let width = dimensions.multiplicity();
    let element = component * width;
    let count = accessor.count();
    let total = count
        .checked_mul(width)
        .filter(|_| count > 0)
        .ok_or_else(|| format!("{what} has a count of {count}"))?;
    crate::memory::check(
        &format!("{what} of {count} elements"),
        (total * std::mem::size_of::<T>()) as u64,
    )?;
    let mut values = vec![T::default(); total];
    if let Some(view) = accessor.view() {
        let bytes = view_elements(&view, buffers, accessor.offset(), count, element)
            .map_err(|e| format!("{what}: {e}"))?;
        let stride = view.stride().unwrap_or(element);
        for (i, value) in values.chunks_exact_mut(width).enumerate() {
            let start = i * stride;
            for (k, slot) in value.iter_mut().enumerate() {
                let at = start + k * component;
                *slot = read(&bytes[at..at + component], data_type);
            }
        }
    }
    if let Some(sparse) = accessor.sparse() {
        let substitutes = sparse.count();
        if substitutes == 0 || substitutes > count {
            return Err(format!(
                "{what}: {substitutes} sparse substitutes for {count} elements"
            ));
        }
        let indices = sparse.indices();
        let index_type = match indices.index_type() {
            gltf::accessor::sparse::IndexType::U8 => DataType::U8,
            gltf::accessor::sparse::IndexType::U16 => DataType::U16,
            gltf::accessor::sparse::IndexType::U32 => DataType::U32,
        };
        let index_size = index_type.size();
        let index_bytes = view_elements(
            &indices.view(),
            buffers,
            indices.offset(),
            substitutes,
            index_size,
        )
        .map_err(|e| format!("{what}: its sparse indices: {e}"))?;
        let values_view = sparse.values().view();
        let value_bytes = view_elements(
            &values_view,
            buffers,
            sparse.values().offset(),
            substitutes,
            element,
        )
        .map_err(|e| format!("{what}: its sparse values: {e}"))?;
        for s in 0..substitutes {
            let index_at = s * indices.view().stride().unwrap_or(index_size);
            let index = unsigned(&index_bytes[index_at..index_at + index_size], index_type);
            let index = index as usize;
            if index >= count {
                return Err(format!(
                    "{what}: sparse index {index} is past its {count} elements"
                ));
            }
            let value_at = s * values_view.stride().unwrap_or(element);
            for k in 0..width {
                let at = value_at + k * component;
                values[index * width + k] = read(&value_bytes[at..at + component], data_type);
            }
        }
    }
    Ok(values)
}

/// The bytes of `count` elements of `element` bytes each, starting `offset` bytes into `view`
/// and `stride` apart (the view's, else packed): checked to lie inside the view, and the view
/// inside its buffer.
fn view_elements<'b>(
    view: &gltf::buffer::View,
    buffers: &'b [Cow<[u8]>],
    offset: usize,
    count: usize,
    element: usize,
) -> Result<&'b [u8], String> {
    let buffer = buffers
        .get(view.buffer().index())
        .ok_or("its view's buffer is missing")?;
    let view_end = view
        .offset()
        .checked_add(view.length())
        .filter(|&end| end <= buffer.len())
        .ok_or_else(|| {
            format!(
                "buffer view {} (bytes {} to {} + {}) reaches past its buffer's {} bytes",
                view.index(),
                view.offset(),
                view.offset(),
                view.length(),
                buffer.len()
            )
        })?;
    let view_bytes = &buffer[view.offset()..view_end];
    let stride = view.stride().unwrap_or(element);
    if stride < element {
        return Err(format!(
            "buffer view {} has a byteStride of {stride}, less than the {element} bytes of an element",
            view.index()
        ));
    }
    let end = count
        .checked_sub(1)
        .and_then(|last| last.checked_mul(stride))
        .and_then(|last| last.checked_add(element))
        .and_then(|size| size.checked_add(offset))
        .filter(|&end| end <= view_bytes.len())
        .ok_or_else(|| {
            format!(
                "{count} elements of {element} bytes, {stride} apart from byte {offset}, do not \
                 fit in buffer view {} of {} bytes",
                view.index(),
                view_bytes.len()
            )
        })?;
    Ok(&view_bytes[offset..end])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percent_escapes_are_decoded_and_a_broken_one_is_an_error() {
        assert_eq!(
            percent_decoded("my%20model.bin").as_deref(),
            Ok("my model.bin")
        );
        assert!(percent_decoded("bad%2").is_err());
        assert!(percent_decoded("bad%zz.bin").is_err());
    }

    #[test]
    fn data_uris_decode_and_network_addresses_are_refused() {
        let files = SceneFiles::Builtin(&[]);
        let bytes = read_uri(
            "data:application/octet-stream;base64,AQID",
            Path::new(""),
            files,
        );
        assert_eq!(bytes.as_deref(), Ok(&[1u8, 2, 3][..]));
        let refused = read_uri("https://example.com/a.bin", Path::new(""), files).unwrap_err();
        assert!(refused.contains("network address"), "{refused}");
        assert!(read_uri("data:text/plain,hello", Path::new(""), files).is_err());
    }
}
