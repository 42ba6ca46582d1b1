//! An example of every kind the Rust enumerates (`ShapeKind`, `LightKind`, `TextureKind`),
//! each a `match` over the kinds: a new variant does not compile until it has one here, and the
//! tests that iterate the kinds then try it.

use std::sync::Arc;

use glam::{Vec2, Vec3};
use raylab::color::Color;
use raylab::light::{Light, LightKind, Spot};
use raylab::shapes::{
    Csg, CsgOperation, Cuboid, Ellipsoid, Operand, Paraboloid, Plane, Polygon, Shape, ShapeKind,
    Sphere, TaperedCylinder, Torus,
};
use raylab::srgb_image::SrgbImage;
use raylab::texture::{Texture, TextureKind, Wrap};

/// A shape of `kind` about the origin, within a ball of radius 1.5 (a plane: the floor, y = -1).
pub fn example_shape(kind: ShapeKind) -> Shape {
    let at = Vec3::ZERO;
    match kind {
        ShapeKind::Sphere => Shape::Sphere(Sphere::new(at, 1.0).unwrap()),
        ShapeKind::Plane => Shape::Plane(Plane {
            point: Vec3::new(0.0, -1.0, 0.0),
            normal: Vec3::Y,
        }),
        ShapeKind::Polygon => {
            // A concave pentagon facing the point (2.5, 3.5, 4.5), up and to the side.
            let facing = Vec3::new(2.5, 3.5, 4.5).normalize();
            let across = facing.cross(Vec3::Y).normalize();
            let up = across.cross(facing);
            let corners = [
                (-1.4, -1.0),
                (1.3, -1.1),
                (0.2, 0.1),
                (-0.3, 1.4),
                (-1.5, 0.4),
            ];
            let vertices = corners.iter().map(|&(x, y)| across * x + up * y).collect();
            Shape::Polygon(Polygon::new(vertices).unwrap())
        }
        ShapeKind::Cuboid => Shape::Cuboid(
            Cuboid::new(Vec3::new(-0.9, -0.7, -0.6), Vec3::new(0.8, 0.9, 0.7)).unwrap(),
        ),
        ShapeKind::TaperedCylinder => Shape::TaperedCylinder(
            TaperedCylinder::new(
                Vec3::new(0.0, -0.9, 0.0),
                Vec3::new(0.2, 0.9, 0.1),
                0.9,
                0.4,
                true,
            )
            .unwrap(),
        ),
        ShapeKind::Ellipsoid => {
            Shape::Ellipsoid(Ellipsoid::new(at, Vec3::new(1.2, 0.7, 0.9)).unwrap())
        }
        ShapeKind::Paraboloid => {
            Shape::Paraboloid(Paraboloid::new(Vec3::new(0.0, -0.8, 0.0), 1.0, 1.5, true).unwrap())
        }
        ShapeKind::Torus => Shape::Torus(Torus::new(at, 1.0, 0.35).unwrap()),
        ShapeKind::Csg => {
            let operand = |shape: ShapeKind| Operand {
                shape: example_shape(shape),
                transform: None,
                material: 0,
            };
            let ball = Operand {
                shape: Shape::Sphere(Sphere::new(Vec3::new(0.5, 0.5, 0.6), 0.8).unwrap()),
                transform: None,
                material: 0,
            };
            let csg = Csg::new(
                CsgOperation::Difference,
                vec![operand(ShapeKind::Cuboid), ball],
            );
            Shape::Csg(Box::new(csg.unwrap()))
        }
    }
}

/// A white light of `kind` up and to the right of the origin, lighting it.
pub fn example_light(kind: LightKind) -> Light {
    let position = Vec3::new(3.0, 4.0, 3.0);
    let color = Color::new(1.0, 1.0, 1.0);
    match kind {
        LightKind::Point => Light::Point { position, color },
        LightKind::Directional => Light::Directional {
            direction: position.normalize(),
            color,
        },
        LightKind::Spot => Light::Spot(Spot::new(
            position,
            -position.normalize(),
            25.0,
            5.0,
            color * position.length_squared(),
        )),
    }
}

/// A texture of `kind` in two colours, its pattern small enough to show several times on a
/// shape of size 2.
pub fn example_texture(kind: TextureKind) -> Texture {
    let (a, b) = (Color::new(0.9, 0.8, 0.2), Color::new(0.1, 0.3, 0.8));
    match kind {
        TextureKind::Checker3d => Texture::Checker3d { a, b, size: 0.4 },
        TextureKind::CheckerUv => Texture::CheckerUv {
            a,
            b,
            u_count: 8.0,
            v_count: 4.0,
        },
        TextureKind::Wood => Texture::Wood { a, b },
        TextureKind::Marble => Texture::Marble { color: a },
        TextureKind::Image => {
            let (width, height) = (16, 8);
            let pixels = (0..width * height)
                .map(|i| {
                    [
                        (i * 37 % 256) as u8,
                        (i * 11 % 256) as u8,
                        (i * 5 % 256) as u8,
                    ]
                })
                .collect();
            Texture::Image {
                image: Arc::new(SrgbImage::new(width, height, pixels)),
                wrap: [Wrap::Repeat; 2],
                scale: Vec2::new(2.0, 1.0),
                offset: Vec2::new(0.25, 0.0),
            }
        }
    }
}
