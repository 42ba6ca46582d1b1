//! Every kind of mistake in a scene file reported at its line and column, with a message that
//! says what was expected: syntax, unknown keys and names, missing fields, wrong types, numbers out
//! of range, transforms, files, the camera, the render settings and meshes.

use crate::harness::assert_error;

#[test]
fn syntax_errors_point_at_the_unexpected_character() {
    assert_error(
        "[render]\nwidth = 640\nheight = [1, 2\n",
        3,
        15,
        "expected `]`",
    );
    assert_error("[render\n", 1, 8, "expected `]`");
}

#[test]
fn display_reads_like_a_compiler_message() {
    let error = assert_error("[[objects]]\ntype = \"sphere\"\nradius = -1\n", 3, 10, "");
    assert_eq!(
        error.to_string(),
        "test.toml:3:10: sphere radius must be a positive number, got -1\n  |\n3 | radius = -1\n  |          ^^"
    );
}

#[test]
fn unknown_keys_are_errors_listing_the_known_ones() {
    assert_error("[render]\nwidht = 3\n", 2, 1, "`width`");
    let error = assert_error(
        "[[objects]]\ntype = \"sphere\"\nradiuss = 1\n",
        3,
        1,
        "radius",
    );
    assert!(
        error.message.contains("`material` and `transform`"),
        "{error}"
    );
    assert_error("colour = [1, 1, 1]\n", 1, 1, "`materials`");
    assert_error("[materials.red]\ncolour = [1, 0, 0]\n", 2, 1, "`color`");
}

#[test]
fn missing_fields_point_at_their_table() {
    assert_error(
        "[[lights]]\ntype = \"point\"\n",
        1,
        1,
        "missing field `position`",
    );
    assert_error(
        "[render]\nwidth = 10\n\n[[objects]]\ntype = \"triangle\"\n",
        4,
        1,
        "missing field `vertices`",
    );
    assert_error(
        "[textures.wood]\ntype = \"image\"\n",
        1,
        1,
        "missing field `file`",
    );
}

#[test]
fn a_missing_or_unknown_type_says_which_kinds_exist() {
    assert_error("[[objects]]\nradius = 1\n", 1, 1, "missing field `type`");
    assert_error(
        "[[objects]]\ntype = \"cube\"\n",
        2,
        8,
        "expected one of `sphere`",
    );
    assert_error(
        "[[lights]]\ntype = \"area\"\n",
        2,
        8,
        "expected one of `point`, `directional`, `spot`",
    );
    assert_error("[textures.t]\ntype = 3\n", 2, 8, "expected a string");
}

#[test]
fn wrong_types_say_what_was_expected() {
    assert_error("[render]\nwidth = \"wide\"\n", 2, 9, "expected u32");
    assert_error("[render]\nshadows = 1\n", 2, 11, "expected a boolean");
    assert_error(
        "[[objects]]\ntype = \"sphere\"\ncenter = [0, \"up\", 0]\n",
        3,
        14,
        "expected f32",
    );
    assert_error(
        "[[objects]]\ntype = \"sphere\"\ncenter = [0, 1]\n",
        3,
        10,
        "expected 3 values, got 2",
    );
}

#[test]
fn out_of_range_numbers_point_at_the_value() {
    assert_error(
        "[[objects]]\ntype = \"sphere\"\nradius = -2.5\n",
        3,
        10,
        "positive",
    );
    assert_error("[materials.m]\nreflectivity = 1.5\n", 2, 16, "from 0 to 1");
    assert_error("[materials.m]\ncolor = [1, -1, 0]\n", 2, 9, "non-negative");
    assert_error(
        "[textures.t]\ntype = \"checker3d\"\nsize = 0\n",
        3,
        8,
        "positive",
    );
    assert_error(
        "[[lights]]\ntype = \"directional\"\ndirection = [0, 0, 0]\n",
        3,
        13,
        "not all zero",
    );
    // An element of an array is pointed at on its own.
    assert_error(
        "[[objects]]\ntype = \"mesh\"\npositions = [[0, 0, 0], [0, nan, 0]]\nfaces = []\n",
        3,
        25,
        "finite",
    );
}

