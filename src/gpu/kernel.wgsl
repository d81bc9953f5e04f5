// photosolid: tensor-product 4-tap resampling from per-axis tap tables.
//
// One dispatch renders a whole chunk of a batch (many luminaires). All inputs
// live in ONE read-only storage buffer of u32 words (`inp`; f32 values are
// stored as their bit patterns), the result in ONE read-write storage buffer of
// f32 (`outp`). Two storage buffers fit every backend's limits, including the
// GLES 3.1 downlevel minimum of 4 storage buffers per stage. No textures and no
// float filtering are used (the GL fallback adapter lacks float32 filtering).
//
// Word layout of `inp` (see `src/gpu/resample.rs`, `pack_chunk`):
//   [0] n_items  [1] n_tiles  [2] dispatch_x (workgroups per dispatch row)  [3] 0
//   [4 + 16*i ..] item descriptor i (16 words):
//      0 src_off     word offset of the source grid (rows x cols, row-major f32)
//      1 src_rows    2 src_cols
//      3 row_tab     word offset of the gamma (row) tap table
//      4 col_tab     word offset of the C (column) tap table
//      5 out_off     f32 offset of this item's output in `outp`
//      6 out_rows    7 out_cols
//      8 tiles_x     ceil(out_cols / TILE_X)
//      9 tile_begin  first global tile of this item (items are sorted by it)
//     10 flags       bit0: clamp negatives to 0, bit1: rows are PCHIP, bit2: columns are PCHIP
//     11 row_stride  words per row-table entry (8 weights mode, 12 PCHIP mode)
//     12 col_stride  words per column-table entry
//     13..15 unused
//   Tap table entry (one per output row / output column):
//      weights mode: i0 i1 i2 i3 (u32 source indices)  w0 w1 w2 w3 (f32)
//      PCHIP mode:   i0 i1 i2 i3 (u32)  x0 x1 x2 x3 (f32 knots)  pos (f32)  0 0 0
//
// Evaluation order (the CPU reference `resample_cpu` does exactly the same):
//   for each C tap j = 0..3 (column c_j):
//       v_j = interp_gamma(src[r0][c_j], src[r1][c_j], src[r2][c_j], src[r3][c_j])
//   out = interp_c(v_0, v_1, v_2, v_3);  if clamp { out = max(out, 0) }
//   weights mode: acc = w0*y0; acc = acc + w1*y1; acc = acc + w2*y2; acc = acc + w3*y3
//   (left to right in f32; drivers may contract a*b+c into an FMA, which differs
//   from the CPU by at most an ulp per step).

@group(0) @binding(0) var<storage, read> inp: array<u32>;
@group(0) @binding(1) var<storage, read_write> outp: array<f32>;

const TILE_X: u32 = 16u;
const TILE_Y: u32 = 4u;
const HEADER: u32 = 4u;
const DESC: u32 = 16u;

fn fv(i: u32) -> f32 {
    return bitcast<f32>(inp[i]);
}

fn sgn(v: f32) -> f32 {
    if (v > 0.0) {
        return 1.0;
    }
    if (v < 0.0) {
        return -1.0;
    }
    return 0.0;
}

// Fritsch-Butland slope at an interior knot (SciPy PchipInterpolator):
// hl, hr = widths of the intervals left and right of the knot, dl, dr = their
// secant slopes. m = 0 if sign(dl)*sign(dr) <= 0 (i.e. dl*dr <= 0, tested on
// signs so that underflow cannot flip it), otherwise
// m = (w1 + w2) / (w1/dl + w2/dr), w1 = 2*hr + hl, w2 = hr + 2*hl.
fn slope_interior(hl: f32, hr: f32, dl: f32, dr: f32) -> f32 {
    if (sgn(dl) * sgn(dr) <= 0.0) {
        return 0.0;
    }
    let w1 = 2.0 * hr + hl;
    let w2 = hr + 2.0 * hl;
    return (w1 + w2) / (w1 / dl + w2 / dr);
}

// SciPy's one-sided three-point end slope (`_edge_case`): h0, m0 = width and
// secant of the interval next to the end knot, h1, m1 = the next one inwards.
// d = ((2*h0 + h1)*m0 - h0*m1) / (h0 + h1); 0 if sign(d) != sign(m0);
// 3*m0 if sign(m0) != sign(m1) and |d| > 3|m0|; else d.
fn slope_edge(h0: f32, h1: f32, m0: f32, m1: f32) -> f32 {
    let d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1);
    if (sgn(d) != sgn(m0)) {
        return 0.0;
    }
    if (sgn(m0) != sgn(m1) && abs(d) > 3.0 * abs(m0)) {
        return 3.0 * m0;
    }
    return d;
}

