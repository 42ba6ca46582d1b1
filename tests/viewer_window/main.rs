//! The viewer as a person sees it: the real app in a real window under a virtual X display
//! (Xvfb) with Mesa's software Vulkan, told to exit once refinement is over and to save a
//! screenshot of its window; the image area is compared with a CPU render of the same scene and
//! camera. The tests start Xvfb themselves through `xvfb-run` (`scripts/test` installs it on
//! Debian), or use the display in `DISPLAY`. Without either they fail, saying what to install.

mod harness;

mod command_line;
mod gpu;
mod process;
mod rays3d;
mod refinement;
mod scene_files;
mod tools;
mod window_size;
