//! Input made up for scripts: a left click at a window position, as the pointer events a real
//! mouse sends, one frame apart (egui ignores a press and release within the same frame). They
//! join the window's own events before egui sees them, so a scripted click takes the same path
//! as a person's; while they play, the real pointer's events are left out (under a virtual
//! display the pointer sits wherever the server put it, and may move into the window).

use std::collections::VecDeque;

use egui::{Event, Modifiers, PointerButton, Pos2};

/// The events still to send, one list per frame.
#[derive(Default)]
pub struct SyntheticInput {
    frames: VecDeque<Vec<Event>>,
}

impl SyntheticInput {
    /// Queues a left click at `pos` (egui points).
    pub fn click(&mut self, pos: Pos2) {
        let button = |pressed| Event::PointerButton {
            pos,
            button: PointerButton::Primary,
            pressed,
            modifiers: Modifiers::NONE,
        };
        self.frames.push_back(vec![Event::PointerMoved(pos)]);
        self.frames.push_back(vec![button(true)]);
        self.frames.push_back(vec![button(false)]);
    }

    /// Puts this frame's synthetic events into `events` (the window's), instead of the real
    /// pointer's while a click plays.
    pub fn play(&mut self, events: &mut Vec<Event>) {
        let Some(frame) = self.frames.pop_front() else {
            return;
        };
        events.retain(|e| {
            !matches!(
                e,
                Event::PointerMoved(_)
                    | Event::MouseMoved(_)
                    | Event::PointerButton { .. }
                    | Event::PointerGone
            )
        });
        events.extend(frame);
    }

    pub fn is_empty(&self) -> bool {
        self.frames.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use egui::pos2;

    use super::*;
    use crate::viewer::input::action::Action;
    use crate::viewer::input::harness::Harness;

    #[test]
    fn a_synthetic_click_is_a_click_on_the_image() {
        let mut input = SyntheticInput::default();
        input.click(pos2(35.0, 75.0));
        let mut h = Harness::new();
        let mut actions = Vec::new();
        while !input.is_empty() {
            // The real pointer, somewhere else, is left out.
            let mut events = vec![Event::PointerMoved(pos2(90.0, 10.0)), Event::PointerGone];
            input.play(&mut events);
            assert!(!events.contains(&Event::PointerGone));
            actions.extend(h.frame(events));
        }
        assert_eq!(actions, vec![Action::PickPixel { x: 3, y: 7 }]);
        let mut events = vec![Event::PointerGone];
        input.play(&mut events);
        assert_eq!(
            events,
            vec![Event::PointerGone],
            "nothing queued, nothing changed"
        );
    }
}
