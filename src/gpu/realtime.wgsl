// photosolid: the real-time lookup of a light distribution texture (Wallner
// 2008, sections 4-5): a stored texture (`reconstruct::StoredTexture`: a
// render of the LDT, I / I_max, whole or only its symmetry's C sector) in a
// float texture, sampled by the hardware for a batch of directions.
//
// Texture coordinates (Wallner's (2008) equations 1-3 and Listing 1, in the
// crate's frame: n0 = -z (gamma 0), r0 = +x (C0), u0 = +y (C90)):
//   s = arccos(n0 . d) / pi                                     (eq. 1)
//   phi = arccos(r0 . proj(d)), proj onto the (r0, u0) plane     (eq. 3)
//   t = phi / 2pi when u0 . d > 0, else 1 - phi / 2pi            (eq. 2)
// evaluated in the numerically stable atan2 form (the same angles; arccos
// of a dot product loses half its digits near the poles in f32):
//   s = atan2(|d x n0|, n0 . d) / pi,  t = atan2(u0 . d, r0 . d) / 2pi mod 1.
// Texel row i is centred at s = (i + 1/2) / height, column j of the full
// render at t = (j + 1/2) / full_width (`TexelMapping`).
//
// A symmetry-reduced texture stores columns first_column .. first_column +
// columns of the full render; C = 360 t is folded into the sector
// (`Symmetry::fold`) and the sampler mirrors at the sector's edges
// (MIRROR_REPEAT in u); rows clamp (CLAMP_TO_EDGE in v), as the CPU lookup does.
//
// Lookups (`params.mode`):
//   0 nearest: one fetch (the texture's sampler is then a nearest one);
//   1 linear: one fetch, hardware bilinear (its sub-texel weights are the
//     hardware's, often 8-bit fixed point);
//   2 Catmull-Rom through linear fetches (Sigg & Hadwiger 2005 adapted to an
//     interpolating kernel): per axis the four weights w0..w3 at fraction f
//     become three fetches, the outer texels at their exact centres (weights
//     w0, w3, which are <= 0) and the middle pair merged into one linear
//     fetch at offset w2 / (w1 + w2) (w1 + w2 >= 1, so the pair never
//     cancels); 3 x 3 = 9 bilinear fetches instead of 16 point fetches;
//   3 probe: dirs[k].xy are (u, v) texture coordinates, one linear fetch
//     (measures the hardware's sub-texel weight precision).
// Output: I / I_max, clamped at 0 (modes 0-2), as `StoredTexture::cd` does.

struct Params {
    n: u32,
    mode: u32,
    // 0 none, 1 rotational, 2 C0-C180, 3 C90-C270, 4 quadrant (EULUMDAT Isym)
    fold: u32,
    dispatch_x: u32,
    height: f32,
    full_width: f32,
    first_column: f32,
    columns: f32,
}

@group(0) @binding(0) var ldt: texture_2d<f32>;
// Linear, or nearest for mode 0 (GL pairs each texture with one sampler).
@group(0) @binding(1) var ldt_sampler: sampler;
@group(0) @binding(2) var<storage, read> dirs: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> outp: array<f32>;
@group(0) @binding(4) var<uniform> params: Params;

const PI: f32 = 3.14159265358979;

// Symmetry::fold, degrees in [0, 360).
fn fold_c(c: f32, sym: u32) -> f32 {
    if (sym == 1u) {
        return 0.0;
    }
    if (sym == 2u) {
        return select(c, 360.0 - c, c > 180.0);
    }
    if (sym == 3u) {
        if (c < 90.0) {
            return 180.0 - c;
        }
        return select(c, 540.0 - c, c > 270.0);
    }
    if (sym == 4u) {
        let h = select(c, 360.0 - c, c > 180.0);
        return select(h, 180.0 - h, h > 90.0);
    }
    return c;
}

// Wallner's (2008) (s, t) of direction d (luminaire frame), see the header.
fn seed_st(d: vec3<f32>) -> vec2<f32> {
    let s = atan2(length(d.xy), -d.z) / PI;
    var t = atan2(d.y, d.x) / (2.0 * PI);
    if (t < 0.0) {
        t = t + 1.0;
    }
    return vec2<f32>(s, t);
}

fn fetch(u: f32, v: f32) -> f32 {
    return textureSampleLevel(ldt, ldt_sampler, vec2<f32>(u, v), 0.0).r;
}

// Catmull-Rom weights of the texels at -1, 0, 1, 2 around fraction f.
fn catmull_rom(f: f32) -> vec4<f32> {
    let f2 = f * f;
    let f3 = f2 * f;
    return vec4<f32>(
        -0.5 * f3 + f2 - 0.5 * f,
        1.5 * f3 - 2.5 * f2 + 1.0,
        -1.5 * f3 + 2.0 * f2 + 0.5 * f,
        0.5 * f3 - 0.5 * f2,
    );
}

// Three (coordinate, weight) pairs along one axis of n texels at texel-space
// position x (texel k centred at x = k): outer texels exact, middle merged.
fn axis3(x: f32, n: f32, c: ptr<function, vec3<f32>>, w: ptr<function, vec3<f32>>) {
    let x0 = floor(x);
    let k = catmull_rom(x - x0);
    let w12 = k.y + k.z;
    *c = vec3<f32>(x0 - 0.5, x0 + k.z / w12 + 0.5, x0 + 2.5) / n;
    *w = vec3<f32>(k.x, w12, k.w);
}

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lidx: u32) {
    let k = (wg.y * params.dispatch_x + wg.x) * 64u + lidx;
    if (k >= params.n) {
        return;
    }
    let q = dirs[k];
    if (params.mode == 3u) {
        outp[k] = fetch(q.x, q.y);
        return;
    }
    if (dot(q.xyz, q.xyz) == 0.0) {
        // The zero vector (and non-finite input, zeroed on upload) emits nothing.
        outp[k] = 0.0;
        return;
    }
    let st = seed_st(q.xyz);
    let c = fold_c(st.y * 360.0, params.fold);
    // Normalised coordinates in the stored texture.
    let u = (c / 360.0 * params.full_width - params.first_column) / params.columns;
    let v = st.x;
    var r = 0.0;
    if (params.mode <= 1u) {
        r = fetch(u, v);
    } else {
        var cu: vec3<f32>;
        var wu: vec3<f32>;
        var cv: vec3<f32>;
        var wv: vec3<f32>;
        axis3(u * params.columns - 0.5, params.columns, &cu, &wu);
        axis3(v * params.height - 0.5, params.height, &cv, &wv);
        for (var a = 0; a < 3; a++) {
            var row = 0.0;
            for (var b = 0; b < 3; b++) {
                row += wu[b] * fetch(cu[b], cv[a]);
            }
            r += wv[a] * row;
        }
    }
    outp[k] = max(r, 0.0);
}
