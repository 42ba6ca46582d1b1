//! The ray-tree figure in the viewer: the view area switched to the picked pixel's ray tree seen
//! by an observer, and back to the scene camera; the observer moved; how much of the tree shows.
//! The image renders from the observer ([`ShownScene::observer`]), and the ray tree thread draws
//! the figure's lines over it ([`crate::viewer::workers::picked_pixel::FigureView`]).

use raylab::figure::{OBSERVER_ANGLE, RayFigure, side_view};

use super::App;
use crate::viewer::input::action::Action;
use crate::viewer::input::navigation;
use crate::viewer::scene::ShownScene;

impl App {
    /// Carries out the figure's actions.
    pub(super) fn rays3d(&mut self, action: Action) {
        match action {
            Action::Rays3d(on) => self.show_rays3d(on),
            Action::ToggleRays3d => {
                let shown = self.scene.shown().is_some_and(|s| s.observer.is_some());
                self.show_rays3d(!shown);
            }
            Action::Rays3dOrbit { yaw, pitch } => {
                match self.scene.shown_mut().and_then(|s| s.observer.as_mut()) {
                    Some(observer) => *observer = navigation::orbit(observer, yaw, pitch),
                    None => self.say("the ray-tree figure is not shown: `rays3d on` first"),
                }
            }
            Action::Rays3dGenerations(k) => self.tracing.picked.figure.generations = Some(k.max(1)),
            _ => {}
        }
    }

    /// Shows the figure from the observer that frames it from the side, or goes back to the
    /// scene camera.
    fn show_rays3d(&mut self, on: bool) {
        let picked = &self.tracing.picked;
        let Some(s) = self.scene.shown_mut() else {
            return;
        };
        if !on || s.observer.is_some() {
            s.observer = s.observer.filter(|_| on);
            return;
        }
        let Some(traced) = picked.tree.as_ref().filter(|_| picked.pixel.is_some()) else {
            self.say("pick a pixel first: click the image, then R shows its rays from outside");
            return;
        };
        let generations = picked.figure.generations.unwrap_or(u32::MAX);
        let scene = (s.scene.scene(), &traced.camera);
        let figure = RayFigure::new(&traced.tree, scene, traced.size, generations);
        let aspect = traced.size.0 as f32 / traced.size.1.max(1) as f32;
        s.observer = Some(side_view(&figure, &traced.camera, OBSERVER_ANGLE, aspect));
    }

    /// Esc and the ray tree panel's Close: back from the figure to the scene camera, else the
    /// picked pixel forgotten.
    pub(super) fn close_ray_tree(&mut self) {
        if let Some(ShownScene {
            observer: observer @ Some(_),
            ..
        }) = self.scene.shown_mut()
        {
            *observer = None;
        } else {
            self.tracing.picked.close();
        }
    }

    /// Picks a pixel of the scene camera's image, unless the image is the figure's observer's.
    pub(super) fn pick_pixel(&mut self, pixel: (u32, u32)) {
        if self.scene.shown().is_some_and(|s| s.observer.is_some()) {
            self.say("the image is the observer's: R or Esc goes back to pick another pixel");
        } else {
            self.tracing.picked.pick(pixel);
        }
    }

    /// Shows `message` in the side panel.
    fn say(&mut self, message: &str) {
        self.ui.panel.message = Some(message.into());
    }
}
