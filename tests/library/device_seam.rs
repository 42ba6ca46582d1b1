//! Every program renders through the one backend ([`raylab::backend`]): no file of the command
//! line, the viewer or the examples names the GPU tracer, the CPU tracer's item buffers or the
//! CPU sweep's render functions, so none chooses between the tracers itself.

use std::path::{Path, PathBuf};

use crate::rust_source::{Token, code_only, read, rust_files_under, tokens};

/// The types only the backend renders with.
const TRACER_TYPES: [&str; 3] = ["GpuRenderer", "CpuItems", "ItemRaster"];

/// The CPU sweep's render functions (`raylab::progressive::…`), which the backend calls.
const SWEEP_FUNCTIONS: [&str; 6] = [
    "render",
    "render_film",
    "render_image",
    "render_image_with",
    "render_pass",
    "render_unwatched",
];

/// The programs' Rust files: src/cli, src/viewer, src/main.rs and examples/.
fn program_files() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let folders = ["src/cli", "src/viewer", "examples"];
    let under = folders.iter().flat_map(|f| rust_files_under(&root.join(f)));
    std::iter::once(root.join("src/main.rs"))
        .chain(under)
        .collect()
}

/// Where `tokens` render without the backend: a tracer type named, a sweep function reached
/// through `progressive::`, or imported from it.
fn bypasses(tokens: &[Token]) -> Vec<String> {
    let mut found = Vec::new();
    let mut in_progressive_path = false;
    for (i, token) in tokens.iter().enumerate() {
        let text = token.text.as_str();
        if text == "use" {
            in_progressive_path = false;
        }
        if text == "progressive" && tokens.get(i + 1).is_some_and(|t| t.text == "::") {
            in_progressive_path = true;
        }
        if text == ";" {
            in_progressive_path = false;
        }
        let after_progressive =
            i >= 2 && tokens[i - 1].text == "::" && tokens[i - 2].text == "progressive";
        let sweep = SWEEP_FUNCTIONS.contains(&text) && (after_progressive || in_progressive_path);
        if TRACER_TYPES.contains(&text) || sweep {
            found.push(format!("line {}: {text}", token.line));
        }
    }
    found
}

#[test]
fn no_program_chooses_between_the_tracers_itself() {
    let files = program_files();
    assert!(files.len() > 40, "{} program files", files.len());
    let failures: Vec<String> = files
        .iter()
        .flat_map(|path| {
            let found = bypasses(&tokens(&code_only(&read(path))));
            found
                .into_iter()
                .map(move |f| format!("{}: {f}", path.display()))
        })
        .collect();
    assert!(
        failures.is_empty(),
        "render through raylab::backend::Backend:\n{}",
        failures.join("\n")
    );
}

#[test]
fn the_check_finds_a_program_that_renders_without_the_backend() {
    let program = "use raylab::progressive::{self, render_image};\n\
                   fn f(t: &Tracer) { progressive::render(t); let g: GpuRenderer; }\n\
                   fn g(b: &mut Backend) { b.render_image(a); render(b); }";
    let found = bypasses(&tokens(&code_only(program)));
    assert_eq!(
        found,
        [
            "line 1: render_image",
            "line 2: render",
            "line 2: GpuRenderer"
        ]
    );
}
