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

// The bindings, the tile constants, `fv`, `combine` (with PCHIP), `weights`,
// `gamma_pass`, `find_item` and `texel_of` are in `taps.wgsl`, prepended to this file at build time.

const GAMMA_TILE: u32 = 64u;

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
        r = gamma_pass(inp[d], inp[d + 1u], col, ge, pchip, gw);
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
    let t = texel_of(tile, lidx);
    if (t.inside) {
        let d = t.desc;
        let ce = t.ce;
        var r = 0.0;
        if (any(weights(t.ge) != vec4<f32>(0.0))) {
            let base = inp[d + 12u] + t.row * inp[d + 2u];
            let v = vec4<f32>(outp[base + inp[ce]], outp[base + inp[ce + 1u]], outp[base + inp[ce + 2u]], outp[base + inp[ce + 3u]]);
            r = combine(t.pchip, v, weights(ce));
            if (t.clamp && r < 0.0) {
                r = 0.0;
                // Rare (cubic overshoot only): counted straight into the
                // item's counter, so the pass needs no workgroup barrier.
                atomicAdd(&counts[inp[d + 11u]], 1u);
            }
        }
        outp[t.out] = r;
    }
}
