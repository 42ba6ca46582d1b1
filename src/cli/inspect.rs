//! `raylab inspect`: the ray tree of one pixel, as text or JSON, and as the lecture's figure
//! ([`super::figure`]); or, with `--materials`, the scene's materials (a glTF model's beside
//! the glTF values they were made from).

use std::io::Write;
use std::path::Path;

use clap::Args;

use raylab::backend::Backend;
use raylab::formats::gltf::materials::Kind;
use raylab::formats::gltf::read_gltf;
use raylab::formats::nff::NffLighting;
use raylab::formats::{SceneFiles, SceneFormat, printable};
use raylab::inspect::{DebugView, trace_ray_tree};
use raylab::material::Material;
use raylab::render::{FirstHit, assemble};
use raylab::settings::SettingsOverrides;

use super::figure::FigureArgs;
use super::overrides::OverrideArgs;

#[derive(Args, Debug)]
pub struct InspectArgs {
    /// Scene: a .toml, .nff, SDL (.dat, .sdl), .obj, .ply, .gltf or .glb file, or `spd:NAME[:SIZE]`; the built-in default scene when left
    /// out.
    scene: Option<String>,
    /// The scene file's format, whatever its name ends in: toml, nff, sdl, obj, ply or gltf.
    #[arg(long)]
    format: Option<SceneFormat>,
    /// The pixel, `X,Y`: X from the left, Y from the top of the image, from 0.
    #[arg(long, value_parser = parse_pixel, required_unless_present = "materials")]
    pixel: Option<(u32, u32)>,
    /// List the scene's materials instead: for a glTF model, each material's glTF values
    /// beside the raylab material they became.
    #[arg(long, conflicts_with_all = ["pixel", "json"])]
    materials: bool,
    /// Print the tree as JSON instead of text.
    #[arg(long)]
    json: bool,
    /// Overrides of the scene's render settings.
    #[command(flatten)]
    overrides: OverrideArgs,
    /// Brightness of NFF and SPD scenes' lights (see `raylab render --help`).
    #[arg(long, default_value_t = NffLighting::default())]
    nff_lights: NffLighting,
    /// Where the eye ray finds its first hit: rays, or raster (from the item buffer, drawn on
    /// the GPU; the tree says whether the hit came from it).
    #[arg(long, default_value_t = FirstHit::Rays)]
    first_hit: FirstHit,
    /// The ray-tree figure.
    #[command(flatten)]
    figure: FigureArgs,
}

/// `X,Y` as two integers.
fn parse_pixel(text: &str) -> Result<(u32, u32), String> {
    let usage = || format!("expected X,Y (two whole numbers, e.g. 320,240), got `{text}`");
    let (x, y) = text.split_once(',').ok_or_else(usage)?;
    let number = |s: &str| s.trim().parse::<u32>().map_err(|_| usage());
    Ok((number(x)?, number(y)?))
}

pub fn run(mut args: InspectArgs) -> Result<(), String> {
    if args.materials {
        let text = materials_text(args.scene.as_deref(), args.nff_lights, args.format)?;
        return super::print_out(|out| out.write_all(text.as_bytes()));
    }
    args.figure.check()?;
    let observer_look_at = match args.figure.draw {
        Some(_) => args.overrides.take_look_at(),
        None => None,
    };
    let mut scene = super::load_scene(args.scene.as_deref(), args.nff_lights, args.format)?;
    let overrides = SettingsOverrides::from(args.overrides);
    overrides.apply(&mut scene.settings)?;
    scene.camera = overrides.apply_camera(scene.camera.spec)?;
    let (width, height) = (scene.settings.width, scene.settings.height);
    let (x, y) = args
        .pixel
        .ok_or("--pixel X,Y names the pixel whose ray tree to show")?;
    if x >= width || y >= height {
        return Err(format!(
            "pixel ({x}, {y}) is outside the {width}×{height} image (x < {width}, y < {height})"
        ));
    }
    let assembled = assemble(scene)?;
    let mut backend = Backend::new(super::thread_pool(None)?);
    backend.set_first_hit(args.first_hit);
    let items = backend
        .item_buffer(&assembled, ((0, 0), (width, height)))
        .map_err(|e| super::explain(e, DebugView::Shaded, args.first_hit))?;
    let tracer = assembled.tracer().with_item_buffer(items.as_ref());
    let tree = trace_ray_tree(&tracer, x, y);
    let text = if args.json {
        let json = serde_json::to_string_pretty(&tree)
            .map_err(|e| format!("cannot write the tree as JSON: {e}"))?;
        json + "\n"
    } else {
        tree.to_text()
    };
    super::print_out(|out| out.write_all(text.as_bytes()))?;
    args.figure
        .write(&tree, &assembled, observer_look_at, &mut backend)
}

