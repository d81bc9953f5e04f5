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

// The bindings, the tile constants, `fv`, `combine` (with PCHIP), `weights`,
// `gamma_pass`, `find_item` and `texel_of` are in `taps.wgsl`, prepended to this file at build time.

var<workgroup> wg_clamped: atomic<u32>;

// ---- the render -----------------------------------------------------------

@compute @workgroup_size(16, 4, 1)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lidx: u32) {
    let n_tiles = inp[1];
    let tile = wg.y * inp[2] + wg.x;
    let t = texel_of(tile, lidx);
    if (tile < n_tiles && t.inside) {
        let tex_off = inp[t.desc];
        let rows = inp[t.desc + 1u];
        let pchip = t.pchip;
        let ge = t.ge;
        let ce = t.ce;
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
            if (t.clamp && r < 0.0) {
                r = 0.0;
                atomicAdd(&wg_clamped, 1u);
            }
        }
        outp[t.out] = r;
    }
    workgroupBarrier();
    if (lidx == 0u && tile < n_tiles) {
        let n = atomicLoad(&wg_clamped);
        if (n > 0u) {
            atomicAdd(&counts[inp[t.desc + 11u]], n);
        }
    }
}
