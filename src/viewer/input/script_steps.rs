//! The script's steps, listed once: how each is written and what it does. The `--script` help,
//! the parser's error for an unknown step and the table in `docs/viewer.md` come from this list
//! (a test checks the table).

/// One step of the script.
pub struct StepHelp {
    /// The keyword and its arguments, e.g. `orbit YAW PITCH [FRAMES]`.
    pub syntax: &'static str,
    pub does: &'static str,
}

impl StepHelp {
    /// The step's keyword: the first word of its syntax.
    pub fn keyword(&self) -> &'static str {
        self.syntax.split(' ').next().unwrap_or_default()
    }
}

/// Every step, in the order the help lists them.
pub const STEPS: &[StepHelp] = &[
    StepHelp {
        syntax: "wait",
        does: "waits until refinement has reached its last pass and the image is on screen; while paused it waits for ever (so `resume` first), and while a preview plays it waits for the preview to end",
    },
    StepHelp {
        syntax: "wait-load N",
        does: "waits until N scene loads (or failed loads) have finished since the start, the first scene's included: `wait-load 2` waits for the watched file to be saved and reloaded",
    },
    StepHelp {
        syntax: "orbit YAW PITCH [FRAMES]",
        does: "orbits by YAW and PITCH degrees, spread over FRAMES frames like a drag (default 1, at most 10,000)",
    },
    StepHelp {
        syntax: "pan DX DY [FRAMES]",
        does: "pans by DX, DY pixels, spread over FRAMES frames likewise",
    },
    StepHelp {
        syntax: "dolly STEPS",
        does: "dollies by STEPS wheel steps",
    },
    StepHelp {
        syntax: "fly X Y Z SECONDS",
        does: "flies along X Y Z for SECONDS, as the W A S D Q E keys",
    },
    StepHelp {
        syntax: "frame",
        does: "frames the whole scene, as F",
    },
    StepHelp {
        syntax: "reset",
        does: "resets the camera to the scene's",
    },
    StepHelp {
        syntax: "save",
        does: "saves the image and the camera, as Ctrl+S",
    },
    StepHelp {
        syntax: "print-camera",
        does: "prints the camera as a `[camera]` snippet, as C (and, while the ray-tree figure is shown, its observer as an `[observer]` table)",
    },
    StepHelp {
        syntax: "open [PATH]",
        does: "opens the scene at PATH (spaces allowed); `open` alone opens the default scene",
    },
    StepHelp {
        syntax: "resize WIDTH HEIGHT",
        does: "asks for a new window size in logical pixels (1 to 16384)",
    },
    StepHelp {
        syntax: "pick X Y",
        does: "inspects image pixel (X, Y), from the top left",
    },
    StepHelp {
        syntax: "click X Y",
        does: "a left click at the centre of image pixel (X, Y), through the window's input like a mouse's",
    },
    StepHelp {
        syntax: "rays3d MODE",
        does: "the ray-tree figure: MODE `on` shows the picked pixel's rays drawn in the scene, seen by an observer (as R), `off` goes back to the scene camera (as R or Esc), `orbit DX DY` turns the observer round the tree by DX and DY degrees (as a left drag), `generations K` shows the tree up to generation K",
    },
    StepHelp {
        syntax: "close-inspector",
        does: "closes the inspector, as Esc",
    },
    StepHelp {
        syntax: "print-tree",
        does: "prints the ray tree panel's node headings on the terminal, and with an image compared with, the pixel's colour in it and raylab's and what accounts for the difference",
    },
    StepHelp {
        syntax: "view NAME",
        does: "shows a debug view: `shaded`, `normals`, `depth`, `uv`, `object`, `material`, `item-buffer`, `tree-depth`, `rays` or `bvh-cost`",
    },
    StepHelp {
        syntax: "device NAME",
        does: "renders the shaded image with `cpu` or `gpu`, as the Tracing panel's device switch",
    },
    StepHelp {
        syntax: "first-hit NAME",
        does: "finds the eye rays' first hits with `rays` or from the item buffer (`raster`), as the Tracing panel's first-hit switch",
    },
    StepHelp {
        syntax: "exposure STOPS",
        does: "sets the exposure, −16 to 16 stops",
    },
    StepHelp {
        syntax: "tonemap CURVE",
        does: "sets the tone curve: `clamp`, `reinhard` or `filmic`",
    },
    StepHelp {
        syntax: "snapshot",
        does: "keeps the image on screen to compare with (as B) and shows the split",
    },
    StepHelp {
        syntax: "compare MODE",
        does: "the split view (snapshot left, live right): MODE is `on`, `off`, or `diff` (the live side as the heat map of its difference from the snapshot, as X)",
    },
    StepHelp {
        syntax: "divider FRACTION",
        does: "where the split is, from 0 (left edge) to 1 (right edge)",
    },
    StepHelp {
        syntax: "material NAME FIELD VALUE…",
        does: "changes a field of the material called NAME (or numbered `#K`, as in the Materials panel; 0 is the TOML reader's default material): `color R G B`, `emission R G B`, `specular_color R G B`, `reflection_color R G B`, `ka`, `kd`, `ks`, `shininess`, `kr`, `kt`, `ior`, `alpha_cutoff` (one number each), `fresnel` `on` or `off`; e.g. `material red kd 0.2`, `material lamp emission 2 1 0`",
    },
    StepHelp {
        syntax: "light N FIELD VALUE…",
        does: "changes light N (counted from 1, in the file's order): `position X Y Z`, `direction X Y Z`, `color R G B` (its brightest channel 1), `intensity I`; e.g. `light 1 intensity 2`",
    },
    StepHelp {
        syntax: "save-scene",
        does: "writes the edited materials and lights into the TOML scene file",
    },
    StepHelp {
        syntax: "skip",
        does: "skips the coarse passes (block size 1 at once), as Enter",
    },
    StepHelp {
        syntax: "pause",
        does: "pauses refinement, as Space",
    },
    StepHelp {
        syntax: "resume",
        does: "resumes refinement, as Space",
    },
    StepHelp {
        syntax: "sleep SECONDS",
        does: "lets that much time pass, 0 to 600 seconds (frames keep coming)",
    },
    StepHelp {
        syntax: "print-status",
        does: "prints the status line on the terminal after `status: `",
    },
    StepHelp {
        syntax: "bookmark N",
        does: "stores the camera as view N (1 to 9), as Ctrl+N",
    },
    StepHelp {
        syntax: "recall N",
        does: "goes to view N, as the key N",
    },
    StepHelp {
        syntax: "turntable FRAMES",
        does: "previews a turntable of FRAMES frames (T plays 72); while a preview plays, this or `play-path` stops it",
    },
    StepHelp {
        syntax: "play-path [FRAMES]",
        does: "previews the path through the stored views, as P",
    },
];

