//! What the user (or a test script) asks the viewer to do, beyond editing a control: the mouse,
//! the keys, the panels' buttons and the script all speak in [`Action`]s, and the app carries
//! them out in one place.

use std::path::PathBuf;

use glam::Vec3;
use raylab::inspect::DebugView;
use raylab::render::{Device, FirstHit};
use raylab::tone::ToneCurve;

use crate::viewer::scene::edits::{LightEdit, MaterialEdit};

#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    /// Turn around the look-at point, in degrees.
    Orbit { yaw: f32, pitch: f32 },
    /// Follow a cursor dragged by this many physical pixels (y down).
    Pan { dx: f32, dy: f32 },
    /// Wheel steps towards the look-at point (negative: away).
    Dolly(f32),
    /// Fly for `seconds` in the direction `motion` (x right, y up, z forward).
    Fly { motion: Vec3, seconds: f32 },
    /// Look at the whole scene.
    Frame,
    /// Back to the scene's own camera.
    ResetCamera,
    /// Make the surface point under this image point (pixels, y down) the orbit centre.
    PickCentre { x: f32, y: f32 },
    /// Show the ray tree of image pixel (x, y) (y down) in the ray tree panel.
    PickPixel { x: u32, y: u32 },
    /// Close the ray tree panel and forget the picked pixel.
    CloseRayTree,
    /// Print the ray tree panel's node headings on the terminal (scripts only).
    PrintTree,
    /// Show the picked pixel's ray tree in the scene, seen by an observer (the view area renders
    /// from the observer, and navigation moves it), or go back to the scene camera.
    Rays3d(bool),
    /// Show the ray-tree figure if it is hidden, hide it if shown.
    ToggleRays3d,
    /// Orbit the figure's observer around the tree, in degrees.
    Rays3dOrbit { yaw: f32, pitch: f32 },
    /// Show the figure's tree up to this generation.
    Rays3dGenerations(u32),
    /// A left click at the centre of image pixel (x, y), sent as the pointer events of a real
    /// mouse (scripts only).
    Click { x: u32, y: u32 },
    /// Show this debug view of the scene (restarts refinement).
    SetDebugView(DebugView),
    /// Render the shaded image with this tracer (restarts refinement).
    SetDevice(Device),
    /// Find the eye rays' first hits this way (restarts refinement).
    SetFirstHit(FirstHit),
    /// Open a scene file (`None`: the built-in default scene).
    Open(Option<PathBuf>),
    /// Save the image and the camera snippet.
    Save,
    /// Print the camera snippet on the terminal.
    PrintCamera,
    /// Ask for a new window size, in logical pixels (scripts only).
    ResizeWindow { width: u32, height: u32 },
    /// Skip the coarse passes: trace the current image at block size 1 at once.
    Skip,
    /// Pause refinement if it runs, resume it if paused.
    TogglePause,
    /// Pause refinement (it waits, using no CPU, until resumed or restarted by a change).
    Pause,
    /// Resume paused refinement.
    Resume,
    /// Print the status line on the terminal (scripts only).
    PrintStatus,
    /// Keep the image as it is now, to compare with (and show the split view).
    Snapshot,
    /// Show the split view (snapshot left, live image right) or not; either way the live side
    /// shows the image, not its difference.
    Compare(bool),
    /// Turn the split view on or off.
    ToggleCompare,
    /// Show the split view with the live side as the heat map of its difference from the
    /// snapshot.
    CompareDifference,
    /// Turn the difference display on (with the split view) or off.
    ToggleDifference,
    /// Put the split view's divider at this fraction of the image's width.
    Divider(f32),
    /// Show the image at this exposure, in stops.
    Exposure(f32),
    /// Show the image through this tone curve.
    ToneCurve(ToneCurve),
    /// Change a field of the material of this name.
    EditMaterial { name: String, edit: MaterialEdit },
    /// Change a field of light `number` (counted from 1, in the file's order).
    EditLight { number: usize, edit: LightEdit },
    /// Write the edited materials and lights into the TOML scene file.
    SaveScene,
    /// Store the camera as view 1…9 (in `NAME.views.toml` beside the scene file).
    StoreView(u8),
    /// Go to view 1…9.
    RecallView(u8),
    /// Preview a turntable of this many frames, or stop the preview playing.
    Turntable(u32),
    /// Preview the path through the views in this many frames (`None`: 30 between two views),
    /// or stop the preview playing.
    PlayPath(Option<u32>),
}
