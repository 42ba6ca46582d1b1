//! The egui panels: the side panel with the scene, camera, tracing, lights and save controls, and
//! the status line at the bottom. Controls are edited in place; buttons become [`Action`]s.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use egui::{Color32, DragValue, Slider};
use raylab::inspect::{DebugView, Legend};
use raylab::render::{Device, FirstHit};
use raylab::settings::{MAX_BLOCK_SIZE, MAX_CAUSTIC_GATHER, MAX_DEPTH_LIMIT, MAX_SAMPLES};
use raylab::srgb_image::SrgbImage;
use strum::IntoEnumIterator;

use super::display::{self, DisplayControls};
use super::fields::vector;
use super::{legend_bar, materials_panel};
use crate::viewer::input::action::Action;
use crate::viewer::layout::Resolution;
use crate::viewer::scene::SceneInfo;
use crate::viewer::scene::controls::Controls;
use crate::viewer::scene::views::{SceneViews, TURNTABLE_FRAMES};

/// What the side panel keeps besides the scene and the controls.
pub struct PanelState {
    /// The path typed in the "open" field.
    pub open_field: String,
    /// Where Save writes the image (the camera goes beside it).
    pub save_field: String,
    /// The last thing the viewer did worth saying (saved, printed).
    pub message: Option<String>,
    /// How the image's size is chosen: fit to the window, N×N or W×H.
    pub resolution: Resolution,
    /// Largest image side the GPU takes.
    pub max_side: u32,
    /// Exposure, tone curve and the comparison with a snapshot.
    pub display: DisplayControls,
    /// The snapshot's pixels as shown: the image given with `--compare`, or the image as it was
    /// when B kept it. The difference display measures against them, and the ray tree panel
    /// shows the picked pixel's.
    pub compared: Option<Arc<SrgbImage>>,
}

/// Shows the side panel for `scene` (with the colour bar of the debug view being rendered, if it has
/// one); returns what its buttons asked for.
pub fn side_panel(
    ui: &mut egui::Ui,
    controls: &mut Controls,
    scene: &SceneInfo<'_>,
    state: &mut PanelState,
    legend: Option<&Legend>,
) -> Vec<Action> {
    let mut actions = Vec::new();
    egui::Panel::left("controls")
        .resizable(true)
        .default_size(300.0)
        .show(ui, |ui| {
            // A scroll bar that is always there, not one that shows only under the pointer:
            // a newcomer sees at once that the panel holds more than the window shows.
            ui.style_mut().spacing.scroll = egui::style::ScrollStyle::solid();
            egui::ScrollArea::vertical()
                .scroll_bar_visibility(egui::scroll_area::ScrollBarVisibility::AlwaysVisible)
                .show(ui, |ui| {
                    scene_section(ui, scene, state, &mut actions);
                    camera_section(ui, controls, &mut actions);
                    views_section(ui, scene.views, &mut actions);
                    tracing_section(ui, controls, state, legend);
                    lights_section(ui, controls, scene.scene.scene().lights.len());
                    display::section(ui, &mut state.display, &mut actions);
                    materials_panel::show(ui, controls, scene, &mut actions);
                    save_section(ui, state, &mut actions);
                });
        });
    actions
}

/// Shows the status line (and why the controls cannot be rendered, if so) at the bottom, with
/// the buttons that skip the preview and pause or resume refinement (`paused`: it is paused);
/// returns what they asked for.
pub fn status_bar(
    ui: &mut egui::Ui,
    line: &str,
    control_error: Option<&str>,
    paused: bool,
) -> Vec<Action> {
    let mut actions = Vec::new();
    egui::Panel::bottom("status").show(ui, |ui| {
        if let Some(e) = control_error {
            ui.colored_label(Color32::from_rgb(255, 120, 80), e);
        }
        ui.horizontal(|ui| {
            if ui
                .button("Skip preview (Enter)")
                .on_hover_text("trace at block size 1 at once")
                .clicked()
            {
                actions.push(Action::Skip);
            }
            let pause = if paused {
                "Resume (Space)"
            } else {
                "Pause (Space)"
            };
            if ui.button(pause).clicked() {
                actions.push(Action::TogglePause);
            }
        });
        // Cut at the window's edge rather than wrapped (hovering shows it whole): the bar's
        // height must not depend on its text, or in fit mode a longer line would shrink the
        // image, which restarts the render, which changes the line.
        for row in line.lines() {
            ui.add(egui::Label::new(egui::RichText::new(row).monospace()).truncate());
        }
    });
    actions
}

/// The most height the list of scene files beside the open one takes in the panel (points);
/// a longer list scrolls within it.
const SCENE_LIST_HEIGHT: f32 = 120.0;

