//! Scripted input, for tests and demonstrations: `--script "wait; orbit 30 10 5; wait"` drives
//! the viewer through the same [`Action`]s as the mouse and keys. Steps, separated by `;` or new
//! lines, start once the first scene has loaded; [`STEPS`](super::script_steps::STEPS) lists them.

use std::collections::VecDeque;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use glam::Vec3;
use raylab::inspect::DebugView;
use raylab::render::{Device, FirstHit};
use raylab::tone::{Tone, ToneCurve};

use super::action::Action;
use super::script_steps::keywords;
use crate::viewer::layout::MAX_WINDOW_SIDE;
use crate::viewer::scene::edits::{LightEdit, MaterialEdit};

#[derive(Clone, Debug, PartialEq)]
enum Step {
    Wait,
    /// Waits for this many scene loads to have finished.
    WaitLoad(u64),
    /// Lets `time` pass from the frame it is first reached (`until`, then).
    Sleep {
        time: Duration,
        until: Option<Instant>,
    },
    /// The same action on each of `frames` frames.
    Repeat {
        action: Action,
        frames: u32,
    },
}

/// A parsed script and how far it has run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Script {
    steps: VecDeque<Step>,
}

impl Script {
    pub fn parse(text: &str) -> Result<Script, String> {
        let steps = text
            .split([';', '\n'])
            .map(str::trim)
            .filter(|s| !s.is_empty())
            .map(|s| parse_step(s).map_err(|e| format!("script step `{s}`: {e}")))
            .collect::<Result<_, _>>()?;
        Ok(Script { steps })
    }

    pub fn is_done(&self) -> bool {
        self.steps.is_empty()
    }

    /// This frame's action, if any. `idle` says whether refinement is over (and shown), which is
    /// what `wait` waits for; `loads` counts the scene loads finished so far.
    pub fn next(&mut self, idle: bool, loads: u64) -> Option<Action> {
        loop {
            match self.steps.front_mut()? {
                Step::Wait if idle => {
                    self.steps.pop_front();
                }
                Step::Wait => return None,
                Step::WaitLoad(count) if loads >= *count => {
                    self.steps.pop_front();
                }
                Step::WaitLoad(_) => return None,
                Step::Sleep { time, until } => {
                    let until = *until.get_or_insert_with(|| Instant::now() + *time);
                    if Instant::now() < until {
                        return None;
                    }
                    self.steps.pop_front();
                }
                Step::Repeat { action, frames } => {
                    let action = action.clone();
                    *frames -= 1;
                    if *frames == 0 {
                        self.steps.pop_front();
                    }
                    return Some(action);
                }
            }
        }
    }
}

