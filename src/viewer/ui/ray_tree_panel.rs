//! The ray tree panel: the ray tree of the picked pixel as nested collapsing headings, one per
//! ray (its kind, depth and what it hit), each with the ray's numbers, its shadow rays, the
//! colours it gathered and where and why its branch stopped. While an image is compared with,
//! the pixel's colour there beside raylab's, and what in the tree accounts for the difference. Hovering a heading highlights the
//! object it hit in the image. `print-tree` prints the same headings.

use egui::{Color32, RichText};
use glam::{Vec2, Vec3};
use raylab::color::{Color, srgb_to_linear};
use raylab::compare::difference::pixel_difference;
use raylab::compare::explain::explain_pixel;
use raylab::inspect::{RayNode, RayTree, ShadowRay};
use raylab::srgb_image::SrgbImage;
use raylab::tone::Tone;
use raylab::whitted::{RayKind, StopReason};

use super::swatch::swatch;
use crate::viewer::input::action::Action;
use crate::viewer::workers::picked_pixel::PickedPixel;

/// The panel's widest (points), however long its lines.
const MAX_WIDTH: f32 = 420.0;

/// A ray kind as the panel names it.
pub fn kind_name(kind: RayKind) -> &'static str {
    match kind {
        RayKind::Eye => "eye ray",
        RayKind::Reflected => "reflected ray",
        RayKind::Transmitted => "transmitted ray",
    }
}

/// Why a branch stopped, in words.
fn stop_text(reason: StopReason) -> &'static str {
    match reason {
        StopReason::Miss => "missed: left the scene",
        StopReason::MaxDepth => "depth limit (max depth)",
        StopReason::MinWeight => "adaptive threshold (weight below min weight)",
        StopReason::TotalInternalReflection => "total internal reflection",
        StopReason::Disabled => "switched off in the settings",
        StopReason::RayBudget => "ray budget of the pixel used up",
    }
}

/// The compared image's colour at the tree's pixel (`theirs`, its levels) beside raylab's as
/// shown through `tone`, with swatches, and what accounts for the difference
/// ([`compared_lines`]).
fn compared_ui(ui: &mut egui::Ui, tree: &RayTree, theirs: [u8; 3], tone: Tone) {
    let ours = tone.map(tree.color);
    let linear = |c: [u8; 3]| Color::from_array(c.map(|l| srgb_to_linear(f32::from(l) / 255.0)));
    let [colours, why] = compared_lines(tree, theirs, tone);
    ui.horizontal_wrapped(|ui| {
        swatch(ui, linear(theirs));
        swatch(ui, linear(ours));
        ui.label(colours);
    });
    ui.label(why);
}

/// Two lines: the compared image's levels at the tree's pixel (`theirs`) and raylab's as shown
/// through `tone`; and the term of the tree that accounts for the difference, if one does.
pub fn compared_lines(tree: &RayTree, theirs: [u8; 3], tone: Tone) -> [String; 2] {
    let ours = tone.map(tree.color);
    let levels = |c: [u8; 3]| format!("({}, {}, {})", c[0], c[1], c[2]);
    let colours = format!("your image {}, raylab {}", levels(theirs), levels(ours));
    let why = explain_pixel(tree, theirs, ours)
        .accounted_for
        .unwrap_or_else(|| match pixel_difference(theirs, ours) {
            0 => "the same".to_string(),
            d => format!("{d} levels apart; no single term of the tree accounts for it"),
        });
    [colours, why]
}

/// A ray's heading: its kind, its depth and what it hit.
pub fn heading(node: &RayNode) -> String {
    let what = match &node.hit {
        Some(hit) => format!("{} ({})", hit.label, hit.material_name),
        None => "miss".to_string(),
    };
    format!("{} · depth {}: {what}", kind_name(node.kind), node.depth)
}

/// The tree's headings in the panel's order, each indented two spaces per level.
pub fn heading_lines(tree: &RayTree) -> Vec<String> {
    fn walk(tree: &RayTree, index: usize, level: usize, lines: &mut Vec<String>) {
        let node = &tree.nodes[index];
        lines.push(format!("{}{}", "  ".repeat(level), heading(node)));
        for &child in &node.children {
            walk(tree, child, level + 1, lines);
        }
    }
    let mut lines = Vec::new();
    if !tree.nodes.is_empty() {
        walk(tree, 0, 0, &mut lines);
    }
    lines
}

