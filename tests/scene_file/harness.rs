//! What several topics share: the shipped assets' folders, parsing a text as if from `test.toml`
//! in the scenes folder, checking where and why a text fails, and the full-feature file that the
//! full-feature tests read and the robustness test mutates.

use std::path::{Path, PathBuf};

use raylab::formats::SceneError;
use raylab::formats::toml::parse_scene;
use raylab::scene::Scene;

/// The repository's `assets` folder.
pub fn assets() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets")
}

/// The shipped scenes' folder, `assets/scenes`.
pub fn scenes_dir() -> PathBuf {
    assets().join("scenes")
}

/// Parses `text` as `test.toml` in the scenes folder.
pub fn parse(text: &str) -> Result<Scene, SceneError> {
    parse_scene(text, Path::new("test.toml"), &scenes_dir())
}

/// Parses `text`, which must fail, and checks where and why.
pub fn assert_error(text: &str, line: usize, column: usize, message_part: &str) -> SceneError {
    let error = match parse(text) {
        Ok(_) => panic!("expected an error for:\n{text}"),
        Err(error) => error,
    };
    assert_eq!(error.file, Path::new("test.toml"), "{error}");
    assert_eq!((error.line, error.column), (line, column), "{error}");
    assert!(
        error.message.contains(message_part),
        "expected the message to contain {message_part:?}:\n{error}"
    );
    error
}

/// A scene file that uses every feature of the format.
pub const FULL: &str = r#"
[render]
width = 320
height = 200
max_depth = 7
min_weight = 0.05
block_size = 8
samples = 4
aa_threshold = 0.05
background = [0.1, 0.2, 0.3]
ambient = [0.3, 0.3, 0.3]
shadows = false
reflections = false
transmission = false
textures = false
fog_steps = 12
caustic_photons = 1000
caustic_gather = 20

[camera]
eye = [0, 2, 8]
look_at = [0, 1, 0]
up = [0, 1, 0]
view_angle = 30
near = 0.5

[[lights]]
type = "point"
position = [5, 8, 5]
color = [1, 0.5, 0.25]
intensity = 2

[[lights]]
type = "directional"
direction = [0, 3, 4]

[textures.checks]
type = "checker3d"
a = [1, 0, 0]
b = [0, 0, 1]
size = 0.5

[textures.stripes]
type = "checker_uv"
u_count = 4
v_count = 1

[textures.tiles]
type = "image"
file = "../textures/grid.png"
wrap = "clamp"
scale = [3, 2]

[materials.red]
color = [0.8, 0.1, 0.1]
texture = "checks"
alpha_cutoff = 0.25
emission = [0.05, 0.1, 0]
ambient = 0.2
diffuse = 0.7
specular = 0.5
specular_color = [1, 1, 0]
shininess = 10
reflectivity = 0.25
reflection_color = [1, 0.5, 0.25]
transparency = 0.5
ior = 1.33
fresnel = true

[materials.blue]
color = [0, 0, 1]

[materials.stripy]
texture = "stripes"

[materials.tiled]
texture = "tiles"

[[objects]]
type = "sphere"
center = [0, 1, 0]
radius = 2
material = "red"
transform = [ { translate = [0, 1, 0] }, { rotate = { axis = [0, 1, 0], degrees = 90 } }, { scale = [1, 2, 1] } ]

[[objects]]
type = "plane"
point = [0, -1, 0]
normal = [0, 2, 0]

[[objects]]
type = "triangle"
vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
normals = [[0, 0, 1], [0, 0, 1], [0, 0, 1]]
uvs = [[0, 0], [1, 0], [0, 1]]
material = "blue"

[[objects]]
type = "mesh"
positions = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
faces = [[0, 1, 2], [0, 2, 3]]
uvs = [[0, 0], [1, 0], [1, 1], [0, 1]]
transform = [ { scale = [2, 2, 2] } ]

[[objects]]
type = "obj"
file = "../models/tetra.obj"
material = "blue"
"#;
