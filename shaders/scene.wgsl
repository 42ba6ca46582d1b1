// The scene as the GPU holds it (src/gpu/scene.rs uploads it): bind group 0, shared by every
// entry point. Buffers hold plain records; the `Frame` holds the camera and the settings.

@group(0) @binding(SCENE_OBJECTS) var<storage, read> objects: array<Object>;
@group(0) @binding(SCENE_SHAPE_WORDS) var<storage, read> shape_words: array<vec4<f32>>;
@group(0) @binding(SCENE_NODES) var<storage, read> nodes: array<Node>;
@group(0) @binding(SCENE_TRIANGLES) var<storage, read> triangles: array<Triangle>;
@group(0) @binding(SCENE_REFS) var<storage, read> refs: array<u32>;
@group(0) @binding(SCENE_TRIANGLE_SHADING) var<storage, read> triangle_shading: array<TriangleShading>;
@group(0) @binding(SCENE_VERTEX_ATTRIBUTES) var<storage, read> vertex_attributes: array<VertexAttributes>;
@group(0) @binding(SCENE_MATERIALS) var<storage, read> materials: array<Material>;
@group(0) @binding(SCENE_LIGHTS) var<storage, read> lights: array<Light>;
// The scene's textures, then the background image (texture.wgsl).
@group(0) @binding(SCENE_TEXTURES) var<storage, read> textures: array<Texture>;
// The sRGB decode table (the bits of 256 floats), then every image's texels.
@group(0) @binding(SCENE_TEXELS) var<storage, read> texels: array<u32>;
@group(0) @binding(SCENE_PHOTONS) var<storage, read> photons: array<Photon>;
// A storage buffer, not a uniform one: lavapipe would compile the tracer anew for its values.
@group(0) @binding(SCENE_FRAME) var<storage, read> frame: Frame;

// The camera (`Camera`), the image, and the settings the tracer reads (`RenderSettings`).
struct Frame {
    eye: vec3<f32>,
    near: f32,
    u: vec3<f32>,
    half_height: f32,
    v: vec3<f32>,
    width: u32,
    n: vec3<f32>,
    height: u32,
    background: vec3<f32>,
    max_depth: u32,
    ambient: vec3<f32>,
    min_weight: f32,
    flags: u32,
    // The unbounded objects (planes): `unbounded` entries of `refs` from `unbounded_first`.
    unbounded_first: u32,
    unbounded: u32,
    // How many entries `nodes`, `lights` and `objects` hold (a buffer is never empty: an
    // unused one holds one record of zeros).
    node_count: u32,
    light_count: u32,
    object_count: u32,
    // Where the film lies in the image (a window of it for tiles).
    film_left: u32,
    film_top: u32,
    // The background image's texture record (NO_TEXTURE: none).
    background_image: u32,
    // `fog_steps`: the sample points of the light a medium scatters into a ray, per light.
    fog_steps: u32,
    // The fog's medium (`Fog::medium`; a density of zero: no fog) and its backdrop: the ball
    // around the scene where BALL_BACKDROP is set, else `backdrop_distance` along every ray.
    fog_albedo: f32,
    backdrop_distance: f32,
    fog_color: vec3<f32>,
    fog_density: f32,
    backdrop_center: vec3<f32>,
    backdrop_radius: f32,
    // What the pixels show (views.wgsl), and the depth view's range.
    view: u32,
    depth_near: f32,
    depth_far: f32,
    // `caustic_gather`: the photons each caustic estimate gathers.
    caustic_gather: u32,
    // The caustic photon map: the box around its photons, their number, how far an estimate
    // looks at most, and how many photons were shot.
    photons_min: vec3<f32>,
    photon_count: u32,
    photons_max: vec3<f32>,
    photon_radius: f32,
    photons_shot: f32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

// A material: the twin of `Material` in src/material.rs.
struct Material {
    color: vec3<f32>,
    ambient: f32,
    emission: vec3<f32>,
    diffuse: f32,
    specular_color: vec3<f32>,
    specular: f32,
    shininess: f32,
    reflectivity: f32,
    transparency: f32,
    ior: f32,
    fresnel: u32,
    // Its texture record (NO_TEXTURE: none).
    texture: u32,
    // The medium inside it, `Material::medium` (a density of zero: none).
    medium_density: f32,
    medium_albedo: f32,
    medium_color: vec3<f32>,
    // `Material::alpha_cutoff` (0: none).
    alpha_cutoff: f32,
    // `Material::reflection_color`: what `kr`'s reflection is tinted by.
    reflection_color: vec3<f32>,
    // Its emission texture record (NO_TEXTURE: none).
    emission_texture: u32,
}

// A light: the twin of `Light` in src/light.rs. A directional light's `direction` points
// towards it; a spot's away from it, along its cone's axis.
struct Light {
    position: vec3<f32>,
    kind: u32,
    direction: vec3<f32>,
    cos_angle: f32,
    color: vec3<f32>,
    cos_full: f32,
}

// How a mesh triangle is shaded: the indices of its corners in `vertex_attributes` (when its
// mesh has vertex normals or texture coordinates), its material, and which it has.
struct TriangleShading {
    corners: vec3<u32>,
    // The material, with `HAS_NORMALS`, `HAS_UVS` and `HAS_COLORS` set as the mesh has them.
    material: u32,
}

// A mesh vertex's normal, texture coordinates and colour.
struct VertexAttributes {
    normal: vec3<f32>,
    u: f32,
    v: f32,
    red: f32,
    green: f32,
    blue: f32,
}