/// Shows the panel (when a pixel is picked); returns what its buttons asked for.
pub fn show(
    ui: &mut egui::Ui,
    picked: &mut PickedPixel,
    compared: Option<(&SrgbImage, Tone)>,
    rays3d: bool,
) -> Vec<Action> {
    let mut actions = Vec::new();
    picked.hovered = None;
    let Some((x, y)) = picked.pixel else {
        return actions;
    };
    // At most a third of a 1280-wide window: its long lines wrap rather than push the image
    // into a corner.
    egui::Panel::right("inspector")
        .resizable(true)
        .default_size(340.0)
        .max_size(MAX_WIDTH)
        .show(ui, |ui| {
            ui.horizontal(|ui| {
                ui.heading(format!("Pixel ({x}, {y})"));
                if ui.button("Close").on_hover_text("Esc").clicked() {
                    actions.push(Action::CloseRayTree);
                }
            });
            let (label, tip) = if rays3d {
                (
                    "Back to the camera",
                    "R or Esc: the scene camera's image again",
                )
            } else {
                (
                    "See it from outside",
                    "R: the rays drawn in the scene, seen by an observer",
                )
            };
            if ui.button(label).on_hover_text(tip).clicked() {
                actions.push(Action::ToggleRays3d);
            }
            if rays3d {
                let deepest = picked.tree.as_ref().map_or(1, |t| {
                    t.tree.nodes.iter().map(|n| n.depth).max().unwrap_or(1)
                });
                let mut k = picked.figure.generations.unwrap_or(deepest).min(deepest);
                let slider = egui::Slider::new(&mut k, 1..=deepest.max(1)).text("generations");
                if ui.add(slider).changed() {
                    actions.push(Action::Rays3dGenerations(k));
                }
                ui.label(
                    "drag: orbit · wheel: dolly · right drag: pan · click a ray here to mark it",
                );
            } else {
                ui.checkbox(&mut picked.show_overlay, "draw the rays over the image");
            }
            if let Some(e) = &picked.error {
                ui.colored_label(Color32::from_rgb(255, 120, 80), e);
            }
            let Some(traced) = &picked.tree else {
                ui.label("tracing…");
                return;
            };
            let tree = &traced.tree;
            ui.horizontal(|ui| {
                ui.label("pixel colour");
                swatch(ui, tree.color);
            });
            if let Some((image, tone)) = compared.filter(|(i, _)| x < i.width && y < i.height) {
                compared_ui(ui, tree, image.at(x, y), tone);
            }
            let mut timing = format!(
                "{} rays, traced in {:.2} ms",
                tree.nodes.len(),
                traced.time.as_secs_f64() * 1e3
            );
            if let Some(ids) = picked.current_object_ids() {
                let ms = ids.time.as_secs_f64() * 1e3;
                timing += &format!("; objects of the image in {ms:.0} ms");
            }
            ui.label(timing);
            let mut hovered = None;
            let mut links = NodeLinks {
                from_figure: picked.figure.hovered_node.filter(|_| rays3d),
                marked: picked.figure.highlight,
                clicked: None,
            };
            egui::ScrollArea::vertical().show(ui, |ui| {
                if !tree.nodes.is_empty() {
                    node_ui(ui, tree, 0, (&mut hovered, &mut links));
                }
            });
            picked.hovered = hovered;
            if let Some(node) = links.clicked {
                let marked = &mut picked.figure.highlight;
                *marked = (*marked != Some(node)).then_some(node);
            }
        });
    actions
}

/// How the panel's nodes and the figure's lines point at each other.
struct NodeLinks {
    /// The node whose line the cursor is over in the figure: its heading is highlighted.
    from_figure: Option<usize>,
    /// The node whose lines the figure draws wider.
    marked: Option<usize>,
    /// The node whose heading was clicked this frame.
    clicked: Option<usize>,
}

/// One ray and, nested inside, its shadow rays and children. `hovered` is set to the object hit
/// by the ray whose heading the cursor is over.
fn node_ui(
    ui: &mut egui::Ui,
    tree: &RayTree,
    index: usize,
    (hovered, links): (&mut Option<u32>, &mut NodeLinks),
) {
    let node = &tree.nodes[index];
    let mut text = RichText::new(heading(node));
    if links.from_figure == Some(index) {
        text = text.background_color(Color32::from_rgb(90, 80, 20));
    }
    if links.marked == Some(index) {
        text = text.strong();
    }
    let response = egui::CollapsingHeader::new(text)
        .id_salt(("ray", index))
        .default_open(node.depth <= 2)
        .show(ui, |ui| {
            egui::Grid::new(("ray fields", index))
                .num_columns(2)
                .show(ui, |ui| node_fields(ui, node));
            for shadow in &node.shadows {
                shadow_ui(ui, shadow, hovered);
            }
            if let Some(stop) = node.stop {
                ui.label(format!("stopped here: {}", stop_text(stop)));
            }
            for cut in &node.cuts {
                ui.label(format!(
                    "{} not traced: {} (weight {:.4})",
                    kind_name(cut.branch),
                    stop_text(cut.reason),
                    cut.weight
                ));
            }
            for &child in &node.children {
                node_ui(ui, tree, child, (&mut *hovered, &mut *links));
            }
        });
    if response.header_response.hovered() {
        *hovered = node.hit.as_ref().map(|h| h.object);
    }
    if response.header_response.clicked() {
        links.clicked = Some(index);
    }
}

