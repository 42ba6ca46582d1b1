//! Writing edits of a scene's materials and lights back into its TOML file, keeping the file's
//! comments and layout (through `toml_edit`): only the keys whose values changed are rewritten,
//! each keeping the comment after it, and keys a material or light did not have are added at the
//! end of its table. A material is found by its name, `[materials.NAME]`; a light by its place
//! among the `[[lights]]`, which is its index in [`Scene::lights`]. The file is replaced
//! atomically ([`crate::output::write_atomically`]).

use std::io::Write;
use std::path::Path;

use glam::Vec3;
use toml_edit::{Array, DocumentMut, Item, TableLike, Value};

use crate::color::Color;
use crate::light::Light;
use crate::material::Material;
use crate::output::write_atomically;
use crate::scene::Scene;

/// A scene's materials (with their names, index for index) and lights: as the file has them,
/// or as edited.
#[derive(Clone, Copy, Debug)]
pub struct Looks<'a> {
    pub names: &'a [String],
    pub materials: &'a [Material],
    pub lights: &'a [Light],
}

impl<'a> Looks<'a> {
    /// `scene`'s materials and lights.
    pub fn of(scene: &'a Scene) -> Looks<'a> {
        Looks {
            names: &scene.material_names,
            materials: &scene.materials,
            lights: &scene.lights,
        }
    }
}

/// What [`save_edits`] wrote.
#[derive(Debug, PartialEq)]
pub struct SavedEdits {
    /// The file's new text.
    pub text: String,
    /// The edits the file has no place for (a material an OBJ file brings, the default
    /// material), one line each.
    pub unsaved: Vec<String>,
}

/// Writes into the scene file at `path` (which has `before`) the materials and lights of `after`
/// that differ from `before`'s, atomically. The error says what went wrong, naming the file.
pub fn save_edits(path: &Path, before: Looks, after: Looks) -> Result<SavedEdits, String> {
    let named = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let bytes = crate::memory::read_file(path).map_err(|e| named(&e))?;
    let text = String::from_utf8(bytes).map_err(|e| named(&e))?;
    let saved = edit_text(&text, before, after).map_err(|e| named(&e))?;
    write_atomically(
        path,
        |e| named(&e),
        |out| out.write_all(saved.text.as_bytes()).map_err(|e| named(&e)),
    )?;
    Ok(saved)
}

/// [`save_edits`] on the file's text: the text with the edits written in.
pub fn edit_text(text: &str, before: Looks, after: Looks) -> Result<SavedEdits, String> {
    let mut document: DocumentMut = text.parse().map_err(|e| format!("{e}"))?;
    let mut unsaved = Vec::new();
    for (index, (old, new)) in before.materials.iter().zip(after.materials).enumerate() {
        if old == new {
            continue;
        }
        let name = before.names.get(index).map_or("?", String::as_str);
        match material_table(&mut document, name) {
            Some(table) => write_material(table, old, new),
            None => unsaved.push(format!(
                "material `{name}` is not a [materials] table of the file: its edits are not saved"
            )),
        }
    }
    for (index, (old, new)) in before.lights.iter().zip(after.lights).enumerate() {
        if old == new {
            continue;
        }
        match light_table(&mut document, index) {
            Some(table) => write_light(table, old, new),
            None => unsaved.push(format!(
                "light {} is not in the file's [[lights]]: its edits are not saved",
                index + 1
            )),
        }
    }
    Ok(SavedEdits {
        text: document.to_string(),
        unsaved,
    })
}

/// `[materials.NAME]` (or `NAME = { … }` inside `[materials]`).
fn material_table<'a>(document: &'a mut DocumentMut, name: &str) -> Option<&'a mut dyn TableLike> {
    document
        .get_mut("materials")?
        .as_table_like_mut()?
        .get_mut(name)?
        .as_table_like_mut()
}

/// The `index`th `[[lights]]` table (or the inline table at `index` of `lights = [ … ]`).
fn light_table(document: &mut DocumentMut, index: usize) -> Option<&mut dyn TableLike> {
    match document.get_mut("lights")? {
        Item::ArrayOfTables(tables) => Some(tables.get_mut(index)?),
        Item::Value(Value::Array(array)) => Some(array.get_mut(index)?.as_inline_table_mut()?),
        _ => None,
    }
}

