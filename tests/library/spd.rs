//! The built-in SPD generators: at every size they make the primitives the SPD documentation
//! counts, in the places, under the camera and lights it describes; at the sizes SPD's files were
//! made, they write the same numbers as SPD's own programs; and every scene loads by name.

use std::path::Path;

use glam::DVec3;
use raylab::formats::load_any;
use raylab::formats::nff::{Item, NffDocument, NffLighting, PrimitiveCounts, parse_nff_document};
use raylab::formats::spd::{Database, load_spd, parse_scene_name};
use strum::IntoEnumIterator;

fn counts(spheres: usize, cones: usize, polygons: usize, patches: usize) -> PrimitiveCounts {
    PrimitiveCounts {
        spheres,
        cones,
        polygons,
        patches,
    }
}

/// The primitive counts SPD's documentation gives for each database at size factor `n`.
fn published_counts(database: Database, n: u32) -> PrimitiveCounts {
    let n = n as usize;
    match database {
        Database::Balls => counts((0..=n).map(|k| 9usize.pow(k as u32)).sum(), 0, 1, 0),
        Database::Gears => counts(0, 0, 146 * n.pow(3) + 1, 0),
        Database::Mount => counts(4, 0, 2 * 4usize.pow(n as u32), 0),
        Database::Rings => {
            let each = 5 * n * (n + 1) * (2 * n + 1);
            counts(each, each, 1, 0)
        }
        Database::Teapot => counts(0, 0, n * n, 64 * n * n - 8 * n),
        Database::Tetra => counts(0, 0, 4usize.pow(n as u32), 0),
        Database::Tree => {
            let each = 2usize.pow(n as u32 + 1) - 1;
            counts(each, each, 1, 0)
        }
    }
}

#[test]
fn every_size_makes_the_published_number_of_primitives() {
    for database in Database::iter() {
        let largest_checked = database.standard_size().min(6);
        for size in 1..=largest_checked {
            let document = database.generate(size).unwrap();
            assert_eq!(
                document.primitive_counts(),
                published_counts(database, size),
                "{database} size {size}"
            );
        }
    }
}

#[test]
fn the_standard_sizes_have_the_published_totals() {
    // "total prim." in the SPD readme's statistics table.
    let totals = [
        (Database::Balls, 7382),
        (Database::Gears, 9345),
        (Database::Mount, 8196),
        (Database::Rings, 8401),
        (Database::Teapot, 9264),
        (Database::Tetra, 4096),
        (Database::Tree, 8191),
    ];
    for (database, total) in totals {
        let document = database.generate(database.standard_size()).unwrap();
        assert_eq!(document.primitive_counts().total(), total, "{database}");
        assert_eq!(
            document.primitive_counts(),
            published_counts(database, database.standard_size())
        );
    }
}

/// FNV-1a, 64 bits: a fingerprint of a file's bytes.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |hash, &b| {
        (hash ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

#[test]
fn generated_files_are_spds_own_files_byte_for_byte() {
    // Length and FNV-1a hash of the files SPD 3.14's programs write (`<database> -s <size>`).
    let spd = [
        (Database::Balls, 2, 3884, 0x0a52_09d5_e8ec_4a4b),
        (Database::Balls, 4, 305_317, 0x863d_74a4_c777_c8cd),
        (Database::Gears, 2, 161_775, 0xa1c5_c034_9b5b_b361),
        (Database::Gears, 4, 1_335_003, 0x7d04_4478_1e90_80a6),
        (Database::Mount, 6, 632_253, 0x5064_e6fd_cf1c_1819),
        (Database::Rings, 7, 421_988, 0x0702_914b_a86a_b5ef),
        (Database::Teapot, 6, 360_747, 0xab98_8a06_c43c_dd58),
        (Database::Teapot, 12, 1_508_322, 0x21bc_db5a_2681_01dc),
        (Database::Tetra, 6, 255_616, 0x4041_ef6f_1654_2f4a),
        (Database::Tree, 6, 14_696, 0x22cc_28d0_4b64_5db9),
        (Database::Tree, 11, 475_128, 0xa579_f6e6_fb2d_5c8f),
    ];
    for (database, size, length, hash) in spd {
        let text = database.generate(size).unwrap().to_nff_string();
        assert_eq!(text.len(), length, "{database} {size}");
        assert_eq!(fnv1a(text.as_bytes()), hash, "{database} {size}");
    }
}

#[test]
fn small_generated_files_equal_the_spd_files_kept_with_the_tests() {
    for (database, size, file) in [
        (Database::Balls, 2, "balls-2.nff"),
        (Database::Tree, 6, "tree-6.nff"),
    ] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/nff")
            .join(file);
        let spd = std::fs::read_to_string(&path).unwrap();
        let generated = database.generate(size).unwrap().to_nff_string();
        assert_eq!(generated, spd, "{file}");
    }
}