fn scene_section(
    ui: &mut egui::Ui,
    scene: &SceneInfo<'_>,
    state: &mut PanelState,
    actions: &mut Vec<Action>,
) {
    egui::CollapsingHeader::new("Scene")
        .default_open(true)
        .show(ui, |ui| {
            ui.label(scene.scene.name());
            if let Some(e) = scene.load_error {
                ui.colored_label(Color32::from_rgb(255, 90, 90), e);
                ui.label("(showing the last good scene)");
            }
            for warning in &scene.scene.scene().warnings {
                ui.colored_label(
                    Color32::from_rgb(255, 200, 80),
                    format!("warning: {warning}"),
                );
            }
            // Monospace: its font has the report's arrow (→), egui's proportional one not.
            for note in &scene.scene.scene().notes {
                ui.label(egui::RichText::new(format!("note: {note}")).monospace());
            }
            ui.horizontal(|ui| {
                let field = ui.add(
                    egui::TextEdit::singleline(&mut state.open_field)
                        .hint_text(
                            "scene file (.toml, .nff, .dat, .obj, .ply, .gltf, .glb) or spd:NAME, or drop a file here",
                        )
                        .desired_width(190.0),
                );
                let entered = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
                if (ui.button("Open").clicked() || entered) && !state.open_field.trim().is_empty() {
                    actions.push(Action::Open(Some(PathBuf::from(state.open_field.trim()))));
                }
            });
            if ui.button("Built-in default scene").clicked() {
                actions.push(Action::Open(None));
            }
            // However many files there are, the sections below stay in sight.
            egui::ScrollArea::vertical()
                .id_salt("scene files beside")
                .max_height(SCENE_LIST_HEIGHT)
                .show(ui, |ui| {
                    for file in scene.files_beside {
                        let current = scene.scene.path.as_deref() == Some(file.as_path());
                        let name = file_name(file);
                        if ui.selectable_label(current, name).clicked() && !current {
                            actions.push(Action::Open(Some(file.clone())));
                        }
                    }
                });
        });
}

fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

fn camera_section(ui: &mut egui::Ui, controls: &mut Controls, actions: &mut Vec<Action>) {
    egui::CollapsingHeader::new("Camera")
        .default_open(true)
        .show(ui, |ui| {
            let c = &mut controls.camera;
            vector(ui, "eye    ", &mut c.eye);
            vector(ui, "look at", &mut c.look_at);
            vector(ui, "up     ", &mut c.up);
            ui.add(Slider::new(&mut c.view_angle, 1.0..=170.0).text("view angle °"));
            ui.horizontal(|ui| {
                ui.label("near");
                ui.add(
                    DragValue::new(&mut c.near)
                        .speed(0.01)
                        .range(0.001..=1000.0)
                        .max_decimals(3),
                );
            });
            ui.horizontal(|ui| {
                if ui
                    .button("Reset")
                    .on_hover_text("the scene's camera")
                    .clicked()
                {
                    actions.push(Action::ResetCamera);
                }
                if ui
                    .button("Frame (F)")
                    .on_hover_text("look at the whole scene")
                    .clicked()
                {
                    actions.push(Action::Frame);
                }
            });
            ui.label(
                "left-drag orbit · right/middle-drag pan · wheel dolly · W/A/S/D/Q/E fly · \
                 double-click: orbit centre · click or I: inspect the pixel · Esc: close",
            );
        });
}

