// Cut-outs: the twin of `Tracer::cut_away` in src/whitted/cut_outs.rs. Where a material has an
// `alpha_cutoff` above its texture's alpha, its surface is not there: the ray tree's loop
// searches past a closest hit there (trace.wgsl), and a shadow ray passes it as clear air
// (`tint`).

// `Tracer::cut_away`: whether `hit`, along the ray from `origin` along `dir`, falls where its
// surface is cut away.
fn cut_away(origin: vec3<f32>, dir: vec3<f32>, hit: Hit) -> bool {
    if (frame.flags & CUT_OUTS) == 0u {
        return false;
    }
    let m = materials[material_of(hit)];
    if m.alpha_cutoff == 0.0 {
        return false;
    }
    return cut_away_uv(m, hit_uv(origin, dir, hit));
}

// Whether the surface of material `m` is cut away at texture coordinates `uv`: its
// `alpha_cutoff` (0: none) is above its texture's alpha there.
fn cut_away_uv(m: Material, uv: vec2<f32>) -> bool {
    var alpha = 1.0;
    if m.texture != NO_TEXTURE && (frame.flags & TEXTURES) != 0u {
        alpha = texture_alpha(m.texture, uv);
    }
    return alpha < m.alpha_cutoff;
}
