//! Edits of the scene's materials and lights: one field of a material ([`MaterialEdit`]) or of a
//! light ([`LightEdit`]), as the script's `material` and `light` steps write them, the colour and
//! intensity the Lights panel shows of a light, and the checks an edited material or light
//! passes before it is traced.

use glam::Vec3;
use raylab::color::Color;
use raylab::light::Light;
use raylab::material::Material;

/// A new value for one field of a material, named as in the lecture (`kd`) or the scene file
/// (`diffuse`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MaterialEdit {
    Color(Color),
    Emission(Color),
    Ambient(f32),
    Diffuse(f32),
    Specular(f32),
    SpecularColor(Color),
    Shininess(f32),
    Reflectivity(f32),
    ReflectionColor(Color),
    Transparency(f32),
    Ior(f32),
    /// The cut-outs' threshold ([`Material::alpha_cutoff`]).
    AlphaCutoff(f32),
    Fresnel(bool),
}

/// The field names a script's `material` step takes.
const MATERIAL_FIELDS: &str = "color, emission, ka (ambient), kd (diffuse), ks (specular), \
    specular_color, shininess, kr (reflectivity), reflection_color, kt (transparency), ior, alpha_cutoff, fresnel";

impl MaterialEdit {
    /// `FIELD VALUE…`: one number, three for a colour, `on`/`off` for `fresnel`.
    pub fn parse(field: &str, values: &[f32], flag: Option<bool>) -> Result<MaterialEdit, String> {
        let one = |make: fn(f32) -> MaterialEdit| match values {
            [x] => Ok(make(*x)),
            _ => Err(format!("`{field}` takes one number")),
        };
        let three = |make: fn(Color) -> MaterialEdit| match values {
            [r, g, b] => Ok(make(Color::new(*r, *g, *b))),
            _ => Err(format!("`{field}` takes three numbers (r g b)")),
        };
        match field {
            "color" | "colour" => three(MaterialEdit::Color),
            "emission" | "emissive" => three(MaterialEdit::Emission),
            "ka" | "ambient" => one(MaterialEdit::Ambient),
            "kd" | "diffuse" => one(MaterialEdit::Diffuse),
            "ks" | "specular" => one(MaterialEdit::Specular),
            "specular_color" => three(MaterialEdit::SpecularColor),
            "shininess" => one(MaterialEdit::Shininess),
            "kr" | "reflectivity" => one(MaterialEdit::Reflectivity),
            "reflection_color" => three(MaterialEdit::ReflectionColor),
            "kt" | "transparency" => one(MaterialEdit::Transparency),
            "ior" => one(MaterialEdit::Ior),
            "alpha_cutoff" => one(MaterialEdit::AlphaCutoff),
            "fresnel" => flag
                .map(MaterialEdit::Fresnel)
                .ok_or_else(|| "`fresnel` takes on or off".to_string()),
            _ => Err(format!(
                "unknown material field `{field}` (use {MATERIAL_FIELDS})"
            )),
        }
    }

    pub fn apply(self, m: &mut Material) {
        match self {
            MaterialEdit::Color(c) => m.color = c,
            MaterialEdit::Emission(c) => m.emission = c,
            MaterialEdit::Ambient(x) => m.ambient = x,
            MaterialEdit::Diffuse(x) => m.diffuse = x,
            MaterialEdit::Specular(x) => m.specular = x,
            MaterialEdit::SpecularColor(c) => m.specular_color = c,
            MaterialEdit::Shininess(x) => m.shininess = x,
            MaterialEdit::Reflectivity(x) => m.reflectivity = x,
            MaterialEdit::ReflectionColor(c) => m.reflection_color = c,
            MaterialEdit::Transparency(x) => m.transparency = x,
            MaterialEdit::Ior(x) => m.ior = x,
            MaterialEdit::AlphaCutoff(x) => m.alpha_cutoff = Some(x),
            MaterialEdit::Fresnel(on) => m.fresnel = on,
        }
    }
}

