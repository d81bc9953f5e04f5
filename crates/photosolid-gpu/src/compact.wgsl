// photosolid: the compact representations evaluated on the GPU, one thread
// per direction, in f32 as a renderer's shader evaluates them.
//
// kind 0, spherical harmonics (`reconstruct::sh::ShField::unclamped_cd`, the
// same sums in the same order): real orthonormal harmonics of degree L =
// params.count in the luminaire frame (z' = -d.z = cos gamma, no
// trigonometry: sin^m(gamma) e^{imC} = (d.x + i d.y)^m), the fully
// normalised associated Legendre functions by the three-term recurrence
// (Holmes and Featherstone 2002) with constants precomputed on the CPU.
// data = [coefficients (L+1)^2, relative to the scale, at l^2 + l + m;
//         a zonal series (params.zonal = 1) holds only its L+1 m = 0 ones, at l]
//        [recurrence (a, b) per (l, m >= 0) at l(l+1)/2 + m, from rec_at]
//        [the diagonal factors sqrt((2m+1)/2m) per m, from diag_at].
// Output: the series / scale, clamped at 0.
//
// kind 1, cosine-power lobes (`reconstruct::lobes::Lobes`): params.count
// lobes of 5 floats (axis x, y, z, exponent p, weight in cd);
// I = sum_k w_k max(0, d . a_k)^p_k, with max(0, t)^0 = 1 for t > 0;
// rings (params.zonal = 1, `Lobes::rings`): each axis turned about the
// vertical into d's C-plane, t = d.z a.z + |d.xy| |a.xy|.
// Output: cd.
//
// A zero direction (the CPU's zero or non-finite vector) gives 0.

struct Params {
    n: u32,
    kind: u32,
    count: u32,
    dispatch_x: u32,
    rec_at: u32,
    diag_at: u32,
    zonal: u32,
    pad: u32,
}

@group(0) @binding(0) var<storage, read> data: array<f32>;
@group(0) @binding(2) var<storage, read> dirs: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> outp: array<f32>;
@group(0) @binding(4) var<uniform> params: Params;

const SQRT_2: f32 = 1.41421356237310;

fn sh_eval(d: vec3<f32>) -> f32 {
    let degree = params.count;
    let x = d.x;
    let y = d.y;
    let z = -d.z;
    var sum = 0.0;
    var pmm = 1.0;
    var cr = 1.0;
    var ci = 0.0;
    // A zonal series has only the m = 0 order (its other coefficients are zero and not stored).
    let orders = select(degree, 0u, params.zonal == 1u);
    for (var m = 0u; m <= orders; m++) {
        if (m > 0u) {
            pmm *= data[params.diag_at + m];
            let ncr = cr * x - ci * y;
            ci = cr * y + ci * x;
            cr = ncr;
        }
        var p2 = 0.0;
        var p1 = pmm;
        var sc = data[select(m * m + 2u * m, 0u, params.zonal == 1u)] * p1;
        var ss = 0.0;
        if (m > 0u) {
            ss = data[m * m] * p1;
        }
        for (var l = m + 1u; l <= degree; l++) {
            let r = params.rec_at + 2u * (l * (l + 1u) / 2u + m);
            let p = data[r] * (z * p1 - data[r + 1u] * p2);
            let base = select(l * l + l, l, params.zonal == 1u);
            sc += data[base + m] * p;
            if (m > 0u) {
                ss += data[base - m] * p;
            }
            p2 = p1;
            p1 = p;
        }
        if (m == 0u) {
            sum += sc;
        } else {
            sum += SQRT_2 * (sc * cr + ss * ci);
        }
    }
    return max(sum, 0.0);
}

fn lobes_eval(d: vec3<f32>) -> f32 {
    var sum = 0.0;
    for (var k = 0u; k < params.count; k++) {
        let at = 5u * k;
        let a = vec3<f32>(data[at], data[at + 1u], data[at + 2u]);
        let ring = d.z * a.z + length(d.xy) * length(a.xy);
        let t = min(select(dot(d, a), ring, params.zonal == 1u), 1.0);
        let p = data[at + 3u];
        if (t > 0.0) {
            // pow(t, 0) is 1 for t > 0; exp2(p log2 t) underflows to 0, never NaN, for tiny t.
            sum += data[at + 4u] * select(exp2(p * log2(t)), 1.0, p == 0.0);
        }
    }
    return sum;
}

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) lidx: u32) {
    let i = (wg.y * params.dispatch_x + wg.x) * 64u + lidx;
    if (i >= params.n) {
        return;
    }
    let d = dirs[i].xyz;
    if (dot(d, d) == 0.0) {
        outp[i] = 0.0;
        return;
    }
    if (params.kind == 0u) {
        outp[i] = sh_eval(d);
    } else {
        outp[i] = lobes_eval(d);
    }
}