fn tracing_section(
    ui: &mut egui::Ui,
    controls: &mut Controls,
    state: &mut PanelState,
    legend: Option<&Legend>,
) {
    egui::CollapsingHeader::new("Tracing")
        .default_open(true)
        .show(ui, |ui| {
            egui::ComboBox::from_label("view")
                .selected_text(controls.debug_view.to_string())
                .show_ui(ui, |ui| {
                    for view in DebugView::iter() {
                        ui.selectable_value(&mut controls.debug_view, view, view.to_string());
                    }
                });
            if let Some(legend) = legend {
                legend_bar::show(ui, legend);
            }
            ui.horizontal(|ui| {
                ui.label("device");
                for device in Device::iter() {
                    ui.selectable_value(&mut controls.device, device, device.to_string())
                        .on_hover_text("the tracer of the shaded image (debug views: the CPU)");
                }
            });
            ui.horizontal(|ui| {
                ui.label("first hits");
                for first_hit in FirstHit::iter() {
                    let name = first_hit.to_string();
                    ui.selectable_value(&mut controls.first_hit, first_hit, name)
                        .on_hover_text(
                            "rays: each eye ray searches the BVH; raster: each starts from the \
                             item buffer a raster pass draws on the GPU (the same image)",
                        );
                }
            });
            let auto_block = &mut controls.auto_block;
            let s = &mut controls.settings;
            ui.add(Slider::new(&mut s.max_depth, 1..=MAX_DEPTH_LIMIT).text("max depth"));
            ui.add(
                Slider::new(&mut s.min_weight, 0.0..=1.0)
                    .logarithmic(true)
                    .smallest_positive(1e-4)
                    .text("min weight"),
            );
            let start = if *auto_block {
                "auto".to_string()
            } else {
                s.block_size.to_string()
            };
            egui::ComboBox::from_label("starting block size")
                .selected_text(start)
                .show_ui(ui, |ui| {
                    ui.selectable_value(auto_block, true, "auto")
                        .on_hover_text("the first pass takes about 8 ms at the last passes' speed");
                    let sizes = std::iter::successors(Some(1), |b| {
                        (b * 2 <= MAX_BLOCK_SIZE).then_some(b * 2)
                    });
                    for b in sizes {
                        let chosen = !*auto_block && s.block_size == b;
                        if ui.selectable_label(chosen, b.to_string()).clicked() {
                            *auto_block = false;
                            s.block_size = b;
                        }
                    }
                });
            ui.horizontal(|ui| {
                ui.label("resolution");
                for (mode, name) in [
                    (Resolution::Fit, "fit window"),
                    (Resolution::Square, "N×N"),
                    (Resolution::Free, "W×H"),
                ] {
                    ui.selectable_value(&mut state.resolution, mode, name);
                }
            });
            ui.horizontal(|ui| {
                let range = 1..=state.max_side;
                let fixed = state.resolution != Resolution::Fit;
                ui.add_enabled(fixed, DragValue::new(&mut s.width).range(range.clone()));
                ui.label("×");
                let free = state.resolution == Resolution::Free;
                ui.add_enabled(free, DragValue::new(&mut s.height).range(range));
                for n in [256, 512, 1024, 2048] {
                    if n <= state.max_side && ui.small_button(n.to_string()).clicked() {
                        s.width = n;
                        s.height = n;
                        state.resolution = Resolution::Square;
                    }
                }
            });
            if state.resolution == Resolution::Square {
                s.height = s.width;
            }
            ui.add(
                Slider::new(&mut s.samples, 1..=MAX_SAMPLES.min(256))
                    .logarithmic(true)
                    .text("samples per pixel"),
            );
            // Adaptive anti-aliasing: 0 gives every pixel all its samples.
            ui.add(
                Slider::new(&mut s.aa_threshold, 0.0..=1.0)
                    .logarithmic(true)
                    .smallest_positive(0.001)
                    .text("AA threshold"),
            )
            .on_hover_text(
                "supersample only pixels that differ from a neighbour by more than this \
                 (0: every pixel takes all the samples)",
            );
            ui.horizontal_wrapped(|ui| {
                ui.checkbox(&mut s.shadows, "shadows");
                ui.checkbox(&mut s.reflections, "reflections");
                ui.checkbox(&mut s.transmission, "transmission");
                ui.checkbox(&mut s.textures, "textures");
            });
            // Caustics: photons shot per round (0 turns them off) and gathered per estimate.
            ui.add(
                Slider::new(&mut s.caustic_photons, 0..=CAUSTIC_PHOTONS_SLIDER_MAX)
                    .logarithmic(true)
                    .smallest_positive(1000.0)
                    .text("caustic photons"),
            );
            ui.add_enabled(
                s.caustic_photons > 0,
                Slider::new(&mut s.caustic_gather, 1..=MAX_CAUSTIC_GATHER)
                    .logarithmic(true)
                    .text("photons per estimate"),
            );
        });
}

/// The caustic photons per round the slider reaches (a scene file may ask for more).
const CAUSTIC_PHOTONS_SLIDER_MAX: u32 = 4_000_000;

fn lights_section(ui: &mut egui::Ui, controls: &mut Controls, light_count: usize) {
    egui::CollapsingHeader::new("Lights")
        .default_open(true)
        .show(ui, |ui| {
            ui.add(Slider::new(&mut controls.light_scale, 0.0..=4.0).text("intensity"));
            ui.label(format!("{light_count} lights in the scene"));
        });
}

fn save_section(ui: &mut egui::Ui, state: &mut PanelState, actions: &mut Vec<Action>) {
    egui::CollapsingHeader::new("Save")
        .default_open(true)
        .show(ui, |ui| {
            ui.add(egui::TextEdit::singleline(&mut state.save_field).desired_width(240.0));
            ui.horizontal(|ui| {
                if ui.button("Save image (Ctrl+S)").clicked() {
                    actions.push(Action::Save);
                }
                if ui.button("Print camera (C)").clicked() {
                    actions.push(Action::PrintCamera);
                }
            });
            if let Some(m) = &state.message {
                ui.label(m);
            }
        });
}

