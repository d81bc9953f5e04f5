// photosolid: the render of a light distribution texture
// (`photosolid::reconstruct::render_planned`) on the GPU, from the same
// `RenderPlan` tap tables and the same padded texture, with the same f32
// arithmetic in the same order.
//
// One dispatch renders a whole chunk of a batch (many luminaires). All inputs
// live in ONE read-only storage buffer of u32 words (`inp`; f32 values are
// stored as their bit patterns), the texels in ONE read-write storage buffer of
// f32 (`outp`), the clamped-texel counts (one per item) in a third (`counts`).
// Three storage buffers fit every backend's limits, including the GLES 3.1
// downlevel minimum of 4 storage buffers per stage. No textures and no float
// filtering are used (the GL fallback adapter lacks float32 filtering).
//
// Word layout of `inp` (see `src/gpu/resample.rs`, `pack_chunk`):
//   [0] n_items  [1] n_tiles  [2] dispatch_x (workgroups per dispatch row)  [3] 0
//   [4 + 16*i ..] item descriptor i (16 words):
//      0 tex_off     word offset of the padded texture `LightTexture::normalized()`:
//                    column-major, value (column c, padded row r) at tex_off + c * rows + r
//      1 rows        padded rows per column (`RenderPlan::rows_per_column`)
//      2 columns     texture columns (`RenderPlan::columns`)
//      3 gamma_tab   word offset of the gamma tap table (`RenderPlan::gamma`), one entry per output row
//      4 c_tab       word offset of the C tap table (`RenderPlan::c`), one entry per output column
//      5 out_off     f32 offset of this item's output in `outp` (row-major, rows = gamma)
//      6 height      7 width
//      8 tiles_x     ceil(width / TILE_X)
//      9 tile_begin  first global tile of this item (items are sorted by it)
//     10 flags       bit0: clamp negatives to 0 (and count them), bit1: PCHIP tables
//     11 slot        index of this item's counter in `counts`
//     12..15 unused
//   Tap table entry (`AxisTaps` row k): index[k][0..4] (u32), weight[k][0..4] (f32 bits).
//
// Evaluation, exactly `render_row` (separable, gamma first, then C):
//   gamma entry all-zero weights -> 0 (outside the measured band);
//   for each C tap m = 0..3 (texture column ci[m]):
//       v[m] = combine(pchip, texture[ci[m]][gi[0..4]], gw)
//   out = combine(pchip, v, cw);  if clamp && out < 0 { out = 0; count it }
// where `combine` is `photosolid::reconstruct::combine` ported line by line
// (drivers may contract a*b+c into an FMA, which differs from the CPU by at
// most an ulp per step).

@group(0) @binding(0) var<storage, read> inp: array<u32>;
@group(0) @binding(1) var<storage, read_write> outp: array<f32>;
@group(0) @binding(2) var<storage, read_write> counts: array<atomic<u32>>;

const TILE_X: u32 = 16u;
const TILE_Y: u32 = 4u;
const HEADER: u32 = 4u;
const DESC: u32 = 16u;
const ENTRY: u32 = 8u;

var<workgroup> wg_clamped: atomic<u32>;

fn fv(i: u32) -> f32 {
    return bitcast<f32>(inp[i]);
}

// ---- reconstruct/filter.rs, ported line by line -------------------------

// hermite_basis: (h00, h10, h01, h11) at s in [0, 1].
fn hermite_basis(s: f32) -> vec4<f32> {
    let one = 1.0;
    let two = 2.0;
    let three = 3.0;
    let s2 = s * s;
    let s3 = s2 * s;
    return vec4<f32>(
        two * s3 - three * s2 + one,
        s3 - two * s2 + s,
        three * s2 - two * s3,
        s3 - s2,
    );
}

// fritsch_butland: slope at a knot between secants d0 (left, spacing h0) and
// d1 (right, spacing h1): 0 at a local extremum, else the weighted harmonic mean.
fn fritsch_butland(d0: f32, d1: f32, h0: f32, h1: f32) -> f32 {
    if (d0 * d1 <= 0.0) {
        return 0.0;
    }
    let two = 2.0;
    let w1 = two * h1 + h0;
    let w2 = h1 + two * h0;
    return (w1 + w2) / (w1 / d0 + w2 / d1);
}