fn view(database: Database) -> raylab::formats::nff::View {
    database.generate(1).unwrap().view.unwrap()
}

#[test]
fn cameras_and_lights_are_as_described() {
    for database in Database::iter() {
        let document = database.generate(2).unwrap();
        let view = document.view.unwrap();
        assert_eq!(
            (view.angle, view.resolution),
            (45.0, [512, 512]),
            "{database}"
        );
        assert_eq!(document.background, Some(DVec3::new(0.078, 0.361, 0.753)));
        let lights = match database {
            Database::Balls | Database::Rings => 3,
            Database::Gears => 5,
            Database::Mount | Database::Tetra => 1,
            Database::Teapot => 2,
            Database::Tree => 7,
        };
        assert_eq!(document.lights.len(), lights, "{database}");
        assert!(document.lights.iter().all(|l| l.color.is_none()));
    }
    let balls = view(Database::Balls);
    assert_eq!(
        (balls.from, balls.at, balls.up),
        (DVec3::new(2.1, 1.3, 1.7), DVec3::ZERO, DVec3::Z)
    );
    // rings looks straight down +y from the pyramid's tip, one unit in front of it.
    let rings = view(Database::Rings);
    assert_eq!(rings.at - rings.from, DVec3::Y);
    assert!((rings.from.y + 1.0 / (std::f64::consts::PI / 8.0).sin()).abs() < 1e-12);
    let tetra = view(Database::Tetra);
    assert!(
        tetra.up.dot(tetra.at - tetra.from).abs() > 0.1,
        "up is not perpendicular"
    );
}

/// Bounds of every point of every object in `document`, skipping the first `skip` objects.
fn bounds(document: &NffDocument, skip: usize) -> (DVec3, DVec3) {
    let mut lo = DVec3::INFINITY;
    let mut hi = DVec3::NEG_INFINITY;
    let mut grow = |p: DVec3, r: f64| {
        lo = lo.min(p - r);
        hi = hi.max(p + r);
    };
    let objects = document
        .items
        .iter()
        .filter(|i| !matches!(i, Item::Fill(_)))
        .skip(skip);
    for item in objects {
        match item {
            Item::Sphere { center, radius } => grow(*center, *radius),
            Item::Cone {
                base,
                base_radius,
                apex,
                apex_radius,
            } => {
                grow(*base, *base_radius);
                grow(*apex, *apex_radius);
            }
            Item::Polygon(vertices) => vertices.iter().for_each(|&v| grow(v, 0.0)),
            Item::Patch(vertices) => vertices.iter().for_each(|v| grow(v.position, 0.0)),
            Item::Fill(_) => {}
        }
    }
    (lo, hi)
}

fn inside(bounds: (DVec3, DVec3), lo: [f64; 3], hi: [f64; 3]) -> bool {
    let eps = 1e-9;
    bounds.0.cmpge(DVec3::from_array(lo) - eps).all()
        && bounds.1.cmple(DVec3::from_array(hi) + eps).all()
}