/// `--materials`: each material of the scene `name` as raylab has it; for a glTF model, with
/// the glTF values it was made from and the report line first.
fn materials_text(
    name: Option<&str>,
    lighting: NffLighting,
    format: Option<SceneFormat>,
) -> Result<String, String> {
    let path = name.map(Path::new);
    let is_gltf = match (format, path) {
        (Some(format), _) => format == SceneFormat::Gltf,
        (None, Some(path)) => SceneFormat::of(path) == SceneFormat::Gltf,
        (None, None) => false,
    };
    let mut text = String::new();
    if let (true, Some(path)) = (is_gltf, path) {
        let files = SceneFiles::Folder(path.parent().unwrap_or(Path::new("")));
        let bytes = files
            .read(path)
            .map_err(|e| format!("{}: cannot read it: {e}", path.display()))?;
        let model = read_gltf(path, &bytes, files).map_err(|e| e.to_string())?;
        text += &format!("{}\n", model.report);
        for (k, (values, material)) in model.pbr_values.iter().zip(&model.materials).enumerate() {
            let name = &model.material_names[k];
            let [r, g, b, a] = values.base_color;
            let texture = match material.texture {
                Some(t) => format!(", base colour texture {t}"),
                None => String::new(),
            };
            let cutoff = match values.alpha_cutoff {
                Some(cutoff) => format!(", alpha cut at {cutoff}"),
                None => String::new(),
            };
            text += &format!(
                "material {k} `{}` → {}\n  glTF:   base colour {r} {g} {b} {a}{texture}{cutoff}, metallic {}, \
                 roughness {}, transmission {}, ior {}, emissive {} × {}\n  raylab: {}\n",
                printable(name),
                kind_name(Kind::of(material)),
                values.metallic,
                values.roughness,
                values.transmission,
                values.ior,
                triple(values.emissive),
                values.emissive_strength,
                raylab_values(material),
            );
        }
        return Ok(text);
    }
    let scene = super::load_scene(name, lighting, format)?;
    for (k, material) in scene.materials.iter().enumerate() {
        text += &format!(
            "material {k} `{}`\n  raylab: {}\n",
            printable(&scene.material_names[k]),
            raylab_values(material)
        );
    }
    Ok(text)
}

/// A report kind's name.
fn kind_name(kind: Kind) -> &'static str {
    match kind {
        Kind::Mirror => "mirror",
        Kind::Glass => "glass",
        Kind::Phong => "Phong",
    }
}

/// Three numbers, space-separated.
fn triple(c: [f32; 3]) -> String {
    format!("{} {} {}", c[0], c[1], c[2])
}

/// A raylab material's numbers, in the scene file's names.
fn raylab_values(m: &Material) -> String {
    let texture = |texture: Option<u32>| match texture {
        Some(t) => format!(" × texture {t}"),
        None => String::new(),
    };
    let (texture, emission_texture) = (texture(m.texture), texture(m.emission_texture));
    let cutoff = match m.alpha_cutoff {
        Some(cutoff) => format!(", alpha_cutoff {cutoff}"),
        None => String::new(),
    };
    format!(
        "color {}{texture}{cutoff}, ambient {}, diffuse {}, specular {} in {}, shininess {}, \
         reflectivity {} in {}, transparency {}, ior {}, fresnel {}, emission {}{emission_texture}",
        triple(m.color.to_array()),
        m.ambient,
        m.diffuse,
        m.specular,
        triple(m.specular_color.to_array()),
        m.shininess,
        m.reflectivity,
        triple(m.reflection_color.to_array()),
        m.transparency,
        m.ior,
        m.fresnel,
        triple(m.emission.to_array()),
    )
}