fn parse_step(step: &str) -> Result<Step, String> {
    let mut words = step.split_whitespace();
    let command = words.next().unwrap_or_default();
    let args: Vec<&str> = words.collect();
    let numbers = || numbers_of(&args);
    let count = |n: Vec<f32>, needed: usize, optional: usize| -> Result<Vec<f32>, String> {
        if n.len() < needed || n.len() > needed + optional {
            Err(format!(
                "takes {needed} number{}{}",
                if needed == 1 { "" } else { "s" },
                if optional > 0 {
                    format!(" (and {optional} optional)")
                } else {
                    String::new()
                }
            ))
        } else {
            Ok(n)
        }
    };
    let frames = |n: &[f32], at: usize| -> Result<u32, String> {
        match n.get(at) {
            None => Ok(1),
            Some(&f) if (1.0..=10_000.0).contains(&f) && f.fract() == 0.0 => Ok(f as u32),
            Some(f) => Err(format!("frames must be a whole number from 1, got {f}")),
        }
    };
    let once = |action| Step::Repeat { action, frames: 1 };
    let spread = |n: f32, frames: u32| n / frames as f32;
    Ok(match command {
        "wait" if args.is_empty() => Step::Wait,
        "wait-load" => {
            let n = count(numbers()?, 1, 0)?[0];
            if !(n >= 1.0 && n.fract() == 0.0) {
                return Err(format!("takes a whole number of loads from 1, got {n}"));
            }
            Step::WaitLoad(n as u64)
        }
        "frame" if args.is_empty() => once(Action::Frame),
        "reset" if args.is_empty() => once(Action::ResetCamera),
        "save" if args.is_empty() => once(Action::Save),
        "print-camera" if args.is_empty() => once(Action::PrintCamera),
        "open" => once(Action::Open(
            (!args.is_empty()).then(|| PathBuf::from(args.join(" "))),
        )),
        "orbit" => {
            let n = count(numbers()?, 2, 1)?;
            let frames = frames(&n, 2)?;
            Step::Repeat {
                action: Action::Orbit {
                    yaw: spread(n[0], frames),
                    pitch: spread(n[1], frames),
                },
                frames,
            }
        }
        "pan" => {
            let n = count(numbers()?, 2, 1)?;
            let frames = frames(&n, 2)?;
            Step::Repeat {
                action: Action::Pan {
                    dx: spread(n[0], frames),
                    dy: spread(n[1], frames),
                },
                frames,
            }
        }
        "pick" | "click" => {
            let n = count(numbers()?, 2, 0)?;
            if n.iter()
                .any(|&v| !(0.0..=65535.0).contains(&v) || v.fract() != 0.0)
            {
                return Err("pixel coordinates must be whole numbers from 0".into());
            }
            let (x, y) = (n[0] as u32, n[1] as u32);
            once(match command {
                "pick" => Action::PickPixel { x, y },
                _ => Action::Click { x, y },
            })
        }
        "view" if args.len() == 1 => once(Action::SetDebugView(args[0].parse::<DebugView>()?)),
        "view" => return Err("takes one view name".into()),
        "device" if args.len() == 1 => once(Action::SetDevice(args[0].parse::<Device>()?)),
        "device" => return Err("takes `cpu` or `gpu`".into()),
        "first-hit" if args.len() == 1 => once(Action::SetFirstHit(args[0].parse::<FirstHit>()?)),
        "first-hit" => return Err("takes `rays` or `raster`".into()),
        "snapshot" if args.is_empty() => once(Action::Snapshot),
        "compare" => match args[..] {
            ["on"] => once(Action::Compare(true)),
            ["off"] => once(Action::Compare(false)),
            ["diff"] => once(Action::CompareDifference),
            _ => return Err("takes `on`, `off` or `diff`".into()),
        },
        "divider" => {
            let n = count(numbers()?, 1, 0)?[0];
            if !(0.0..=1.0).contains(&n) {
                return Err(format!(
                    "takes a fraction of the image's width from 0 to 1, got {n}"
                ));
            }
            once(Action::Divider(n))
        }
        "exposure" => {
            let n = count(numbers()?, 1, 0)?[0];
            once(Action::Exposure(Tone::new(n, ToneCurve::Clamp)?.exposure))
        }
        "tonemap" if args.len() == 1 => once(Action::ToneCurve(args[0].parse::<ToneCurve>()?)),
        "tonemap" => return Err("takes one tone curve name".into()),
        "rays3d" => match args[..] {
            ["on"] => once(Action::Rays3d(true)),
            ["off"] => once(Action::Rays3d(false)),
            ["orbit", ..] => {
                let n = count(numbers_of(&args[1..])?, 2, 0)?;
                once(Action::Rays3dOrbit {
                    yaw: n[0],
                    pitch: n[1],
                })
            }
            ["generations", k] => match k.parse::<u32>() {
                Ok(k) if k >= 1 => once(Action::Rays3dGenerations(k)),
                _ => {
                    return Err(format!(
                        "generations takes a whole number from 1, got `{k}`"
                    ));
                }
            },
            _ => return Err("takes `on`, `off`, `orbit DX DY` or `generations K`".into()),
        },
        "close-inspector" if args.is_empty() => once(Action::CloseRayTree),
        "print-tree" if args.is_empty() => once(Action::PrintTree),
        "dolly" => once(Action::Dolly(count(numbers()?, 1, 0)?[0])),
        "resize" => {
            let n = count(numbers()?, 2, 0)?;
            let most = MAX_WINDOW_SIDE as f32;
            if n.iter()
                .any(|&v| !(1.0..=most).contains(&v) || v.fract() != 0.0)
            {
                return Err(format!("sizes must be whole numbers from 1 to {most}"));
            }
            once(Action::ResizeWindow {
                width: n[0] as u32,
                height: n[1] as u32,
            })
        }
        "skip" if args.is_empty() => once(Action::Skip),
        "pause" if args.is_empty() => once(Action::Pause),
        "resume" if args.is_empty() => once(Action::Resume),
        "print-status" if args.is_empty() => once(Action::PrintStatus),
        "sleep" => {
            let n = count(numbers()?, 1, 0)?[0];
            if !(0.0..=600.0).contains(&n) {
                return Err(format!("takes seconds from 0 to 600, got {n}"));
            }
            Step::Sleep {
                time: Duration::from_secs_f32(n),
                until: None,
            }
        }
        "bookmark" | "recall" => {
            let n = count(numbers()?, 1, 0)?[0];
            if !((1.0..=9.0).contains(&n) && n.fract() == 0.0) {
                return Err(format!("views are numbered 1 to 9, got {n}"));
            }
            once(match command {
                "bookmark" => Action::StoreView(n as u8),
                _ => Action::RecallView(n as u8),
            })
        }
        "turntable" => {
            let n = count(numbers()?, 1, 0)?;
            once(Action::Turntable(frames(&n, 0)?))
        }
        "play-path" => {
            let n = count(numbers()?, 0, 1)?;
            once(Action::PlayPath(
                n.first().map(|_| frames(&n, 0)).transpose()?,
            ))
        }
        "fly" => {
            let n = count(numbers()?, 4, 0)?;
            once(Action::Fly {
                motion: Vec3::new(n[0], n[1], n[2]),
                seconds: n[3],
            })
        }
        "material" if args.len() >= 2 => {
            let flag = match args[2..] {
                ["on" | "true"] => Some(true),
                ["off" | "false"] => Some(false),
                _ => None,
            };
            let values = if flag.is_some() {
                Vec::new()
            } else {
                numbers_of(&args[2..])?
            };
            once(Action::EditMaterial {
                name: args[0].to_string(),
                edit: MaterialEdit::parse(args[1], &values, flag)?,
            })
        }
        "material" => return Err("takes a material's name, a field and its value".into()),
        "light" if args.len() >= 2 => {
            let number = args[0]
                .parse::<usize>()
                .ok()
                .filter(|&n| n >= 1)
                .ok_or_else(|| format!("`{}` is not a light number (from 1)", args[0]))?;
            once(Action::EditLight {
                number,
                edit: LightEdit::parse(args[1], &numbers_of(&args[2..])?)?,
            })
        }
        "light" => return Err("takes a light's number, a field and its value".into()),
        "save-scene" if args.is_empty() => once(Action::SaveScene),
        "wait" | "frame" | "reset" | "save" | "print-camera" | "close-inspector" | "print-tree"
        | "snapshot" | "save-scene" | "skip" | "pause" | "resume" | "print-status" => {
            return Err("takes no arguments".into());
        }
        _ => {
            return Err(format!("unknown step (use {})", keywords()));
        }
    })
}