/// The views: which are stored, and the buttons that start and stop the previews.
fn views_section(ui: &mut egui::Ui, views: &SceneViews, actions: &mut Vec<Action>) {
    egui::CollapsingHeader::new("Views")
        .default_open(true)
        .show(ui, |ui| {
            let stored: Vec<String> = views.views.iter().map(|(n, _)| n.to_string()).collect();
            ui.label(if stored.is_empty() {
                "none stored".to_string()
            } else {
                format!("stored: {}", stored.join(" "))
            });
            ui.horizontal(|ui| {
                let (turntable, path) = if views.previewing() {
                    ("Stop (T)", "Stop (P)")
                } else {
                    ("Turntable (T)", "Path (P)")
                };
                if ui
                    .button(turntable)
                    .on_hover_text("preview the eye orbiting the look-at point")
                    .clicked()
                {
                    actions.push(Action::Turntable(TURNTABLE_FRAMES));
                }
                if ui
                    .button(path)
                    .on_hover_text("preview the path through the views, in order")
                    .clicked()
                {
                    actions.push(Action::PlayPath(None));
                }
            });
            ui.label("Ctrl+1…9: store the camera · 1…9: go to it");
        });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viewer::scene::source::load;
    use raylab::views::Views;

    /// Where the texts of `shapes` that read exactly `text` are drawn and shown (their rectangle
    /// inside their clip rectangle), the top of each.
    fn shown_at(shapes: &[egui::epaint::ClippedShape], text: &str) -> Vec<f32> {
        shapes
            .iter()
            .filter_map(|clipped| match &clipped.shape {
                egui::Shape::Text(shape) if shape.galley.text() == text => {
                    let rect = shape.visual_bounding_rect();
                    clipped.clip_rect.contains_rect(rect).then_some(rect.top())
                }
                _ => None,
            })
            .collect()
    }

    #[test]
    fn at_1280_by_800_the_camera_stays_in_sight_and_the_last_section_scrolls_into_view() {
        let loaded = load(None, None).unwrap();
        let mut controls = Controls::from_scene(loaded.scene());
        // A folder of many scene files.
        let files: Vec<PathBuf> = (0..40)
            .map(|i| PathBuf::from(format!("scene_{i:02}.toml")))
            .collect();
        let views = SceneViews::new(Views::default(), None);
        let info = SceneInfo {
            scene: &loaded,
            load_error: None,
            files_beside: &files,
            views: &views,
        };
        let mut state = PanelState {
            open_field: String::new(),
            save_field: "raylab.png".into(),
            message: None,
            resolution: Resolution::Fit,
            max_side: 2048,
            display: DisplayControls::default(),
            compared: None,
        };
        let ctx = egui::Context::default();
        let screen = egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(1280.0, 800.0));
        let mut frame = |k: usize, events: Vec<egui::Event>| {
            let input = egui::RawInput {
                screen_rect: Some(screen),
                time: Some(k as f64 / 60.0),
                events,
                ..Default::default()
            };
            let mut output = ctx.run_ui(input, |ui| {
                side_panel(ui, &mut controls, &info, &mut state, None);
            });
            output.textures_delta.clear();
            output.shapes
        };
        // The second frame, once egui knows the sizes it laid out in the first.
        frame(0, Vec::new());
        let shapes = frame(1, Vec::new());
        let camera = shown_at(&shapes, "Camera");
        assert!(
            camera.iter().any(|&top| top < 400.0),
            "the camera section starts in the upper half: {camera:?}"
        );
        assert!(
            shown_at(&shapes, "Save").is_empty(),
            "the panel holds more than 800 points"
        );
        // The wheel over the panel scrolls it down to its last section.
        let over_panel = egui::pos2(150.0, 600.0);
        let mut last = shapes;
        for k in 2..60 {
            let events = vec![
                egui::Event::PointerMoved(over_panel),
                egui::Event::MouseWheel {
                    unit: egui::MouseWheelUnit::Point,
                    delta: egui::vec2(0.0, -400.0),
                    phase: egui::TouchPhase::Move,
                    source: egui::MouseWheelSource::Unknown,
                    modifiers: egui::Modifiers::NONE,
                },
            ];
            last = frame(k, events);
        }
        let save = shown_at(&last, "Save");
        assert!(
            save.iter().any(|&top| top < 800.0),
            "the Save section scrolls into view: {save:?}"
        );
    }
}