fn write_material(table: &mut dyn TableLike, old: &Material, new: &Material) {
    let numbers = [
        ("ambient", old.ambient, new.ambient),
        ("diffuse", old.diffuse, new.diffuse),
        ("specular", old.specular, new.specular),
        ("shininess", old.shininess, new.shininess),
        ("reflectivity", old.reflectivity, new.reflectivity),
        ("transparency", old.transparency, new.transparency),
        ("ior", old.ior, new.ior),
    ];
    for (key, old, new) in numbers {
        if old != new {
            set(table, key, number(new));
        }
    }
    if old.color != new.color {
        set(table, "color", triple(new.color.to_array()));
    }
    if old.emission != new.emission {
        set(table, "emission", triple(new.emission.to_array()));
    }
    if old.specular_color != new.specular_color {
        set(
            table,
            "specular_color",
            triple(new.specular_color.to_array()),
        );
    }
    if old.reflection_color != new.reflection_color {
        set(
            table,
            "reflection_color",
            triple(new.reflection_color.to_array()),
        );
    }
    if old.fresnel != new.fresnel {
        set(table, "fresnel", Value::from(new.fresnel));
    }
    if let Some(cutoff) = new.alpha_cutoff
        && old.alpha_cutoff != new.alpha_cutoff
    {
        set(table, "alpha_cutoff", number(cutoff));
    }
}

fn write_light(table: &mut dyn TableLike, old: &Light, new: &Light) {
    let (old_place, new_place) = (place(old), place(new));
    if old_place.position != new_place.position
        && let Some(p) = new_place.position
    {
        set(table, "position", triple(p.to_array()));
    }
    if old_place.direction != new_place.direction
        && let Some(d) = new_place.direction
    {
        set(table, "direction", triple(d.to_array()));
    }
    if old_place.color != new_place.color {
        // The file's colour is multiplied by its intensity, which stays as it is unless it is 0.
        let intensity = table
            .get("intensity")
            .and_then(Item::as_value)
            .and_then(|v| v.as_float().or(v.as_integer().map(|i| i as f64)))
            .unwrap_or(1.0) as f32;
        let intensity = if intensity > 0.0 {
            intensity
        } else {
            set(table, "intensity", number(1.0));
            1.0
        };
        set(
            table,
            "color",
            triple((new_place.color * (1.0 / intensity)).to_array()),
        );
    }
}

/// Where a light is and what it shines, as its file says it.
struct Placed {
    position: Option<Vec3>,
    direction: Option<Vec3>,
    color: Color,
}

fn place(light: &Light) -> Placed {
    match *light {
        Light::Point { position, color } => Placed {
            position: Some(position),
            direction: None,
            color,
        },
        Light::Directional { direction, color } => Placed {
            position: None,
            direction: Some(direction),
            color,
        },
        Light::Spot(spot) => Placed {
            position: Some(spot.position),
            direction: Some(spot.direction),
            color: spot.color,
        },
    }
}

/// Sets `key` to `value`, keeping the spaces and comment around the old value if there was one.
fn set(table: &mut dyn TableLike, key: &str, mut value: Value) {
    match table.get_mut(key) {
        Some(Item::Value(old)) => {
            *value.decor_mut() = old.decor().clone();
            *old = value;
        }
        _ => {
            table.insert(key, Item::Value(value));
        }
    }
}

/// `x` as the file should say it: its shortest decimal form (0.2, not 0.20000000298…), which
/// reads back as the same `f32`.
fn number(x: f32) -> Value {
    let shortest: f64 = x.to_string().parse().unwrap_or(f64::from(x));
    Value::from(shortest)
}

