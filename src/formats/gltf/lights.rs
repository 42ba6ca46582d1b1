//! KHR_lights_punctual lights and glTF's perspective cameras, placed by their nodes, as
//! raylab's lights and camera views.
//!
//! The intensity conversion: glTF's diffuse surface reflects `albedo/π` of the light arriving,
//! raylab's reflects `kd·colour` of it, so every glTF intensity is divided by π. Then:
//! - a directional light (lux) becomes a directional light of `colour·intensity/π`;
//! - a spot light (candela) becomes a spot of `colour·intensity/π`, which falls off with the
//!   square of the distance as glTF's does, its cone the outer cone angle and its soft edge the
//!   band between the inner and outer angles;
//! - a point light (candela) becomes a point light, which in the lecture's model does not fall
//!   off: it is given glTF's brightness at the model's centre, `colour·intensity/(π·d²)` with `d`
//!   the light's distance from that centre.
//!
//! `range` is not used.

use glam::{Mat4, Vec3};
use gltf::json::extensions::scene::khr_lights_punctual::Type;
use gltf::json::validation::Checked;

use crate::camera::CameraSpec;
use crate::color::Color;
use crate::light::{Light, Spot};

/// The distance a point light is taken to be from the model's centre at the least, so that a
/// light at the centre stays finite.
const MIN_LIGHT_DISTANCE: f32 = 1e-3;

/// The raylab light of light `index` of the file, placed by its node's `world` matrix;
/// `centre` is the model's centre, where a point light keeps its brightness.
pub fn whitted_light(
    document: &gltf::Document,
    index: usize,
    world: Mat4,
    centre: Vec3,
) -> Result<Light, String> {
    let light = document
        .as_json()
        .extensions
        .as_ref()
        .and_then(|e| e.khr_lights_punctual.as_ref())
        .and_then(|l| l.lights.get(index))
        .ok_or_else(|| format!("light {index} is not in the file"))?;
    let intensity = if light.intensity.is_finite() {
        light.intensity.max(0.0)
    } else {
        0.0
    };
    let [r, g, b] = light
        .color
        .map(|c| if c.is_finite() { c.max(0.0) } else { 0.0 });
    let color = Color::new(r, g, b) * (intensity / std::f32::consts::PI);
    let position = world.transform_point3(Vec3::ZERO);
    // A light shines along its node's −z.
    let along = world.transform_vector3(Vec3::NEG_Z).normalize_or_zero();
    let Checked::Valid(kind) = &light.type_ else {
        return Err(format!("light {index} has no valid type"));
    };
    if along == Vec3::ZERO && *kind != Type::Point {
        return Err(format!(
            "light {index}'s node squashes its direction to nothing"
        ));
    }
    Ok(match kind {
        Type::Directional => Light::Directional {
            direction: -along,
            color,
        },
        Type::Point => {
            let d = position.distance(centre).max(MIN_LIGHT_DISTANCE);
            Light::Point {
                position,
                color: color * (1.0 / (d * d)),
            }
        }
        Type::Spot => {
            let spot = light
                .spot
                .as_ref()
                .ok_or_else(|| format!("light {index} is a spot without its `spot` cone"))?;
            let outer = spot
                .outer_cone_angle
                .to_degrees()
                .clamp(f32::MIN_POSITIVE, 90.0);
            let inner = spot.inner_cone_angle.to_degrees().clamp(0.0, outer);
            Light::Spot(Spot::new(position, along, outer, outer - inner, color))
        }
    })
}

/// The view of perspective camera `index` of the file from its node's `world` matrix, looking
/// down its −z with its +y up, aimed at the point nearest `centre` along that line (so that
/// orbiting turns round the model); `None` for an orthographic camera, which raylab's camera
/// cannot be. The aspect ratio, if the file gives one, comes with it.
pub fn camera_view(
    document: &gltf::Document,
    index: usize,
    world: Mat4,
    centre: Vec3,
) -> Option<(CameraSpec, Option<f32>)> {
    let camera = document.as_json().cameras.get(index)?;
    let perspective = camera.perspective.as_ref()?;
    let eye = world.transform_point3(Vec3::ZERO);
    let forward = world.transform_vector3(Vec3::NEG_Z).normalize_or_zero();
    let up = world.transform_vector3(Vec3::Y).normalize_or_zero();
    let yfov = perspective.yfov.to_degrees();
    if forward == Vec3::ZERO || up == Vec3::ZERO || !(yfov > 0.0 && yfov < 180.0) {
        return None;
    }
    let distance = (centre - eye).dot(forward).max(1.0);
    let spec = CameraSpec {
        eye,
        look_at: eye + forward * distance,
        up,
        view_angle: yfov,
        ..CameraSpec::default()
    };
    let aspect = perspective
        .aspect_ratio
        .filter(|a| a.is_finite() && *a > 0.0);
    Some((spec, aspect))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn document(json: &str) -> gltf::Document {
        gltf::Gltf::from_slice(json.as_bytes())
            .expect("a valid file")
            .document
    }

    const LIGHTS: &str = r#"{
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "intensity": 8.0, "color": [1, 0.5, 0.25]},
            {"type": "directional", "intensity": 3.14159265},
            {"type": "spot", "intensity": 2.0, "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.5}}
        ]}}
    }"#;

    #[test]
    fn a_point_light_keeps_its_brightness_at_the_models_centre() {
        let doc = document(LIGHTS);
        let world = Mat4::from_translation(Vec3::new(0.0, 2.0, 0.0));
        let Ok(Light::Point { position, color }) = whitted_light(&doc, 0, world, Vec3::ZERO) else {
            panic!("a point light");
        };
        assert_eq!(position, Vec3::new(0.0, 2.0, 0.0));
        let expected = 8.0 / (std::f32::consts::PI * 4.0);
        assert!((color.x - expected).abs() < 1e-6);
        assert!((color.z - expected * 0.25).abs() < 1e-6);
    }

    #[test]
    fn a_directional_light_points_back_along_its_nodes_minus_z() {
        let doc = document(LIGHTS);
        let turned = Mat4::from_rotation_x(-std::f32::consts::FRAC_PI_2);
        let Ok(Light::Directional { direction, color }) =
            whitted_light(&doc, 1, turned, Vec3::ZERO)
        else {
            panic!("a directional light");
        };
        // −z turned −90° about x points down: the light is above.
        assert!(direction.abs_diff_eq(Vec3::Y, 1e-6), "{direction}");
        assert!((color.x - 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_spot_light_keeps_its_cones() {
        let doc = document(LIGHTS);
        let Ok(Light::Spot(spot)) = whitted_light(&doc, 2, Mat4::IDENTITY, Vec3::ZERO) else {
            panic!("a spot light");
        };
        assert!((spot.cos_angle - 0.5f32.cos()).abs() < 1e-6);
        assert!((spot.cos_full - 0.3f32.cos()).abs() < 1e-5);
        assert_eq!(spot.direction, Vec3::NEG_Z);
    }
}