// PCHIP on 4 taps (x0 <= x1 < x2 <= x3), evaluated at `x` (normally in [x1, x2]).
// A missing neighbour is encoded by a repeated knot: x0 == x1 (no left
// neighbour: x1 is a data end) or x3 == x2 (x2 is a data end); then SciPy's end
// formula is used; with neither neighbour the interval is linear (2-point case).
// h1 = x2 - x1, d1 = (y2 - y1)/h1; d0, d2 likewise for the outer intervals.
// Slopes: m1 = has_left ? slope_interior(h0, h1, d0, d1) : has_right ? slope_edge(h1, h2, d1, d2) : d1
//         m2 = has_right ? slope_interior(h1, h2, d1, d2) : has_left ? slope_edge(h1, h0, d1, d0) : d1
// Cubic (SciPy CubicHermiteSpline coefficients), dx = x - x1:
//   t = (m1 + m2 - 2*d1) / h1;  c3 = t / h1;  c2 = (d1 - m1) / h1 - t
//   y = y1 + dx * (m1 + dx * (c2 + dx * c3))
// If h1 <= 0 the result is y1.
fn pchip4(x0: f32, x1: f32, x2: f32, x3: f32, y0: f32, y1: f32, y2: f32, y3: f32, x: f32) -> f32 {
    let h1 = x2 - x1;
    if (!(h1 > 0.0)) {
        return y1;
    }
    let h0 = x1 - x0;
    let h2 = x3 - x2;
    let d1 = (y2 - y1) / h1;
    let has_l = h0 > 0.0;
    let has_r = h2 > 0.0;
    var d0 = 0.0;
    var d2 = 0.0;
    if (has_l) {
        d0 = (y1 - y0) / h0;
    }
    if (has_r) {
        d2 = (y3 - y2) / h2;
    }
    var m1 = d1;
    var m2 = d1;
    if (has_l) {
        m1 = slope_interior(h0, h1, d0, d1);
    } else if (has_r) {
        m1 = slope_edge(h1, h2, d1, d2);
    }
    if (has_r) {
        m2 = slope_interior(h1, h2, d1, d2);
    } else if (has_l) {
        m2 = slope_edge(h1, h0, d1, d0);
    }
    let t = (m1 + m2 - 2.0 * d1) / h1;
    let c3 = t / h1;
    let c2 = (d1 - m1) / h1 - t;
    let dx = x - x1;
    return y1 + dx * (m1 + dx * (c2 + dx * c3));
}

// Interpolate 4 tap values with table entry `e` (weights or PCHIP).
fn axis_eval(e: u32, pchip: bool, y0: f32, y1: f32, y2: f32, y3: f32) -> f32 {
    if (pchip) {
        return pchip4(fv(e + 4u), fv(e + 5u), fv(e + 6u), fv(e + 7u), y0, y1, y2, y3, fv(e + 8u));
    }
    var acc = fv(e + 4u) * y0;
    acc = acc + fv(e + 5u) * y1;
    acc = acc + fv(e + 6u) * y2;
    acc = acc + fv(e + 7u) * y3;
    return acc;
}

// Gamma interpolation within source column `c`.
fn column(src_off: u32, src_cols: u32, re: u32, row_pchip: bool, c: u32) -> f32 {
    let y0 = fv(src_off + inp[re] * src_cols + c);
    let y1 = fv(src_off + inp[re + 1u] * src_cols + c);
    let y2 = fv(src_off + inp[re + 2u] * src_cols + c);
    let y3 = fv(src_off + inp[re + 3u] * src_cols + c);
    return axis_eval(re, row_pchip, y0, y1, y2, y3);
}

@compute @workgroup_size(16, 4, 1)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_id) lid: vec3<u32>) {
    let n_items = inp[0];
    let n_tiles = inp[1];
    let tile = wg.y * inp[2] + wg.x;
    if (tile >= n_tiles) {
        return;
    }
    // Largest item whose tile_begin <= tile (binary search; uniform per workgroup).
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
    let col = (local_tile % tiles_x) * TILE_X + lid.x;
    let row = (local_tile / tiles_x) * TILE_Y + lid.y;
    let out_rows = inp[d + 6u];
    let out_cols = inp[d + 7u];
    if (row >= out_rows || col >= out_cols) {
        return;
    }
    let src_off = inp[d];
    let src_cols = inp[d + 2u];
    let flags = inp[d + 10u];
    let row_pchip = (flags & 2u) != 0u;
    let col_pchip = (flags & 4u) != 0u;
    let re = inp[d + 3u] + row * inp[d + 11u];
    let ce = inp[d + 4u] + col * inp[d + 12u];

    let v0 = column(src_off, src_cols, re, row_pchip, inp[ce]);
    let v1 = column(src_off, src_cols, re, row_pchip, inp[ce + 1u]);
    let v2 = column(src_off, src_cols, re, row_pchip, inp[ce + 2u]);
    let v3 = column(src_off, src_cols, re, row_pchip, inp[ce + 3u]);
    var r = axis_eval(ce, col_pchip, v0, v1, v2, v3);
    if ((flags & 1u) != 0u) {
        r = max(r, 0.0);
    }
    outp[inp[d + 5u] + row * out_cols + col] = r;
}