/// A new value for one field of a light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightEdit {
    /// Of a point or spot light.
    Position(Vec3),
    /// Of a directional light (towards the light) or a spot light (along its cone).
    Direction(Vec3),
    /// The light's colour, its brightest channel 1 (see [`color_and_intensity`]).
    Color(Color),
    /// What multiplies the colour.
    Intensity(f32),
}

/// The field names a script's `light` step takes.
const LIGHT_FIELDS: &str = "position, direction, color, intensity";

impl LightEdit {
    /// `FIELD VALUE…`: three numbers, one for `intensity`.
    pub fn parse(field: &str, values: &[f32]) -> Result<LightEdit, String> {
        let three = |make: fn(Vec3) -> LightEdit| match values {
            [x, y, z] => Ok(make(Vec3::new(*x, *y, *z))),
            _ => Err(format!("`{field}` takes three numbers")),
        };
        match field {
            "position" => three(LightEdit::Position),
            "direction" => three(LightEdit::Direction),
            "color" | "colour" => three(LightEdit::Color),
            "intensity" => match values {
                [x] => Ok(LightEdit::Intensity(*x)),
                _ => Err("`intensity` takes one number".into()),
            },
            _ => Err(format!(
                "unknown light field `{field}` (use {LIGHT_FIELDS})"
            )),
        }
    }

    /// Changes `light`; the error says the light has no such field.
    pub fn apply(self, light: &mut Light) -> Result<(), String> {
        let (color, intensity) = color_and_intensity(light);
        match (self, light) {
            (LightEdit::Position(p), Light::Point { position, .. }) => *position = p,
            (LightEdit::Position(p), Light::Spot(spot)) => spot.position = p,
            (LightEdit::Direction(d), Light::Directional { direction, .. }) => *direction = d,
            (LightEdit::Direction(d), Light::Spot(spot)) => spot.direction = d,
            (LightEdit::Color(c), light) => set_color(light, c * intensity),
            (LightEdit::Intensity(i), light) => set_color(light, color * i),
            (LightEdit::Position(_), _) => return Err("a directional light has no position".into()),
            (LightEdit::Direction(_), _) => return Err("a point light has no direction".into()),
        }
        Ok(())
    }
}

/// The colour a light shines split into a colour whose brightest channel is 1 and the
/// intensity that multiplies it (white for a light that shines nothing).
pub fn color_and_intensity(light: &Light) -> (Color, f32) {
    let shone = shone(light);
    let intensity = shone.max_element();
    if intensity > 0.0 {
        (shone / intensity, intensity)
    } else {
        (Color::ONE, 0.0)
    }
}

/// The colour `light` shines (its colour times its intensity).
fn shone(light: &Light) -> Color {
    match light {
        Light::Point { color, .. } | Light::Directional { color, .. } => *color,
        Light::Spot(spot) => spot.color,
    }
}

/// Makes `light` shine `shone` (its colour times its intensity).
pub fn set_color(light: &mut Light, shone: Color) {
    match light {
        Light::Point { color, .. } | Light::Directional { color, .. } => *color = shone,
        Light::Spot(spot) => spot.color = shone,
    }
}

/// Whether `m` can be traced: finite coefficients and alpha cutoff, none negative, `kr` and
/// `kt` at most 1, an index of refraction above 0. The error says which field is wrong.
pub fn check_material(m: &Material) -> Result<(), String> {
    let non_negative = [
        ("ka", m.ambient),
        ("kd", m.diffuse),
        ("ks", m.specular),
        ("shininess", m.shininess),
        ("alpha_cutoff", m.alpha_cutoff.unwrap_or(0.0)),
    ];
    for (name, x) in non_negative {
        if !(x.is_finite() && x >= 0.0) {
            return Err(format!("{name} must be zero or more, got {x}"));
        }
    }
    for (name, x) in [("kr", m.reflectivity), ("kt", m.transparency)] {
        if !(0.0..=1.0).contains(&x) {
            return Err(format!("{name} must be from 0 to 1, got {x}"));
        }
    }
    if !(m.ior.is_finite() && m.ior > 0.0) {
        return Err(format!("ior must be more than 0, got {}", m.ior));
    }
    check_color("color", m.color)?;
    check_color("emission", m.emission)?;
    check_color("specular colour", m.specular_color)?;
    check_color("reflection colour", m.reflection_color)
}