fn triple(xs: [f32; 3]) -> Value {
    Value::Array(xs.into_iter().map(number).collect::<Array>())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::toml::parse_scene;

    const FILE: &str = "\
# A test scene: its comments must stay.
[render]
width = 8   # tiny
height = 8

[[lights]]
type = \"point\"
position = [0, 5, 0]  # above
intensity = 0.5

[[lights]]
type = \"directional\"
direction = [0, 1, 0]

[materials.red]
# red plastic
color = [1, 0, 0]
diffuse = 0.7   # kd
specular = 0.3

[materials.glass]
transparency = 0.9
ior = 1.5

[[objects]]
type = \"sphere\"
material = \"red\"
";

    fn read(text: &str) -> Scene {
        parse_scene(text, Path::new("test.toml"), Path::new(".")).unwrap()
    }

    fn index(scene: &Scene, name: &str) -> usize {
        scene.material_names.iter().position(|n| n == name).unwrap()
    }

    /// `before`'s names with these materials and lights.
    fn edited<'a>(before: &'a Scene, materials: &'a [Material], lights: &'a [Light]) -> Looks<'a> {
        Looks {
            names: &before.material_names,
            materials,
            lights,
        }
    }

    #[test]
    fn an_edited_material_is_written_in_place_keeping_comments_and_layout() {
        let before = read(FILE);
        let mut materials = before.materials.clone();
        let red = index(&before, "red");
        materials[red].diffuse = 0.2;
        materials[red].color = Color::new(0.0, 0.5, 1.0);
        materials[red].fresnel = true;
        materials[red].emission = Color::new(0.25, 0.0, 0.0);
        let saved = edit_text(
            FILE,
            Looks::of(&before),
            edited(&before, &materials, &before.lights),
        )
        .unwrap();
        assert!(saved.unsaved.is_empty(), "{:?}", saved.unsaved);
        // Only the edited lines change; a key the table lacked comes at its end.
        let expected = FILE
            .replace("diffuse = 0.7   # kd", "diffuse = 0.2   # kd")
            .replace("color = [1, 0, 0]", "color = [0.0, 0.5, 1.0]")
            .replace(
                "specular = 0.3\n",
                "specular = 0.3\nemission = [0.25, 0.0, 0.0]\nfresnel = true\n",
            );
        assert_eq!(saved.text, expected);
        let after = read(&saved.text);
        assert_eq!(after.materials, materials);
        assert_eq!(after.lights, before.lights);
    }

    #[test]
    fn an_edited_light_keeps_its_intensity_and_comments() {
        let before = read(FILE);
        let mut lights = before.lights.clone();
        lights[0] = Light::Point {
            position: Vec3::new(1.0, 4.0, 0.0),
            color: Color::new(0.5, 0.25, 0.0),
        };
        lights[1] = Light::Directional {
            direction: Vec3::X,
            color: Color::splat(2.0),
        };
        let saved = edit_text(
            FILE,
            Looks::of(&before),
            edited(&before, &before.materials, &lights),
        )
        .unwrap();
        assert!(
            saved.text.contains(
                "position = [1.0, 4.0, 0.0]  # above\nintensity = 0.5\ncolor = [1.0, 0.5, 0.0]\n"
            ),
            "{}",
            saved.text
        );
        assert!(
            saved
                .text
                .contains("direction = [1.0, 0.0, 0.0]\ncolor = [2.0, 2.0, 2.0]\n")
        );
        assert!(
            saved
                .text
                .starts_with("# A test scene: its comments must stay.\n")
        );
        assert_eq!(read(&saved.text).lights, lights);
    }

    #[test]
    fn materials_the_file_does_not_name_are_reported_unsaved() {
        let before = read(FILE);
        let mut materials = before.materials.clone();
        materials[0].diffuse = 0.1;
        let saved = edit_text(
            FILE,
            Looks::of(&before),
            edited(&before, &materials, &before.lights),
        )
        .unwrap();
        assert_eq!(saved.text, FILE);
        assert_eq!(saved.unsaved.len(), 1);
        assert!(
            saved.unsaved[0].contains("`default`"),
            "{:?}",
            saved.unsaved
        );
    }

    #[test]
    fn saving_replaces_the_file_atomically_and_refuses_a_read_only_one() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("scene.toml");
        std::fs::write(&path, FILE).unwrap();
        let before = read(FILE);
        let mut materials = before.materials.clone();
        materials[index(&before, "glass")].ior = 1.33;
        let saved = save_edits(
            &path,
            Looks::of(&before),
            edited(&before, &materials, &before.lights),
        )
        .unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), saved.text);
        assert!(saved.text.contains("ior = 1.33\n"), "{}", saved.text);
        // Nothing but the scene is left in the folder (no temporary file).
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        let mut permissions = std::fs::metadata(&path).unwrap().permissions();
        permissions.set_readonly(true);
        std::fs::set_permissions(&path, permissions).unwrap();
        materials[index(&before, "glass")].ior = 2.0;
        let error = save_edits(
            &path,
            Looks::of(&before),
            edited(&before, &materials, &before.lights),
        )
        .unwrap_err();
        assert!(error.contains("scene.toml"), "{error}");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), saved.text);
    }

    #[test]
    fn inline_tables_take_edits_too() {
        let text = "lights = [{ type = \"point\", position = [0, 5, 0] }]  # one lamp\n\n\
                    [materials]\nred = { color = [1, 0, 0], diffuse = 0.7 } # red\n";
        let before = read(text);
        let mut materials = before.materials.clone();
        materials[index(&before, "red")].diffuse = 0.25;
        let lights = [Light::Point {
            position: Vec3::ZERO,
            color: Color::ONE,
        }];
        let saved = edit_text(
            text,
            Looks::of(&before),
            edited(&before, &materials, &lights),
        )
        .unwrap();
        assert_eq!(
            saved.text,
            "lights = [{ type = \"point\", position = [0.0, 0.0, 0.0] }]  # one lamp\n\n\
             [materials]\nred = { color = [1, 0, 0], diffuse = 0.25 } # red\n"
        );
        let after = read(&saved.text);
        assert_eq!(
            (after.materials, after.lights),
            (materials, lights.to_vec())
        );
    }
}
