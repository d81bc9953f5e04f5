// photosolid: the part the two render shaders share (`kernel.wgsl`, the
// fused kernel, and `separable.wgsl`, the two passes). `src/gpu/context.rs`
// puts this file in front of each of them before compiling, so the filter
// taps are written once. The word layout of `inp` is described in
// `kernel.wgsl`.

@group(0) @binding(0) var<storage, read> inp: array<u32>;
@group(0) @binding(1) var<storage, read_write> outp: array<f32>;
@group(0) @binding(2) var<storage, read_write> counts: array<atomic<u32>>;

const TILE_X: u32 = 16u;
const TILE_Y: u32 = 4u;
const HEADER: u32 = 4u;
const DESC: u32 = 16u;
const ENTRY: u32 = 8u;

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

// ---- tap tables and items -------------------------------------------------

// The four weights of tap-table entry `e` (word offset).
fn weights(e: u32) -> vec4<f32> {
    return vec4<f32>(fv(e + 4u), fv(e + 5u), fv(e + 6u), fv(e + 7u));
}

// The gamma pass in texture column `col`: `tmp[col]` of `render_row`
// (padded texture at word `tex_off`, `rows` words per column, gamma entry `ge`).
fn gamma_pass(tex_off: u32, rows: u32, col: u32, ge: u32, pchip: bool, gw: vec4<f32>) -> f32 {
    let base = tex_off + col * rows;
    let v = vec4<f32>(fv(base + inp[ge]), fv(base + inp[ge + 1u]), fv(base + inp[ge + 2u]), fv(base + inp[ge + 3u]));
    return combine(pchip, v, gw);
}

// The item whose tiles (first tile in descriptor word `field`) contain `tile`:
// the word offset of its descriptor. Items are sorted by that word, and every
// tile lies in one item, so the result is uniform per workgroup.
fn find_item(tile: u32, field: u32) -> u32 {
    var lo = 0u;
    var hi = inp[0];
    loop {
        if (hi - lo <= 1u) {
            break;
        }
        let mid = (lo + hi) / 2u;
        if (inp[HEADER + mid * DESC + field] <= tile) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return HEADER + lo * DESC;
}

// The texel that invocation `lidx` of output tile `tile` renders (16 x 4
// tiles, items sorted by their first tile in descriptor word 9): the item's
// descriptor offset, the row (gamma) and column (C), the item's width,
// whether the texel lies inside the item's image (its last tiles overhang),
// the item's flags (bit0 clamp, bit1 PCHIP), the offsets of the row's gamma
// and the column's C tap entries, and the texel's index in the output.
struct Texel {
    desc: u32,
    row: u32,
    col: u32,
    width: u32,
    inside: bool,
    clamp: bool,
    pchip: bool,
    ge: u32,
    ce: u32,
    out: u32,
}

fn texel_of(tile: u32, lidx: u32) -> Texel {
    let d = find_item(tile, 9u);
    let local_tile = tile - inp[d + 9u];
    let tiles_x = inp[d + 8u];
    let row = (local_tile / tiles_x) * TILE_Y + lidx / TILE_X;
    let col = (local_tile % tiles_x) * TILE_X + lidx % TILE_X;
    let width = inp[d + 7u];
    let flags = inp[d + 10u];
    let inside = row < inp[d + 6u] && col < width;
    let ge = inp[d + 3u] + row * ENTRY;
    let ce = inp[d + 4u] + col * ENTRY;
    return Texel(d, row, col, width, inside, (flags & 1u) != 0u, (flags & 2u) != 0u, ge, ce, inp[d + 5u] + row * width + col);
}
