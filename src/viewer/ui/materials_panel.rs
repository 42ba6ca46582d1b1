//! The Materials and Lights sections of the side panel: every material of the scene by name
//! (colour or texture, ka, kd, ks, shininess, kr, kt, ior, Fresnel) and every light (position
//! or direction, colour, intensity), edited in the [`Controls`] so that a change restarts
//! refinement like a camera move, and the Save scene button that writes the edits into a TOML
//! scene file.

use egui::{DragValue, Slider};
use raylab::light::Light;
use raylab::material::Material;

use super::fields::vector;
use super::swatch::color32;
use crate::viewer::input::action::Action;
use crate::viewer::scene::controls::Controls;
use crate::viewer::scene::edits::{color_and_intensity, set_color};
use crate::viewer::scene::{SceneInfo, cannot_save};

/// Shows the Materials and Lights sections and the Save scene button.
pub fn show(
    ui: &mut egui::Ui,
    controls: &mut Controls,
    scene: &SceneInfo<'_>,
    actions: &mut Vec<Action>,
) {
    let names = &scene.scene.scene().material_names;
    egui::CollapsingHeader::new("Materials")
        .default_open(true)
        .show(ui, |ui| {
            for (index, material) in controls.materials.iter_mut().enumerate() {
                let name = names.get(index).map_or("?", String::as_str);
                egui::CollapsingHeader::new(format!("#{index} {name}"))
                    .id_salt(("material", index))
                    .show(ui, |ui| material_fields(ui, material));
            }
        });
    egui::CollapsingHeader::new("Each light")
        .default_open(true)
        .show(ui, |ui| {
            for (index, light) in controls.lights.iter_mut().enumerate() {
                let kind = match light {
                    Light::Point { .. } => "point",
                    Light::Directional { .. } => "directional",
                    Light::Spot(_) => "spot",
                };
                egui::CollapsingHeader::new(format!("light {} ({kind})", index + 1))
                    .id_salt(("light", index))
                    .show(ui, |ui| light_fields(ui, light));
            }
        });
    let saves = scene.scene.toml_file;
    let button = ui
        .add_enabled(saves, egui::Button::new("Save scene"))
        .on_hover_text("write the materials and lights into the scene file, its comments kept")
        .on_disabled_hover_text(cannot_save(scene.scene));
    if button.clicked() {
        actions.push(Action::SaveScene);
    }
}

fn material_fields(ui: &mut egui::Ui, m: &mut Material) {
    match m.texture {
        Some(t) => {
            ui.label(format!("texture #{t} (replaces the colour)"));
        }
        None => color(ui, "colour", &mut m.color),
    }
    if let Some(cutoff) = &mut m.alpha_cutoff {
        ui.add(Slider::new(cutoff, 0.0..=1.0).text("alpha cutoff"))
            .on_hover_text("the surface is cut away where its texture's alpha is below this");
    }
    color(ui, "emission", &mut m.emission);
    if let Some(t) = m.emission_texture {
        ui.label(format!("emission × texture #{t}"));
    }
    let coefficient = |ui: &mut egui::Ui, x: &mut f32, text: &str| {
        ui.add(Slider::new(x, 0.0..=1.0).text(text));
    };
    coefficient(ui, &mut m.ambient, "ka ambient");
    coefficient(ui, &mut m.diffuse, "kd diffuse");
    coefficient(ui, &mut m.specular, "ks specular");
    color(ui, "highlight", &mut m.specular_color);
    ui.add(
        Slider::new(&mut m.shininess, 1.0..=1000.0)
            .logarithmic(true)
            .text("shininess"),
    );
    ui.add(Slider::new(&mut m.reflectivity, 0.0..=1.0).text("kr reflection"));
    color(ui, "reflection tint", &mut m.reflection_color);
    ui.add(Slider::new(&mut m.transparency, 0.0..=1.0).text("kt transmission"));
    ui.add(Slider::new(&mut m.ior, 1.0..=3.0).text("ior"));
    ui.checkbox(&mut m.fresnel, "Fresnel (Schlick)");
    if m.medium.is_some() {
        ui.label("filled with a medium (edit it in the file)");
    }
}

fn light_fields(ui: &mut egui::Ui, light: &mut Light) {
    match light {
        Light::Point { position, .. } => vector(ui, "position ", position),
        Light::Directional { direction, .. } => vector(ui, "direction", direction),
        Light::Spot(spot) => {
            vector(ui, "position ", &mut spot.position);
            vector(ui, "direction", &mut spot.direction);
            let degrees = |cos: f32| cos.clamp(-1.0, 1.0).acos().to_degrees();
            ui.label(format!(
                "cone {:.1}°, soft edge {:.1}° (edit them in the file)",
                degrees(spot.cos_angle),
                degrees(spot.cos_angle) - degrees(spot.cos_full)
            ));
        }
    }
    let (mut rgb, mut intensity) = color_and_intensity(light);
    let before = (rgb, intensity);
    color(ui, "colour", &mut rgb);
    ui.horizontal(|ui| {
        ui.label("intensity");
        ui.add(
            DragValue::new(&mut intensity)
                .speed(0.01)
                .range(0.0..=f32::MAX),
        );
    });
    if (rgb, intensity) != before {
        // The colour and the intensity together are the colour the light shines.
        set_color(light, rgb * intensity);
    }
}

/// Three channels of a linear colour and a swatch of it.
fn color(ui: &mut egui::Ui, label: &str, c: &mut raylab::color::Color) {
    ui.horizontal(|ui| {
        ui.label(label);
        for x in [&mut c.x, &mut c.y, &mut c.z] {
            ui.add(
                DragValue::new(x)
                    .speed(0.005)
                    .range(0.0..=f32::MAX)
                    .max_decimals(3),
            );
        }
        egui::color_picker::show_color(ui, color32(*c), egui::vec2(22.0, 12.0));
    });
}