// pchip_eval: w = [s, h_prev, h, h_next]; h = 0 means outside the band.
fn pchip_eval(v: vec4<f32>, w: vec4<f32>) -> f32 {
    let s = w.x;
    let h_prev = w.y;
    let h = w.z;
    let h_next = w.w;
    if (h <= 0.0) {
        return 0.0;
    }
    let d_prev = (v.y - v.x) / h_prev;
    let d = (v.z - v.y) / h;
    let d_next = (v.w - v.z) / h_next;
    let m0 = fritsch_butland(d_prev, d, h_prev, h);
    let m1 = fritsch_butland(d, d_next, h, h_next);
    let hb = hermite_basis(s);
    return hb.x * v.y + hb.y * h * m0 + hb.z * v.z + hb.w * h * m1;
}

// combine: the four linear weights, or PCHIP's [s, h_prev, h, h_next].
fn combine(pchip: bool, v: vec4<f32>, w: vec4<f32>) -> f32 {
    if (pchip) {
        return pchip_eval(v, w);
    }
    return w.x * v.x + w.y * v.y + w.z * v.z + w.w * v.w;
}

// ---- the render -----------------------------------------------------------

fn weights(e: u32) -> vec4<f32> {
    return vec4<f32>(fv(e + 4u), fv(e + 5u), fv(e + 6u), fv(e + 7u));
}

// The gamma pass in texture column `col`: `tmp[col]` of `render_row`.
fn gamma_pass(tex_off: u32, rows: u32, col: u32, ge: u32, pchip: bool, gw: vec4<f32>) -> f32 {
    let base = tex_off + col * rows;
    let v = vec4<f32>(fv(base + inp[ge]), fv(base + inp[ge + 1u]), fv(base + inp[ge + 2u]), fv(base + inp[ge + 3u]));
    return combine(pchip, v, gw);
}

@compute @workgroup_size(16, 4, 1)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lidx: u32) {
    let n_items = inp[0];
    let n_tiles = inp[1];
    let tile = wg.y * inp[2] + wg.x;
    // Every item's tiles lie in one item, so `d` is uniform per workgroup.
    var lo = 0u;
    var hi = n_items;
    loop {
        if (hi - lo <= 1u) {
            break;
        }
        let mid = (lo + hi) / 2u;
        if (inp[HEADER + mid * DESC + 9u] <= tile) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let d = HEADER + lo * DESC;
    let local_tile = tile - inp[d + 9u];
    let tiles_x = inp[d + 8u];
    let col = (local_tile % tiles_x) * TILE_X + lidx % TILE_X;
    let row = (local_tile / tiles_x) * TILE_Y + lidx / TILE_X;
    let height = inp[d + 6u];
    let width = inp[d + 7u];
    let flags = inp[d + 10u];
    let clamp = (flags & 1u) != 0u;
    if (tile < n_tiles && row < height && col < width) {
        let tex_off = inp[d];
        let rows = inp[d + 1u];
        let pchip = (flags & 2u) != 0u;
        let ge = inp[d + 3u] + row * ENTRY;
        let ce = inp[d + 4u] + col * ENTRY;
        let gw = weights(ge);
        var r = 0.0;
        if (any(gw != vec4<f32>(0.0))) {
            let v = vec4<f32>(
                gamma_pass(tex_off, rows, inp[ce], ge, pchip, gw),
                gamma_pass(tex_off, rows, inp[ce + 1u], ge, pchip, gw),
                gamma_pass(tex_off, rows, inp[ce + 2u], ge, pchip, gw),
                gamma_pass(tex_off, rows, inp[ce + 3u], ge, pchip, gw),
            );
            r = combine(pchip, v, weights(ce));
            if (clamp && r < 0.0) {
                r = 0.0;
                atomicAdd(&wg_clamped, 1u);
            }
        }
        outp[inp[d + 5u] + row * width + col] = r;
    }
    workgroupBarrier();
    if (lidx == 0u && tile < n_tiles) {
        let n = atomicLoad(&wg_clamped);
        if (n > 0u) {
            atomicAdd(&counts[inp[d + 11u]], n);
        }
    }
}