#[test]
fn transform_steps_are_checked_where_they_are_written() {
    assert_error(
        "[[objects]]\ntype = \"sphere\"\ntransform = [{ translate = [1, 0, 0] }, { scale = [1, 0, 1] }]\n",
        3,
        51,
        "non-zero",
    );
    assert_error(
        "[[objects]]\ntype = \"sphere\"\ntransform = [{ rotate = { axis = [0, 0, 0], degrees = 5 } }]\n",
        3,
        34,
        "not all zero",
    );
    assert_error(
        "[[objects]]\ntype = \"plane\"\ntransform = [{ shear = [1, 0, 0] }]\n",
        3,
        16,
        "`translate`, `rotate`, `scale`",
    );
}

#[test]
fn unknown_names_list_the_names_defined() {
    assert_error(
        "[materials.red]\n[materials.blue]\n[[objects]]\ntype = \"sphere\"\nmaterial = \"green\"\n",
        5,
        12,
        "unknown material `green`; expected one of `blue`, `red`",
    );
    assert_error(
        "[materials.red]\ntexture = \"wood\"\n",
        2,
        11,
        "unknown texture `wood`; the scene defines no textures",
    );
}

#[test]
fn missing_files_point_at_the_file_name() {
    assert_error(
        "[textures.t]\ntype = \"image\"\nfile = \"no-such.png\"\n[materials.m]\ntexture = \"t\"\n",
        3,
        8,
        "cannot load texture image",
    );
    assert_error(
        "[[objects]]\ntype = \"obj\"\nfile = \"no-such.obj\"\n",
        3,
        8,
        "cannot load OBJ file",
    );
    // A file that is there but is not an image.
    assert_error(
        "[textures.t]\ntype = \"image\"\nfile = \"../models/tetra.obj\"\n\
         [materials.m]\ntexture = \"t\"\n",
        3,
        8,
        "cannot load texture image",
    );
}

#[test]
fn camera_errors_point_at_the_key_or_the_camera_table() {
    assert_error(
        "[camera]\neye = [1, 2, 3]\nlook_at = [1, 2, 3]\n",
        3,
        11,
        "coincide",
    );
    assert_error(
        "[camera]\neye = [0, 5, 0]\nup = [0, 2, 0]\n",
        3,
        6,
        "parallel",
    );
    // The default up vector is parallel: only the table can be blamed.
    assert_error("\n[camera]\neye = [0, 5, 0]\n", 2, 1, "parallel");
    assert_error("[camera]\nview_angle = 180\n", 2, 14, "view angle");
    assert_error("[camera]\nnear = 0\n", 2, 8, "near distance");
}

#[test]
fn render_settings_errors_point_at_the_key() {
    assert_error("[render]\nwidth = 0\n", 2, 9, "at least 1×1");
    assert_error("[render]\nheight = 100000\n", 2, 10, "at most");
    assert_error("[render]\nmax_depth = 0\n", 2, 13, "max_depth");
    assert_error("[render]\nmin_weight = 2\n", 2, 14, "min_weight");
    assert_error("[render]\nsamples = 0\n", 2, 11, "samples");
}

#[test]
fn block_size_must_be_a_power_of_two() {
    assert_error(
        "[render]\nblock_size = 12\n",
        2,
        14,
        "block_size must be a power of two",
    );
    assert_error("[render]\nblock_size = 128\n", 2, 14, "from 1 to 64");
}

#[test]
fn mesh_errors_point_at_the_part_at_fault() {
    let quad = "[[objects]]\ntype = \"mesh\"\npositions = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n";
    assert_error(
        &format!("{quad}faces = [[0, 1, 3]]\n"),
        4,
        9,
        "vertex 3, which does not exist",
    );
    assert_error(
        &format!("{quad}faces = [[0, 1, 2]]\nnormals = [[0, 0, 1]]\n"),
        5,
        11,
        "1 normals for 3 vertices",
    );
    assert_error(
        "[[objects]]\ntype = \"triangle\"\nvertices = [[0, 0, 0], [1, 1, 1], [2, 2, 2]]\n",
        3,
        12,
        "no area",
    );
}
