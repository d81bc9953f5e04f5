// photosolid: the render of a light distribution texture in two passes
// (separable, as the CPU's `render_row` is): a gamma pass that reconstructs,
// for every output row and every texture column, one value along gamma
// (`tmp[row][col]`), then a C pass that combines four of those per texel.
// The fused kernel (`kernel.wgsl`) instead repeats the gamma combine for
// each of a texel's four C taps: 4 x 4 + 4 reads per texel here become
// 4 (C pass) + 4 * columns / width (gamma pass, amortised).
//
// Same inputs as `kernel.wgsl` (see there for the word layout of `inp`,
// the item descriptors and the tap tables), plus:
//   header [3]      n_tiles of the gamma pass (64 entries per tile)
//   descriptor 12   tmp_off: f32 offset in `outp` of this item's gamma-pass
//                   scratch, row-major, `height` rows x `columns` entries
//   descriptor 13   first gamma-pass tile of this item (items sorted by it)
// The C pass tiles the output exactly as the fused kernel does (16 x 4).
// Between the passes wgpu's usage tracking inserts the storage barrier (two
// dispatches in one compute pass).
//
// Arithmetic: the same `combine` in the same order as the CPU, so results
// agree up to FMA contraction (`tests/gpu.rs` checks 1e-5 of I_max).

@group(0) @binding(0) var<storage, read> inp: array<u32>;
@group(0) @binding(1) var<storage, read_write> outp: array<f32>;
@group(0) @binding(2) var<storage, read_write> counts: array<atomic<u32>>;

const TILE_X: u32 = 16u;
const TILE_Y: u32 = 4u;
const GAMMA_TILE: u32 = 64u;
const HEADER: u32 = 4u;
const DESC: u32 = 16u;
const ENTRY: u32 = 8u;

fn fv(i: u32) -> f32 {
    return bitcast<f32>(inp[i]);
}

// ---- reconstruct/filter.rs, ported line by line (as in kernel.wgsl) -------

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

fn fritsch_butland(d0: f32, d1: f32, h0: f32, h1: f32) -> f32 {
    if (d0 * d1 <= 0.0) {
        return 0.0;
    }
    let two = 2.0;
    let w1 = two * h1 + h0;
    let w2 = h1 + two * h0;
    return (w1 + w2) / (w1 / d0 + w2 / d1);
}

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

fn combine(pchip: bool, v: vec4<f32>, w: vec4<f32>) -> f32 {
    if (pchip) {
        return pchip_eval(v, w);
    }
    return w.x * v.x + w.y * v.y + w.z * v.z + w.w * v.w;
}

fn weights(e: u32) -> vec4<f32> {
    return vec4<f32>(fv(e + 4u), fv(e + 5u), fv(e + 6u), fv(e + 7u));
}

// The item whose tiles (first tile in descriptor word `field`) contain `tile`.
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

// Pass 1: tmp[row][col] = combine(gamma taps of `row`, texture column `col`).
@compute @workgroup_size(64, 1, 1)
fn gamma_main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lidx: u32) {
    let tile = wg.y * inp[2] + wg.x;
    if (tile >= inp[3]) {
        return;
    }
    let d = find_item(tile, 13u);
    let columns = inp[d + 2u];
    let height = inp[d + 6u];
    let k = (tile - inp[d + 13u]) * GAMMA_TILE + lidx;
    if (k >= height * columns) {
        return;
    }
    let row = k / columns;
    let col = k % columns;
    let ge = inp[d + 3u] + row * ENTRY;
    let gw = weights(ge);
    var r = 0.0;
    if (any(gw != vec4<f32>(0.0))) {
        let pchip = (inp[d + 10u] & 2u) != 0u;
        let base = inp[d] + col * inp[d + 1u];
        let v = vec4<f32>(fv(base + inp[ge]), fv(base + inp[ge + 1u]), fv(base + inp[ge + 2u]), fv(base + inp[ge + 3u]));
        r = combine(pchip, v, gw);
    }
    outp[inp[d + 12u] + k] = r;
}

// Pass 2: out[row][col] = combine(C taps of `col`, tmp[row][.]), clamped and counted.
@compute @workgroup_size(16, 4, 1)
fn c_main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lidx: u32) {
    let n_tiles = inp[1];
    let tile = wg.y * inp[2] + wg.x;
    if (tile >= n_tiles) {
        return;
    }
    let d = find_item(tile, 9u);
    let local_tile = tile - inp[d + 9u];
    let tiles_x = inp[d + 8u];
    let col = (local_tile % tiles_x) * TILE_X + lidx % TILE_X;
    let row = (local_tile / tiles_x) * TILE_Y + lidx / TILE_X;
    let height = inp[d + 6u];
    let width = inp[d + 7u];
    let flags = inp[d + 10u];
    let clamp = (flags & 1u) != 0u;
    if (row < height && col < width) {
        let pchip = (flags & 2u) != 0u;
        let ge = inp[d + 3u] + row * ENTRY;
        let ce = inp[d + 4u] + col * ENTRY;
        var r = 0.0;
        if (any(weights(ge) != vec4<f32>(0.0))) {
            let t = inp[d + 12u] + row * inp[d + 2u];
            let v = vec4<f32>(outp[t + inp[ce]], outp[t + inp[ce + 1u]], outp[t + inp[ce + 2u]], outp[t + inp[ce + 3u]]);
            r = combine(pchip, v, weights(ce));
            if (clamp && r < 0.0) {
                r = 0.0;
                // Rare (cubic overshoot only): counted straight into the
                // item's counter, so the pass needs no workgroup barrier.
                atomicAdd(&counts[inp[d + 11u]], 1u);
            }
        }
        outp[inp[d + 5u] + row * width + col] = r;
    }
}
