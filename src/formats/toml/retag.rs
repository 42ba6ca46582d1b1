//! Moving `type = "…"` tags out of the tables they name, before serde reads the document.
//!
//! The file writes a light, texture or object as one table with its kind inside it:
//! `{ type = "sphere", radius = 2, material = "red" }`. serde's internally tagged enums would
//! read that, but they first copy the table into a buffer that forgets where each value stood in
//! the file, so an error inside (a negative radius, an unknown key) could no longer point at its
//! line. Instead the parsed document, which keeps every value's position, is rewritten into
//! serde's externally tagged form, `{ material = "red", shape = { sphere = { radius = 2 } } }`,
//! which serde reads without buffering, positions and all.
//!
//! Keys that have been renamed are given their new names here too, so that older scene files
//! still load.

use std::ops::Range;

use toml::Spanned;
use toml::de::{DeTable, DeValue};

use super::object_file::OBJECT_KEYS;
use crate::formats::{SceneError, Source};
use crate::shapes::MAX_CSG_DEPTH;

/// The key that says what kind of light, texture or object a table describes.
const TAG: &str = "type";

/// The key [`super::object_file::ObjectFile`] reads an object's shape from.
const SHAPE_KEY: &str = "shape";

/// The kind of object whose `children` are objects too, and that key.
const CSG_KIND: &str = "csg";
const CHILDREN_KEY: &str = "children";

/// Keys of `[render]` that older scene files write under another name: (old, new).
const OLD_RENDER_KEYS: [(&str, &str); 1] = [("refractions", "transmission")];

/// Rewrites `[[lights]]`, `[textures.*]` and `[[objects]]` in place, and renames the old keys
/// of `[render]`. Values of the wrong TOML type are left alone for serde to report. Returns the positions of the keys that went into
/// objects' shapes: serde, knowing only the shape's keys, reports an unknown one without
/// mentioning [`OBJECT_KEYS`], and the caller adds them.
pub(crate) fn retag_document(
    root: &mut DeTable<'_>,
    source: Source,
) -> Result<Vec<Range<usize>>, SceneError> {
    if let Some(DeValue::Table(render)) = root.get_mut("render").map(Spanned::get_mut) {
        rename_old_keys(render, &OLD_RENDER_KEYS, source)?;
    }
    if let Some(DeValue::Array(lights)) = root.get_mut("lights").map(Spanned::get_mut) {
        for light in lights.iter_mut() {
            retag(light, source, "light", Kind::Default("point"))?;
        }
    }
    if let Some(DeValue::Table(textures)) = root.get_mut("textures").map(Spanned::get_mut) {
        for (_, texture) in textures.iter_mut() {
            retag(texture, source, "texture", Kind::Required("checker3d"))?;
        }
    }
    let mut shape_keys = Vec::new();
    if let Some(DeValue::Array(objects)) = root.get_mut("objects").map(Spanned::get_mut) {
        for object in objects.iter_mut() {
            retag_object(object, source, &mut shape_keys, 1)?;
        }
    }
    Ok(shape_keys)
}

/// Gives each `old` key of `table` its `new` name, keeping its position; an old key beside its
/// new name is an error there.
fn rename_old_keys(
    table: &mut DeTable<'_>,
    renamed: &[(&str, &'static str)],
    source: Source,
) -> Result<(), SceneError> {
    for &(old, new) in renamed {
        let Some((key, value)) = table.remove_entry(old) else {
            continue;
        };
        if table.contains_key(new) {
            return Err(source.error(
                key.span(),
                format!("`{old}` is the old name of `{new}`, which is set too; keep one"),
            ));
        }
        table.insert(Spanned::new(key.span(), new.into()), value);
    }
    Ok(())
}

/// What a table without a `type` is.
#[derive(Clone, Copy)]
enum Kind {
    /// An error; the kind named is the example the message gives.
    Required(&'static str),
    /// This kind.
    Default(&'static str),
}

/// `{ type = "x", rest… }` becomes `{ x = { rest… } }`. The key `x` takes the position of the
/// tag's value, so that an unknown kind is reported there; the inner table takes the position
/// of the whole, so that a missing key is reported at the table.
fn retag(
    value: &mut Spanned<DeValue<'_>>,
    source: Source,
    what: &str,
    kind: Kind,
) -> Result<(), SceneError> {
    let span = value.span();
    let DeValue::Table(table) = value.get_mut() else {
        return Ok(());
    };
    let (Kind::Required(example) | Kind::Default(example)) = kind;
    let tag = match (table.remove(TAG), kind) {
        (Some(tag), _) => tag,
        (None, Kind::Default(default)) => {
            Spanned::new(span.clone(), DeValue::String(default.into()))
        }
        (None, Kind::Required(_)) => {
            return Err(source.error(
                span,
                format!(
                    "missing field `{TAG}`: the kind of {what}, for example \
                     `{TAG} = \"{example}\"`"
                ),
            ));
        }
    };
    let tag_span = tag.span();
    let DeValue::String(kind) = tag.into_inner() else {
        return Err(source.error(
            tag_span,
            format!("expected a string naming the kind of {what}, for example \"{example}\""),
        ));
    };
    let rest = std::mem::take(table);
    table.insert(
        Spanned::new(tag_span, kind),
        Spanned::new(span, DeValue::Table(rest)),
    );
    Ok(())
}

/// Like [`retag`], but the keys every object has ([`OBJECT_KEYS`]) stay at the top and the
/// tagged shape goes under `shape`: `{ material, transform, shape = { x = { rest… } } }`. The
/// positions of the shape's keys are added to `shape_keys`. The children of a csg object, at
/// `depth` (1 for a top-level object), are objects too and retagged alike.
fn retag_object(
    value: &mut Spanned<DeValue<'_>>,
    source: Source,
    shape_keys: &mut Vec<Range<usize>>,
    depth: usize,
) -> Result<(), SceneError> {
    let span = value.span();
    let DeValue::Table(table) = value.get_mut() else {
        return Ok(());
    };
    let is_csg = table
        .get(TAG)
        .is_some_and(|tag| matches!(tag.get_ref(), DeValue::String(kind) if kind == CSG_KIND));
    if is_csg && depth > MAX_CSG_DEPTH {
        return Err(source.error(
            span,
            format!("csg objects are nested more than {MAX_CSG_DEPTH} deep"),
        ));
    }
    if is_csg
        && let Some(DeValue::Array(children)) = table.get_mut(CHILDREN_KEY).map(Spanned::get_mut)
    {
        for child in children.iter_mut() {
            retag_object(child, source, shape_keys, depth + 1)?;
        }
    }
    let mut object = DeTable::new();
    for key in OBJECT_KEYS {
        if let Some((key, value)) = table.remove_entry(key) {
            object.insert(key, value);
        }
    }
    shape_keys.extend(table.keys().map(|key| key.span()));
    retag(value, source, "object", Kind::Required("sphere"))?;
    let shape = std::mem::replace(value.get_mut(), DeValue::Table(DeTable::new()));
    object.insert(
        Spanned::new(span.clone(), SHAPE_KEY.into()),
        Spanned::new(span, shape),
    );
    *value.get_mut() = DeValue::Table(object);
    Ok(())
}
