//! What the user (or a script) asks for: the mouse and keys over the image, the scripted steps
//! and clicks, the [`action::Action`]s they all become, and the pieces of work the app's carrying
//! out of them uses (camera navigation, picking a surface point).

pub mod action;
#[cfg(test)]
pub mod harness;
pub mod mouse_and_keys;
pub mod navigation;
pub mod pick;
pub mod script;
pub mod script_steps;
pub mod synthetic;

use std::path::{Path, PathBuf};

use self::action::Action;
use self::script::Script;
use self::synthetic::SyntheticInput;

/// The script, the clicks it makes, and what to do once it has run.
pub struct Input {
    script: Script,
    /// Scripted clicks on their way to egui.
    clicks: SyntheticInput,
    /// Exit once the script has run and refinement is over.
    exit_when_done: bool,
    /// Save a screenshot of the window here before exiting.
    screenshot: Option<PathBuf>,
}

impl Input {
    pub fn new(script: Script, exit_when_done: bool, screenshot: Option<PathBuf>) -> Input {
        Input {
            script,
            clicks: SyntheticInput::default(),
            exit_when_done,
            screenshot,
        }
    }

    /// Puts this frame's scripted pointer events into the window's `events`.
    pub fn play(&mut self, events: &mut Vec<egui::Event>) {
        self.clicks.play(events);
    }

    /// Queues a left click at `pos` (egui points).
    pub fn click(&mut self, pos: egui::Pos2) {
        self.clicks.click(pos);
    }

    /// A scripted click is still playing.
    pub fn clicking(&self) -> bool {
        !self.clicks.is_empty()
    }

    /// This frame's scripted action, if any (see [`Script::next`]).
    pub fn next_step(&mut self, idle: bool, loads: u64) -> Option<Action> {
        self.script.next(idle, loads)
    }

    /// The script or its clicks still have steps to play.
    pub fn busy(&self) -> bool {
        !self.script.is_done() || self.clicking()
    }

    pub fn exit_when_done(&self) -> bool {
        self.exit_when_done
    }

    /// The viewer is to exit once this frame is on screen: the script has run and the viewer
    /// is `idle`.
    pub fn finishing(&self, idle: bool) -> bool {
        self.exit_when_done && self.script.is_done() && idle
    }

    /// Where to save the screenshot before exiting.
    pub fn screenshot(&self) -> Option<&Path> {
        self.screenshot.as_deref()
    }
}