/// The steps' keywords, for an error message: `wait, wait-load, orbit, …`.
pub fn keywords() -> String {
    let words: Vec<&str> = STEPS.iter().map(StepHelp::keyword).collect();
    words.join(", ")
}

/// The steps as `raylab view --help` lists them, one a line.
pub fn help() -> String {
    let mut text = String::from(
        "Scripted input: steps separated by `;` or new lines, starting once the first scene has \
         loaded, each as the mouse or a key would do it:\n",
    );
    for step in STEPS {
        text += &format!("\n  {}: {}", step.syntax, step.does);
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viewer::input::script::Script;

    /// The steps as the table of `docs/viewer.md`.
    pub fn markdown_table() -> String {
        let mut table = String::from("| step | what it does |\n|---|---|\n");
        for step in STEPS {
            table += &format!("| `{}` | {} |\n", step.syntax, step.does);
        }
        table
    }

    #[test]
    fn the_docs_list_the_steps_as_this_table_does() {
        let docs = include_str!("../../../docs/viewer.md");
        let table = markdown_table();
        assert!(
            docs.contains(&table),
            "docs/viewer.md should hold the script's steps exactly as `STEPS` says:\n{table}"
        );
    }

    #[test]
    fn the_parser_knows_every_listed_step_and_no_other() {
        for step in STEPS {
            let keyword = step.keyword();
            if let Err(e) = Script::parse(keyword) {
                assert!(!e.contains("unknown step"), "`{keyword}`: {e}");
            }
        }
        let e = Script::parse("jump 1").unwrap_err();
        assert!(
            e.contains(&format!("unknown step (use {})", keywords())),
            "{e}"
        );
        assert!(keywords().starts_with("wait, wait-load, orbit"));
    }
}
