//! Cut-outs: where a material's `alpha_cutoff` is above its texture's alpha the surface is not
//! there, for eye rays, reflected rays and shadow rays alike. A square whose texture is opaque
//! on its left half and clear on its right must draw, shade and shadow as the left half alone.

use std::sync::Arc;

use glam::{Vec2, Vec3};
use raylab::bvh::Bvh;
use raylab::camera::PIXEL_CENTRE;
use raylab::color::Color;
use raylab::item_buffer::{Item, ItemBuffer};
use raylab::light::Light;
use raylab::material::Material;
use raylab::mesh::Mesh;
use raylab::progressive::render_image;
use raylab::scene::Scene;
use raylab::settings::RenderSettings;
use raylab::shapes::{Plane, Shape, Sphere};
use raylab::srgb_image::SrgbImage;
use raylab::texture::{Texture, Wrap};
use raylab::whitted::{EYE_RAY_T_MIN, Tracer};

/// What stands over the floor.
#[derive(Clone, Copy)]
enum Square {
    /// The square x ∈ [−1.5, 1.5], its right half cut away by the texture's alpha.
    CutInHalf,
    /// Its left half, x ∈ [−1.5, 0], with the same texture coordinates there, and no cutoff.
    LeftHalf,
    /// The whole square, the texture's alpha not used.
    Whole,
    /// The whole square with a cutoff above every alpha: nothing of it is there.
    CutAway,
    /// No square.
    None,
}

/// A floor lit from above, a mirror ball beside the square, and the square lying level at
/// y = 1.2 over the floor, textured with an image of two texels: red and opaque on the left,
/// green and clear on the right, clamped (so the alpha falls from 1 to 0 between u = 0.25 and
/// 0.75, and is 0.5 at u = 0.5, x = 0).
fn scene(square: Square) -> Scene {
    let settings = RenderSettings {
        width: 96,
        height: 72,
        max_depth: 3,
        ..RenderSettings::default()
    };
    let eye = Vec3::new(0.5, 5.0, 6.0);
    let camera = crate::common::camera(eye, Vec3::new(0.5, 0.5, 0.0), 45.0);
    let mut scene = Scene::new(settings, camera);
    scene.lights.push(Light::Point {
        position: Vec3::new(0.3, 7.0, 1.0),
        color: Color::ONE,
    });
    let floor = scene.add_material(Material {
        color: Color::new(0.7, 0.7, 0.6),
        ..Material::default()
    });
    let mirror = scene.add_material(Material {
        color: Color::ONE,
        diffuse: 0.1,
        reflectivity: 0.85,
        ..Material::default()
    });
    let floor_plane = Plane {
        point: Vec3::ZERO,
        normal: Vec3::Y,
    };
    scene.add_object(Shape::Plane(floor_plane), None, floor);
    let ball = Sphere {
        center: Vec3::new(2.6, 1.0, -0.5),
        radius: 1.0,
    };
    scene.add_object(Shape::Sphere(ball), None, mirror);

    let mut image = SrgbImage::new(2, 1, vec![[230, 40, 30], [40, 200, 60]]);
    image.alpha = vec![255, 0];
    scene.textures.push(Texture::Image {
        image: Arc::new(image),
        wrap: [Wrap::Clamp; 2],
        scale: Vec2::ONE,
        offset: Vec2::ZERO,
    });
    let (right, alpha_cutoff) = match square {
        Square::CutInHalf => (1.5, Some(0.5)),
        Square::LeftHalf => (0.0, None),
        Square::Whole => (1.5, None),
        Square::CutAway => (1.5, Some(1.5)),
        Square::None => return scene,
    };
    let material = scene.add_material(Material {
        texture: Some(0),
        alpha_cutoff,
        specular: 0.3,
        ..Material::default()
    });
    let u = |x: f32| (x + 1.5) / 3.0;
    let mut mesh = Mesh {
        positions: vec![
            Vec3::new(-1.5, 1.2, 1.0),
            Vec3::new(right, 1.2, 1.0),
            Vec3::new(right, 1.2, -1.0),
            Vec3::new(-1.5, 1.2, -1.0),
        ],
        uvs: [0.0, 1.0, 1.0, 0.0]
            .into_iter()
            .zip([-1.5, right, right, -1.5])
            .map(|(v, x)| Vec2::new(u(x), v))
            .collect(),
        faces: vec![[0, 1, 2], [0, 2, 3]],
        ..Mesh::default()
    };
    mesh.material = material;
    scene.geometry.add_mesh(mesh);
    scene
}