fn node_fields(ui: &mut egui::Ui, node: &RayNode) {
    let mut row = |name: &str, value: String| {
        ui.label(name);
        ui.label(RichText::new(value).monospace());
        ui.end_row();
    };
    row("origin", vec3(node.origin));
    row("direction", vec3(node.dir));
    row("weight", format!("{:.4}", node.weight));
    if let Some(hit) = &node.hit {
        row("object", hit.label.clone());
        row("material", hit.material_name.clone());
        row("t", format!("{:.4}", hit.t));
        row("point", vec3(hit.point));
        row("normal", vec3(hit.normal));
        row("uv", vec2(hit.uv));
        let side = if hit.entering { "front" } else { "back" };
        row("side", side.to_string());
        if hit.emission != Color::ZERO {
            row("emission", vec3(hit.emission));
        }
    }
    if let Some(fog) = &node.fog {
        row("fog transmittance", format!("{:.4}", fog.transmittance));
        ui.label("fog in-scattered");
        swatch(ui, fog.in_scattered);
        ui.end_row();
    }
    if let Some(caustic) = node.caustic {
        ui.label("caustic irradiance");
        swatch(ui, caustic);
        ui.end_row();
    }
    for (name, value) in [
        ("local colour", node.local_color),
        ("factor", node.factor),
        ("colour returned", node.color),
        ("contribution", node.contribution),
    ] {
        ui.label(name);
        swatch(ui, value);
        ui.end_row();
    }
}

fn shadow_ui(ui: &mut egui::Ui, shadow: &ShadowRay, hovered: &mut Option<u32>) {
    let verdict = match (shadow.blocked, shadow.blockers.last()) {
        (true, Some(b)) => format!("blocked by {}", b.label),
        (true, None) => "blocked".to_string(),
        (false, Some(_)) => format!("through {} objects", shadow.blockers.len()),
        (false, None) => "reaches the light".to_string(),
    };
    let response =
        egui::CollapsingHeader::new(format!("shadow ray to light {}: {verdict}", shadow.light))
            .id_salt((
                "shadow",
                shadow.origin.to_array().map(f32::to_bits),
                shadow.light,
            ))
            .show(ui, |ui| {
                ui.label(format!("direction {}", vec3(shadow.dir)));
                ui.label(format!("distance {:.4}", shadow.distance));
                for b in &shadow.blockers {
                    ui.label(format!(
                        "{} at t {:.4}, light left {:.3} {:.3} {:.3}",
                        b.label,
                        b.t,
                        b.transmittance_after[0],
                        b.transmittance_after[1],
                        b.transmittance_after[2]
                    ));
                }
                ui.horizontal(|ui| {
                    ui.label("light arriving");
                    swatch(ui, shadow.light_color);
                });
            });
    if response.header_response.hovered() {
        *hovered = shadow.blockers.last().map(|b| b.object);
    }
}

fn vec3(v: Vec3) -> String {
    format!("{:.3} {:.3} {:.3}", v.x, v.y, v.z)
}

fn vec2(v: Vec2) -> String {
    format!("{:.3} {:.3}", v.x, v.y)
}

#[cfg(test)]
mod tests {
    use raylab::inspect::trace_ray_tree;

    use super::*;
    use crate::viewer::scene::source;

    #[test]
    fn the_headings_follow_the_tree_indented_by_depth() {
        let mut loaded = source::load(None, None).unwrap();
        (
            loaded.assembled.scene.settings.width,
            loaded.assembled.scene.settings.height,
        ) = (24, 24);
        let tracer = loaded.assembled.tracer();
        let trees = (0..24).flat_map(|y| (0..24).map(move |x| (x, y)));
        let tree = trees
            .map(|(x, y)| trace_ray_tree(&tracer, x, y))
            .max_by_key(|t| t.nodes.len())
            .unwrap();
        assert!(tree.nodes.len() > 1);
        let lines = heading_lines(&tree);
        assert_eq!(lines.len(), tree.nodes.len());
        assert!(lines[0].starts_with("eye ray · depth 1: "), "{}", lines[0]);
        for line in &lines {
            let indent = line.len() - line.trim_start().len();
            let depth = indent / 2 + 1;
            assert!(line.contains(&format!("· depth {depth}:")), "{line}");
        }
    }
}