#[test]
fn the_objects_stand_where_the_descriptions_put_them() {
    for size in 1..=4 {
        // balls: the flake fits in the unit sphere about the origin, above the floor at -0.5.
        let balls = Database::Balls.generate(size).unwrap();
        assert!(balls.items.iter().all(|i| match i {
            Item::Sphere { center, radius } => center.length() + radius <= 1.0 + 1e-9,
            _ => true,
        }));
        assert_eq!(bounds(&balls, 0).0.z, -0.5);
        // gears: in the cube from (-1, -1, 0) to (1, 1, 1), on the 4×4 floor.
        let gears = Database::Gears.generate(size).unwrap();
        assert!(
            inside(bounds(&gears, 1), [-1.0, -1.0, 0.0], [1.0, 1.0, 1.0]),
            "gears {size}"
        );
        assert!(inside(
            bounds(&gears, 0),
            [-2.0, -2.0, 0.0],
            [2.0, 2.0, 1.0]
        ));
        // mount: the mountain over the square from (-1, -1) to (1, 1).
        let mount = Database::Mount.generate(size).unwrap();
        let (lo, hi) = bounds(&mount, 4);
        assert_eq!((lo.x, lo.y, hi.x, hi.y), (-1.0, -1.0, 1.0, 1.0));
        // tetra: in the cube from (-1, -1, -1) to (1, 1, 1), touching its corners.
        let tetra = Database::Tetra.generate(size).unwrap();
        assert_eq!(bounds(&tetra, 0), (DVec3::splat(-1.0), DVec3::ONE));
        // tree: everything above the field, the trunk standing on the origin.
        let tree = Database::Tree.generate(size).unwrap();
        assert!(bounds(&tree, 1).0.z >= -0.15 - 1e-9);
        assert!(
            matches!(tree.items[3], Item::Cone { base, apex, .. } if base == DVec3::ZERO && apex == DVec3::Z)
        );
        // teapot: on the 8×8 board at z = 0, no higher than its lid's knob.
        let teapot = Database::Teapot.generate(size).unwrap();
        assert!(inside(
            bounds(&teapot, 0),
            [-4.0, -4.0, 0.0],
            [4.0, 4.0, 3.15]
        ));
        // rings: each layer one spread further from the eye, its objects (about a unit across,
        // plus the rings' thickness) two apart; the wall behind the last.
        let rings = Database::Rings.generate(size).unwrap();
        let spread = 1.0 / (std::f64::consts::PI / 8.0).sin();
        let (n, out) = (f64::from(size), 1.0 + 0.07412);
        assert!(inside(
            bounds(&rings, 1),
            [-(n - 1.0) - out, spread - out, -(n - 1.0) - out],
            [n - 1.0 + out, spread * n + out, n - 1.0 + out]
        ));
        assert!(
            matches!(&rings.items[1], Item::Polygon(wall) if wall.iter().all(|v| v.y == spread * (n + 1.0)))
        );
    }
}

#[test]
fn sizes_out_of_range_are_errors() {
    for database in Database::iter() {
        assert!(database.generate(0).unwrap_err().contains("from 1 to"));
        let too_big = database.max_size() + 1;
        assert!(database.generate(too_big).is_err(), "{database}");
    }
}

#[test]
fn scene_names_give_the_database_and_size() {
    assert_eq!(parse_scene_name("spd:balls:4"), Ok((Database::Balls, 4)));
    assert_eq!(parse_scene_name("spd:teapot"), Ok((Database::Teapot, 12)));
    let error = parse_scene_name("spd:ball").unwrap_err();
    assert!(
        error.contains("balls, gears, mount, rings, teapot, tetra, tree"),
        "{error}"
    );
    assert!(
        parse_scene_name("spd:tree:x")
            .unwrap_err()
            .contains("whole number")
    );
    assert!(parse_scene_name("tree").is_err());
}

#[test]
fn every_database_loads_by_name() {
    for database in Database::iter() {
        let name = format!("spd:{database}:2");
        let scene = load_any(&name).unwrap_or_else(|e| panic!("{e}"));
        let document = database.generate(2).unwrap();
        let counts = document.primitive_counts();
        let triangles = scene.geometry.triangle_count();
        assert_eq!(
            scene.geometry.objects.len() + triangles,
            counts.spheres + counts.cones + counts.polygons + counts.patches,
            "{name}"
        );
        assert_eq!((scene.settings.width, scene.settings.height), (512, 512));
    }
}

#[test]
fn bad_scene_names_are_errors_naming_them() {
    let error = load_spd("spd:balls:99", NffLighting::Readme).unwrap_err();
    assert_eq!(error.file, Path::new("spd:balls:99"));
    assert!(error.message.contains("from 1 to 6"), "{error}");
    assert!(load_any("spd:nothing").is_err());
}

#[test]
fn generated_text_reads_back_as_the_same_document() {
    for database in Database::iter() {
        let document = database.generate(2).unwrap();
        let text = document.to_nff_string();
        let back = parse_nff_document(&text, Path::new("gen.nff")).unwrap();
        assert_eq!(back.primitive_counts(), document.primitive_counts());
        assert_eq!(back.to_nff_string(), text, "{database}");
    }
}