/// The item buffer a raster pass, which knows nothing of textures, draws of `scene`: each pixel
/// centre's closest hit, cut away or not.
fn raster_items(scene: &Scene, bvh: &Bvh) -> ItemBuffer {
    let size = (scene.settings.width, scene.settings.height);
    let items = (0..size.0 * size.1)
        .map(|i| {
            let ray = scene
                .camera
                .eye_ray((i % size.0, i / size.0), PIXEL_CENTRE, size);
            let hit = bvh.closest_hit(&scene.geometry, &ray, EYE_RAY_T_MIN, f32::INFINITY)?;
            Some(Item {
                prim: hit.prim,
                part: hit.part,
                t: hit.t,
            })
        })
        .collect();
    ItemBuffer::new(size, (0, 0), size, items)
}

/// The image of the scene with `square`, as 8-bit sRGB values, with its first hits found by
/// rays or, with `raster`, from the item buffer a raster pass draws.
fn rendered(square: Square, raster: bool) -> Vec<[u8; 3]> {
    let scene = scene(square);
    let bvh = Bvh::build(&scene.geometry);
    let tracer = Tracer::new(&scene, &bvh);
    let items = raster.then(|| raster_items(&scene, &bvh));
    let (colors, _) = render_image(&tracer.with_item_buffer(items.as_ref()));
    let settings = &scene.settings;
    SrgbImage::from_linear(settings.width, settings.height, &colors).pixels
}

fn pixels_apart(a: &[[u8; 3]], b: &[[u8; 3]]) -> usize {
    let apart = |(p, q): (&[u8; 3], &[u8; 3])| p.iter().zip(q).any(|(x, y)| x.abs_diff(*y) > 2);
    a.iter().zip(b).filter(|&pair| apart(pair)).count()
}

#[test]
fn a_square_cut_in_half_draws_reflects_and_shadows_as_its_opaque_half_alone() {
    let cut = rendered(Square::CutInHalf, false);
    let half = rendered(Square::LeftHalf, false);
    let whole = rendered(Square::Whole, false);
    // The cut runs where the bilinear alpha crosses 0.5; pixels along it, on the square, in its
    // shadow and in the mirror, may fall either way.
    let differing = pixels_apart(&cut, &half);
    assert!(
        differing <= 72 * 2,
        "{differing} pixels differ from the opaque half's image"
    );
    // The right half is really gone: with it, the square and its shadow cover much more.
    let whole_apart = pixels_apart(&cut, &whole);
    assert!(
        whole_apart > 96 * 72 / 15,
        "only {whole_apart} pixels differ from the whole square's image"
    );
}

#[test]
fn a_square_cut_away_everywhere_leaves_the_image_without_it_bit_for_bit() {
    let without = rendered(Square::None, false);
    for raster in [false, true] {
        assert!(
            rendered(Square::CutAway, raster) == without,
            "the cut-away square shows (first hits from an item buffer: {raster})"
        );
    }
    assert!(rendered(Square::Whole, false) != without);
}

#[test]
fn first_hits_from_an_item_buffer_pass_cut_outs_as_rays_do() {
    assert!(rendered(Square::CutInHalf, true) == rendered(Square::CutInHalf, false));
}

#[test]
fn with_textures_off_the_alpha_is_one_and_nothing_is_cut() {
    let mut cut = scene(Square::CutInHalf);
    cut.settings.textures = false;
    let mut whole = scene(Square::Whole);
    whole.settings.textures = false;
    let image = |scene: &Scene| {
        let bvh = Bvh::build(&scene.geometry);
        render_image(&Tracer::new(scene, &bvh)).0
    };
    assert!(image(&cut) == image(&whole));
}