/// Whether `light` can be traced: a finite place, a direction that is not zero, a colour of
/// finite, non-negative numbers.
pub fn check_light(light: &Light) -> Result<(), String> {
    let (position, direction) = match light {
        Light::Point { position, .. } => (Some(*position), None),
        Light::Directional { direction, .. } => (None, Some(*direction)),
        Light::Spot(spot) => (Some(spot.position), Some(spot.direction)),
    };
    if position.is_some_and(|p| !p.is_finite()) {
        return Err("the position must be finite".into());
    }
    if direction.is_some_and(|d| !(d.is_finite() && d.length_squared() > 0.0)) {
        return Err("the direction must be finite and not zero".into());
    }
    check_color("colour", shone(light))
}

fn check_color(name: &str, c: Color) -> Result<(), String> {
    if c.is_finite() && c.min_element() >= 0.0 {
        Ok(())
    } else {
        Err(format!(
            "the {name} must be finite and not negative, got {c}"
        ))
    }
}

/// `light` with its direction made a unit vector, as the tracer wants it (the scene file's
/// reader does the same).
pub fn normalized(light: &Light) -> Light {
    match *light {
        Light::Directional { direction, color } => Light::Directional {
            direction: direction.normalize(),
            color,
        },
        Light::Spot(mut spot) => {
            spot.direction = spot.direction.normalize();
            Light::Spot(spot)
        }
        point => point,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn material_fields_parse_by_either_name_and_apply() {
        let mut m = Material::default();
        MaterialEdit::parse("kd", &[0.25], None)
            .unwrap()
            .apply(&mut m);
        MaterialEdit::parse("colour", &[1.0, 0.0, 0.5], None)
            .unwrap()
            .apply(&mut m);
        MaterialEdit::parse("fresnel", &[], Some(true))
            .unwrap()
            .apply(&mut m);
        assert_eq!(m.diffuse, 0.25);
        assert_eq!(m.color, Color::new(1.0, 0.0, 0.5));
        assert!(m.fresnel);
        assert!(MaterialEdit::parse("kd", &[1.0, 2.0], None).is_err());
        let error = MaterialEdit::parse("glossiness", &[1.0], None).unwrap_err();
        assert!(error.contains("unknown material field"), "{error}");
    }

    #[test]
    fn a_lights_colour_and_intensity_split_and_join() {
        let mut light = Light::Point {
            position: Vec3::ZERO,
            color: Color::new(2.0, 1.0, 0.0),
        };
        assert_eq!(
            color_and_intensity(&light),
            (Color::new(1.0, 0.5, 0.0), 2.0)
        );
        LightEdit::Intensity(4.0).apply(&mut light).unwrap();
        LightEdit::Position(Vec3::X).apply(&mut light).unwrap();
        assert_eq!(
            light,
            Light::Point {
                position: Vec3::X,
                color: Color::new(4.0, 2.0, 0.0)
            }
        );
        assert!(LightEdit::Direction(Vec3::Y).apply(&mut light).is_err());
    }

    #[test]
    fn bad_materials_and_lights_are_refused() {
        let mut m = Material {
            reflectivity: 1.5,
            ..Material::default()
        };
        assert!(check_material(&m).unwrap_err().contains("kr"));
        m.reflectivity = 0.0;
        m.ior = 0.0;
        assert!(check_material(&m).unwrap_err().contains("ior"));
        let light = Light::Directional {
            direction: Vec3::ZERO,
            color: Color::ONE,
        };
        assert!(check_light(&light).unwrap_err().contains("direction"));
    }
}