/// The finite numbers `args` write; the error names the first that is not one.
fn numbers_of(args: &[&str]) -> Result<Vec<f32>, String> {
    args.iter()
        .map(|a| {
            a.parse::<f32>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("`{a}` is not a number"))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_run_in_order_and_wait_for_refinement() {
        let mut script = Script::parse("wait; orbit 30 -10 3\nframe;wait;print-camera").unwrap();
        assert_eq!(script.next(false, 0), None, "waits while refining");
        let orbit = Action::Orbit {
            yaw: 10.0,
            pitch: -10.0 / 3.0,
        };
        for _ in 0..3 {
            assert_eq!(script.next(true, 0), Some(orbit.clone()));
        }
        assert_eq!(script.next(false, 0), Some(Action::Frame));
        assert_eq!(script.next(false, 0), None);
        assert!(!script.is_done());
        assert_eq!(script.next(true, 0), Some(Action::PrintCamera));
        assert!(script.is_done());
        assert_eq!(script.next(true, 0), None);
    }

    #[test]
    fn wait_load_waits_for_that_many_loads() {
        let mut script = Script::parse("wait-load 2; frame").unwrap();
        assert_eq!(script.next(true, 0), None);
        assert_eq!(script.next(true, 1), None);
        assert_eq!(script.next(false, 2), Some(Action::Frame));
    }

    #[test]
    fn every_step_parses() {
        let mut script = Script::parse(
            "pan 10 -4; dolly -2; fly 0 0 1 0.5; reset; save; open a b.toml; open; resize 300 200;\
             pick 3 0; click 0 7; print-tree; close-inspector; view bvh-cost",
        )
        .unwrap();
        let all: Vec<_> = std::iter::from_fn(|| script.next(true, 0)).collect();
        assert_eq!(
            all,
            vec![
                Action::Pan { dx: 10.0, dy: -4.0 },
                Action::Dolly(-2.0),
                Action::Fly {
                    motion: Vec3::Z,
                    seconds: 0.5
                },
                Action::ResetCamera,
                Action::Save,
                Action::Open(Some(PathBuf::from("a b.toml"))),
                Action::Open(None),
                Action::ResizeWindow {
                    width: 300,
                    height: 200
                },
                Action::PickPixel { x: 3, y: 0 },
                Action::Click { x: 0, y: 7 },
                Action::PrintTree,
                Action::CloseRayTree,
                Action::SetDebugView(DebugView::BvhCost),
            ]
        );
    }

    #[test]
    fn bad_steps_say_what_is_wrong() {
        for (text, expected) in [
            ("jump", "unknown step"),
            ("orbit 1", "takes 2 numbers"),
            ("orbit 1 x", "`x` is not a number"),
            ("orbit 1 2 0", "whole number"),
            ("orbit 1 2 1.5", "whole number"),
            ("wait 3", "takes no arguments"),
            ("wait-load", "takes 1 number"),
            ("wait-load 0", "whole number of loads"),
            ("dolly nan", "not a number"),
            ("resize 0 10", "whole numbers from 1"),
            ("pick -1 2", "whole numbers from 0"),
            ("click 1.5 2", "whole numbers from 0"),
            ("pick 1", "takes 2 numbers"),
            ("print-tree now", "takes no arguments"),
            ("view", "takes one view name"),
            ("view glossy", "unknown view"),
            ("device", "takes `cpu` or `gpu`"),
            ("device tpu", "unknown device"),
            ("first-hit", "takes `rays` or `raster`"),
            ("first-hit zbuffer", "unknown first-hit search"),
        ] {
            let err = Script::parse(text).unwrap_err();
            assert!(err.contains(expected), "{text}: {err}");
            assert!(err.contains(text), "{text}: {err}");
        }
        assert!(Script::parse("").unwrap().is_done());
    }

    #[test]
    fn skip_pause_resume_sleep_and_print_status_parse() {
        let mut script =
            Script::parse("skip; pause; print-status; sleep 0.05; resume; print-status").unwrap();
        assert_eq!(script.next(false, 0), Some(Action::Skip));
        assert_eq!(script.next(false, 0), Some(Action::Pause));
        assert_eq!(script.next(false, 0), Some(Action::PrintStatus));
        let slept = Instant::now();
        while script.next(false, 0).is_none() {
            std::thread::sleep(Duration::from_millis(5));
        }
        assert!(slept.elapsed() >= Duration::from_millis(50), "it slept");
        assert_eq!(script.next(false, 0), Some(Action::PrintStatus));
        assert!(script.is_done());
        for (text, expected) in [
            ("pause 2", "takes no arguments"),
            ("sleep", "takes 1 number"),
            ("sleep -1", "from 0 to 600"),
        ] {
            let err = Script::parse(text).unwrap_err();
            assert!(err.contains(expected), "{text}: {err}");
        }
    }

    #[test]
    fn display_steps_parse_and_say_what_is_wrong() {
        let mut script = Script::parse(
            "exposure -1.5; tonemap filmic; snapshot; compare off; compare on; divider 0.25; \
             compare diff",
        )
        .unwrap();
        let all: Vec<_> = std::iter::from_fn(|| script.next(true, 0)).collect();
        assert_eq!(
            all,
            vec![
                Action::Exposure(-1.5),
                Action::ToneCurve(ToneCurve::Filmic),
                Action::Snapshot,
                Action::Compare(false),
                Action::Compare(true),
                Action::Divider(0.25),
                Action::CompareDifference,
            ]
        );
        for (text, expected) in [
            ("exposure", "takes 1 number"),
            ("exposure 99", "exposure must be from -16 to 16 stops"),
            ("tonemap aces", "unknown tone curve `aces`"),
            ("tonemap", "takes one tone curve name"),
            ("snapshot now", "takes no arguments"),
            ("compare", "takes `on`, `off` or `diff`"),
            ("compare yes", "takes `on`, `off` or `diff`"),
            (
                "rays3d",
                "takes `on`, `off`, `orbit DX DY` or `generations K`",
            ),
            ("rays3d orbit 5", "takes 2 numbers"),
            ("rays3d generations 0", "a whole number from 1, got `0`"),
            ("divider 1.5", "from 0 to 1"),
        ] {
            let err = Script::parse(text).unwrap_err();
            assert!(err.contains(expected), "{text}: {err}");
        }
    }

    #[test]
    fn rays3d_steps_parse() {
        let mut script =
            Script::parse("rays3d on; rays3d orbit 30 -10; rays3d generations 2; rays3d off")
                .unwrap();
        let expected = [
            Action::Rays3d(true),
            Action::Rays3dOrbit {
                yaw: 30.0,
                pitch: -10.0,
            },
            Action::Rays3dGenerations(2),
            Action::Rays3d(false),
        ];
        for action in expected {
            assert_eq!(script.next(false, 0), Some(action));
        }
        assert!(script.is_done());
    }

    #[test]
    fn material_light_and_save_scene_steps_parse() {
        use raylab::color::Color;

        let mut script = Script::parse(
            "material red kd 0.2; material red color 1 0 0; material glass fresnel on; \
             material lamp emission 2 1 0; \
             light 2 intensity 3; light 1 position 0 5 -1; save-scene",
        )
        .unwrap();
        let all: Vec<_> = std::iter::from_fn(|| script.next(true, 0)).collect();
        let material = |name: &str, edit| Action::EditMaterial {
            name: name.into(),
            edit,
        };
        assert_eq!(
            all,
            vec![
                material("red", MaterialEdit::Diffuse(0.2)),
                material("red", MaterialEdit::Color(Color::new(1.0, 0.0, 0.0))),
                material("glass", MaterialEdit::Fresnel(true)),
                material("lamp", MaterialEdit::Emission(Color::new(2.0, 1.0, 0.0))),
                Action::EditLight {
                    number: 2,
                    edit: LightEdit::Intensity(3.0)
                },
                Action::EditLight {
                    number: 1,
                    edit: LightEdit::Position(Vec3::new(0.0, 5.0, -1.0))
                },
                Action::SaveScene,
            ]
        );
        for (text, expected) in [
            ("material red", "takes a material's name"),
            ("material red kd", "takes one number"),
            ("material red color 1 0", "three numbers"),
            ("material red shine 3", "unknown material field"),
            ("material red kd x", "`x` is not a number"),
            ("light 0 intensity 1", "not a light number"),
            ("light 1 brightness 1", "unknown light field"),
            ("save-scene now", "takes no arguments"),
        ] {
            let err = Script::parse(text).unwrap_err();
            assert!(err.contains(expected), "{text}: {err}");
        }
    }

    #[test]
    fn view_steps_parse() {
        let mut script =
            Script::parse("bookmark 1; recall 9; turntable 8; play-path; play-path 5").unwrap();
        let all: Vec<_> = std::iter::from_fn(|| script.next(true, 0)).collect();
        assert_eq!(
            all,
            vec![
                Action::StoreView(1),
                Action::RecallView(9),
                Action::Turntable(8),
                Action::PlayPath(None),
                Action::PlayPath(Some(5)),
            ]
        );
        for (text, expected) in [
            ("bookmark 0", "views are numbered 1 to 9, got 0"),
            ("recall 10", "views are numbered 1 to 9, got 10"),
            ("recall", "takes 1 number"),
            ("turntable 0", "frames must be a whole number from 1"),
            ("turntable", "takes 1 number"),
            ("play-path 1 2", "takes 0 numbers (and 1 optional)"),
        ] {
            let err = Script::parse(text).unwrap_err();
            assert!(err.contains(expected), "{text}: {err}");
        }
    }
}
