//! What the user sees besides the image (egui): the side panel (with its materials and lights
//! panel), the status line, the ray tree panel, the overlay drawn over the image, the display's
//! controls (exposure, tone curve, snapshot) and the split view's divider, the legend's colour
//! bar and colour swatches. Its input becomes [`Action`]s for the app to carry out.

pub mod display;
pub mod fields;
pub mod figure_view;
pub mod legend_bar;
pub mod materials_panel;
pub mod overlay;
pub mod panels;
pub mod ray_tree_panel;
pub mod swatch;

use raylab::camera::Camera;

use self::figure_view::FigureView;
use self::overlay::Overlay;
use self::panels::PanelState;
use crate::viewer::input::action::Action;
use crate::viewer::input::mouse_and_keys::{self, ImageArea};
use crate::viewer::layout::{PixelRect, Resolution, letterbox, whole_pixels};
use crate::viewer::scene::SceneSlot;
use crate::viewer::workers::Tracing;

/// The egui side of the window: its context, the panel's own state and the overlay's texture.
pub struct Ui {
    pub egui: egui::Context,
    pub panel: PanelState,
    overlay: Overlay,
    figure_view: FigureView,
    /// The window's size when it opens, in logical pixels.
    pub window_size: (u32, u32),
}

impl Ui {
    pub fn new(panel: PanelState, window_size: (u32, u32)) -> Ui {
        Ui {
            egui: egui::Context::default(),
            panel,
            overlay: Overlay::default(),
            figure_view: FigureView::default(),
            window_size,
        }
    }

    /// Lays out one frame: the status line, the side panel, the ray tree panel and the image
    /// area with the overlay over it. `seconds` is the frame's length, for flying. Returns the
    /// actions of the frame's input and where the image goes (physical pixels).
    pub fn show(
        &mut self,
        ui: &mut egui::Ui,
        scene: &mut SceneSlot,
        tracing: &mut Tracing,
        status: &str,
        seconds: f32,
    ) -> (Vec<Action>, PixelRect) {
        let mut actions = panels::status_bar(
            ui,
            status,
            tracing.control_error.as_deref(),
            tracing.paused(),
        );
        let legend = tracing.rendering.as_ref().and_then(|r| r.report.legend());
        if let Some((info, controls)) = scene.for_panel() {
            actions.extend(panels::side_panel(
                ui,
                controls,
                &info,
                &mut self.panel,
                legend.as_ref(),
            ));
        }
        let picked = &mut tracing.picked;
        let tone = self.panel.display.tone;
        let compared = self.panel.compared.as_deref().map(|image| (image, tone));
        let observer = scene.shown().and_then(|s| s.observer);
        let rays3d = observer.is_some();
        actions.extend(ray_tree_panel::show(ui, picked, compared, rays3d));
        if picked.hovered.is_some() {
            picked.want_object_ids();
        }
        let ppp = ui.ctx().pixels_per_point();
        let image_size = tracing
            .rendering
            .as_ref()
            .map_or((0, 0), |r| (r.film.width(), r.film.height()));
        let far = scene.shown().map_or(1.0, |s| overlay::far(s.scene.bounds));
        // Inspecting does not change what is inspected: while a pixel is picked, the image keeps
        // the size it was clicked at (the ray tree panel narrows the area it is shown in).
        let fit = self.panel.resolution == Resolution::Fit && picked.pixel.is_none();
        let mut image_rect = PixelRect::ZERO;
        egui::CentralPanel::no_frame().show(ui, |ui| {
            let rect = ui.available_rect_before_wrap();
            let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
            let area = PixelRect {
                x: rect.min.x * ppp,
                y: rect.min.y * ppp,
                width: rect.width() * ppp,
                height: rect.height() * ppp,
            };
            image_rect = if fit {
                fit_to(whole_pixels(area), scene, self.panel.max_side);
                // The image fills the area; until the render of its new size comes, the last
                // image is stretched over it.
                whole_pixels(area)
            } else {
                letterbox(area, image_size.0, image_size.1)
            };
            let image = egui::Rect::from_min_size(
                egui::pos2(image_rect.x / ppp, image_rect.y / ppp),
                egui::vec2(image_rect.width / ppp, image_rect.height / ppp),
            );
            let observer = observer.and_then(|spec| Camera::new(spec).ok());
            if let Some(observer) = observer {
                self.figure_view
                    .paint(ui, picked, (image, image_size), observer);
            } else {
                self.overlay.paint(ui, picked, image, image_size, far);
            }
            if self.panel.display.drop_stale_snapshot(image_size) {
                self.panel.compared = None;
                self.panel.message =
                    Some("the snapshot was dropped: the image's size changed".into());
            }
            display::split_view(ui, &mut self.panel.display, image);
            if tracing.rendering.is_none() {
                let text = scene.load_error().unwrap_or("loading the scene…");
                ui.put(rect, egui::Label::new(text));
            }
            let area = ImageArea {
                image_rect,
                pixels_per_point: ppp,
                image_size,
            };
            actions.extend(mouse_and_keys::actions(ui.ctx(), &response, &area, seconds));
        });
        (actions, image_rect)
    }
}

/// In fit mode, gives the shown scene the size of the view area `fitted` (at most `max_side` a
/// side, the GPU's largest texture); a changed size restarts refinement once, in this frame.
fn fit_to(fitted: PixelRect, scene: &mut SceneSlot, max_side: u32) {
    if fitted.is_empty() {
        return;
    }
    if let Some(s) = scene.shown_mut() {
        let side = |v: f32| (v as u32).clamp(1, max_side);
        s.controls.settings.width = side(fitted.width);
        s.controls.settings.height = side(fitted.height);
    }
}
