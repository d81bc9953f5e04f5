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
// (`Symmetry::fold`) and the columns mirror at the sector's edges (as
// MIRROR_REPEAT would); a whole circle's columns repeat (REPEAT); rows clamp
// (CLAMP_TO_EDGE), as the CPU lookup does. These address modes are applied
// here, not by the sampler (`texel_fetch`): a BC6H texture is padded to whole
// 4 x 4 blocks, so the device texture can be larger than the stored texels,
// and the sampler's own wrap would read the padding.
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
    // The device texture's size, texels: height x columns padded to whole
    // 4 x 4 blocks for BC6H, else the same.
    texture_width: f32,
    texture_height: f32,
    _pad0: u32,
    _pad1: u32,
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

// Three (texel-space coordinate, weight) pairs along one axis at position x
// (texel k centred at x = k): outer texels exact, middle merged. The
// coordinates are those of `texel_fetch` (texel k centred at k + 1/2).
fn axis3(x: f32, c: ptr<function, vec3<f32>>, w: ptr<function, vec3<f32>>) {
    let x0 = floor(x);
    let k = catmull_rom(x - x0);
    let w12 = k.y + k.z;
    *c = vec3<f32>(x0 - 0.5, x0 + k.z / w12 + 0.5, x0 + 2.5);
    *w = vec3<f32>(k.x, w12, k.w);
}

// Stored column j (any integer) addressed into 0 .. columns - 1: repeated
// over a whole circle, mirrored at a sector's edges (edge texel repeated).
fn column(j: f32) -> f32 {
    let n = params.columns;
    if (params.fold == 0u) {
        return j - n * floor(j / n);
    }
    let m = j - 2.0 * n * floor(j / (2.0 * n));
    return select(m, 2.0 * n - 1.0 - m, m >= n);
}

// The stored texels read at texel-space (x, y) (texel (j, i) centred at
// (j + 1/2, i + 1/2)) with the header's address modes. Rows clamp exactly:
// at the clamped coordinate the row beyond the edge has weight 0. Columns:
// one hardware fetch when the pair it blends lies inside the stored
// columns; at an edge (the 0/360 seam, a sector's mirror) two fetches at
// the pair's column centres, blended here with the same fraction.
fn texel_fetch(x: f32, y: f32) -> f32 {
    let yc = clamp(y, 0.5, params.height - 0.5);
    if (params.mode == 0u) {
        // Nearest: the texel containing (x, y), read at its centre.
        return fetch((column(floor(x)) + 0.5) / params.texture_width, (floor(yc) + 0.5) / params.texture_height);
    }
    let v = yc / params.texture_height;
    let j0 = floor(x - 0.5);
    if (j0 >= 0.0 && j0 + 1.0 <= params.columns - 1.0) {
        return fetch(x / params.texture_width, v);
    }
    let a = fetch((column(j0) + 0.5) / params.texture_width, v);
    let b = fetch((column(j0 + 1.0) + 0.5) / params.texture_width, v);
    return mix(a, b, x - 0.5 - j0);
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
    // Texel-space coordinates in the stored texels.
    let x = c / 360.0 * params.full_width - params.first_column;
    let y = st.x * params.height;
    var r = 0.0;
    if (params.mode <= 1u) {
        r = texel_fetch(x, y);
    } else {
        var cu: vec3<f32>;
        var wu: vec3<f32>;
        var cv: vec3<f32>;
        var wv: vec3<f32>;
        axis3(x - 0.5, &cu, &wu);
        axis3(y - 0.5, &cv, &wv);
        for (var a = 0; a < 3; a++) {
            var row = 0.0;
            for (var b = 0; b < 3; b++) {
                row += wu[b] * texel_fetch(cu[b], cv[a]);
            }
            r += wv[a] * row;
        }
    }
    outp[k] = max(r, 0.0);
}
