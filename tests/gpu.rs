//! GPU resampling against the CPU reference, on whatever adapter exists
//! (CI: Mesa lavapipe via `WGPU_BACKEND=vulkan`, llvmpipe via `WGPU_BACKEND=gl`).
//!
//! Without an adapter the tests print why and pass, unless
//! `PHOTOSOLID_REQUIRE_GPU=1`, which turns a missing adapter into a failure.
#![cfg(feature = "gpu")]

use std::sync::Once;

use photosolid::gpu::{self, resample_cpu, AxisTaps, Backend, GpuContext, ResampleJob, Resolved};

fn require_gpu() -> bool {
    std::env::var("PHOTOSOLID_REQUIRE_GPU").is_ok_and(|v| v == "1")
}

/// The process-wide context, or `None` (test skipped) when there is no adapter.
fn ctx(test: &str) -> Option<&'static GpuContext> {
    static PRINT: Once = Once::new();
    match GpuContext::global() {
        Ok(c) => {
            PRINT.call_once(|| {
                eprintln!(
                    "gpu adapter: {} (WGPU_BACKEND={}, set-up {:.0?})",
                    c.adapter(),
                    std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "unset".into()),
                    c.setup_time()
                )
            });
            Some(c)
        }
        Err(e) if require_gpu() => panic!("PHOTOSOLID_REQUIRE_GPU=1 but: {e}"),
        Err(e) => {
            eprintln!("SKIPPED {test}: {e}");
            None
        }
    }
}

/// SplitMix64: small, seedable, no dependency.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn f32(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.f32()
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// A luminous-intensity-like grid: smooth lobe plus noise, positive.
fn grid(rng: &mut Rng, rows: usize, cols: usize) -> Vec<f32> {
    let imax = rng.range(10.0, 5000.0);
    (0..rows * cols)
        .map(|i| {
            let (r, c) = ((i / cols) as f32 / rows as f32, (i % cols) as f32 / cols as f32);
            imax * (0.5 + 0.4 * (3.0 * r).cos() * (std::f32::consts::TAU * c).cos() + 0.1 * rng.f32())
        })
        .collect()
}

/// Output sample positions for `n_src` source samples upsampled `factor`x,
/// as (interval index, fraction).
fn positions(n_src: usize, n_out: usize) -> impl Iterator<Item = (usize, f32)> {
    (0..n_out).map(move |k| {
        let x = if n_out == 1 {
            0.0
        } else {
            k as f64 * (n_src - 1) as f64 / (n_out - 1) as f64
        };
        let i = (x.floor() as usize).min(n_src.saturating_sub(2));
        (i, (x - i as f64) as f32)
    })
}

/// Linear interpolation using only 2 of the 4 taps.
fn bilinear(n_src: usize, n_out: usize) -> AxisTaps {
    let (mut idx, mut w) = (vec![], vec![]);
    for (i, t) in positions(n_src, n_out) {
        let j = (i + 1).min(n_src - 1) as u32;
        idx.push([i as u32, j, i as u32, i as u32]);
        w.push([1.0 - t, t, 0.0, 0.0]);
    }
    AxisTaps::Weights { idx, w }
}

/// Catmull-Rom (negative lobes) over a source padded with one ghost sample
/// on each side: source index = data index + 1.
fn catmull_rom(n_data: usize, n_out: usize) -> AxisTaps {
    let (mut idx, mut w) = (vec![], vec![]);
    for (i, t) in positions(n_data, n_out) {
        let (t2, t3) = (t * t, t * t * t);
        w.push([
            0.5 * (-t3 + 2.0 * t2 - t),
            0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
            0.5 * (-3.0 * t3 + 4.0 * t2 + t),
            0.5 * (t3 - t2),
        ]);
        let b = i as u32; // data i-1 .. i+2 -> padded i .. i+3
        idx.push([b, b + 1, b + 2, b + 3]);
    }
    AxisTaps::Weights { idx, w }
}

/// Arbitrary random taps and weights (incl. negative), random order.
fn random_taps(rng: &mut Rng, n_src: usize, n_out: usize) -> AxisTaps {
    let idx = (0..n_out)
        .map(|_| [0; 4].map(|_: u32| rng.below(n_src) as u32))
        .collect();
    let w = (0..n_out).map(|_| [0; 4].map(|_: i32| rng.range(-0.6, 1.4))).collect();
    AxisTaps::Weights { idx, w }
}

/// PCHIP on non-uniform knots (angles); ends marked by repeated knots.
fn pchip(rng: &mut Rng, n_src: usize, n_out: usize) -> AxisTaps {
    let mut x = vec![0.0f32];
    for _ in 1..n_src {
        let last = *x.last().unwrap();
        x.push(last + rng.range(0.5, 10.0));
    }
    let (mut idx, mut knots, mut pos) = (vec![], vec![], vec![]);
    for (i, t) in positions(n_src, n_out) {
        let j = (i + 1).min(n_src - 1);
        let w = [i.saturating_sub(1), i, j, (j + 1).min(n_src - 1)];
        idx.push(w.map(|k| k as u32));
        knots.push(w.map(|k| x[k]));
        pos.push(x[i] + t * (x[j] - x[i]));
    }
    AxisTaps::Pchip { idx, knots, pos }
}

fn assert_close(gpu: &[f32], cpu: &[f32], what: &str) {
    assert_eq!(gpu.len(), cpu.len(), "{what}: length");
    let imax = cpu.iter().fold(0.0f32, |m, v| m.max(v.abs())).max(f32::MIN_POSITIVE);
    let (k, err) = gpu
        .iter()
        .zip(cpu)
        .map(|(g, c)| (g - c).abs())
        .enumerate()
        .fold((0, 0.0f32), |a, b| if b.1 > a.1 || b.1.is_nan() { b } else { a });
    assert!(
        err <= 1e-5 * imax,
        "{what}: texel {k}: gpu {} cpu {} (|err| {err:e} > 1e-5 * I_max {imax})",
        gpu[k],
        cpu[k]
    );
}

struct Case {
    name: String,
    src: Vec<f32>,
    rows: usize,
    cols: usize,
    rt: AxisTaps,
    ct: AxisTaps,
    clamp: bool,
}

impl Case {
    fn job(&self) -> ResampleJob<'_> {
        ResampleJob {
            src: &self.src,
            rows: self.rows,
            cols: self.cols,
            row_taps: &self.rt,
            col_taps: &self.ct,
            clamp_negative: self.clamp,
        }
    }
}

/// Cases of every kind; `kind` cycles through the table generators.
fn case(rng: &mut Rng, kind: usize, data_rows: usize, data_cols: usize, out_rows: usize, out_cols: usize) -> Case {
    let clamp = kind % 2 == 1;
    let (rows, cols) = (data_rows + 2, data_cols + 2);
    let src = grid(rng, rows, cols);
    let (rt, ct, name) = match kind % 5 {
        0 => (bilinear(rows, out_rows), bilinear(cols, out_cols), "bilinear"),
        1 => (
            catmull_rom(data_rows, out_rows),
            catmull_rom(data_cols, out_cols),
            "catmull-rom",
        ),
        2 => (
            random_taps(rng, rows, out_rows),
            random_taps(rng, cols, out_cols),
            "random",
        ),
        3 => (pchip(rng, rows, out_rows), pchip(rng, cols, out_cols), "pchip"),
        _ => (
            pchip(rng, rows, out_rows),
            catmull_rom(data_cols, out_cols),
            "pchip x catmull-rom",
        ),
    };
    Case {
        name: format!("{name} {rows}x{cols} -> {out_rows}x{out_cols} clamp={clamp}"),
        src,
        rows,
        cols,
        rt,
        ct,
        clamp,
    }
}

#[test]
fn adapter_is_reported() {
    let Some(c) = ctx("adapter_is_reported") else { return };
    let a = c.adapter();
    assert!(!a.name.is_empty());
    println!(
        "adapter: {a}; software: {}; max binding {} B",
        a.software,
        c.max_binding_bytes()
    );
    if let Ok(b) = std::env::var("WGPU_BACKEND") {
        let want = if b.eq_ignore_ascii_case("vulkan") || b == "vk" {
            "Vulkan"
        } else {
            "Gl"
        };
        assert_eq!(a.backend, want, "WGPU_BACKEND={b} must select that backend");
    }
}

#[test]
fn single_textures_of_all_kinds_and_sizes() {
    let Some(c) = ctx("single_textures_of_all_kinds_and_sizes") else {
        return;
    };
    let mut rng = Rng(0x5EED_0001);
    // (data rows, data cols, out rows, out cols): 1x1 up to 1805 x 905, odd sizes.
    let sizes = [
        (1, 1, 1, 1),
        (2, 2, 1, 1),
        (3, 5, 7, 3),
        (19, 25, 91, 121),
        (37, 73, 181, 365),
        (73, 181, 365, 905),
        (181, 73, 905, 365),
        (361, 181, 1805, 905),
        (13, 7, 63, 65),
        (11, 11, 17, 257),
    ];
    for (i, &(dr, dc, or, oc)) in sizes.iter().enumerate() {
        for kind in 0..5 {
            let cs = case(&mut rng, kind + i, dr.max(2), dc.max(2), or, oc);
            let job = cs.job();
            let gpu = c.render(&job).unwrap();
            assert_close(&gpu, &resample_cpu(&job), &cs.name);
        }
    }
}

#[test]
fn clamping_on_and_off() {
    let Some(c) = ctx("clamping_on_and_off") else { return };
    let mut rng = Rng(7);
    let mut cs = case(&mut rng, 2, 20, 30, 97, 151); // random taps with negative weights
    for v in cs.src.iter_mut() {
        *v -= 2500.0; // plenty of negative results
    }
    for clamp in [false, true] {
        cs.clamp = clamp;
        let job = cs.job();
        let (gpu, cpu) = (c.render(&job).unwrap(), resample_cpu(&job));
        assert_close(&gpu, &cpu, &format!("clamp={clamp}"));
        assert_eq!(gpu.iter().any(|&v| v < 0.0), !clamp);
    }
}

#[test]
fn batch_of_100_in_one_submission() {
    let Some(c) = ctx("batch_of_100_in_one_submission") else {
        return;
    };
    let mut rng = Rng(0xBA7C);
    let cases: Vec<Case> = (0..100)
        .map(|k| {
            let (dr, dc) = (2 + rng.below(72), 2 + rng.below(180));
            let f = 1 + rng.below(5);
            let (or, oc) = (dr * f + rng.below(3), dc * f + rng.below(3));
            case(&mut rng, k, dr, dc, or, oc)
        })
        .collect();
    let jobs: Vec<ResampleJob<'_>> = cases.iter().map(Case::job).collect();
    let (out, t) = c.render_batch_timed(&jobs).unwrap();
    println!("batch of 100: {t:?}");
    assert_eq!(out.len(), 100);
    for (cs, gpu) in cases.iter().zip(&out) {
        assert_close(gpu, &resample_cpu(&cs.job()), &cs.name);
    }
    // The one-submission path gives the same numbers.
    assert_eq!(c.render_batch(&jobs).unwrap(), out);
    // Split into many chunks (small binding limit): same numbers again.
    let chunked = c.render_batch_chunked(&jobs, 1 << 20).unwrap();
    assert_eq!(chunked, out);
    // Upload once, dispatch twice, read back.
    let batch = c.upload(&jobs).unwrap();
    assert!(batch.chunks() >= 1);
    c.dispatch(&batch).unwrap();
    c.dispatch(&batch).unwrap();
    assert_eq!(c.read_back(&batch).unwrap(), out);
}

#[test]
fn empty_batch_and_invalid_job() {
    let Some(c) = ctx("empty_batch_and_invalid_job") else {
        return;
    };
    assert!(c.render_batch(&[]).unwrap().is_empty());
    let src = vec![1.0f32; 4];
    let good = AxisTaps::Weights {
        idx: vec![[0, 1, 0, 0]],
        w: vec![[0.5, 0.5, 0.0, 0.0]],
    };
    let bad = AxisTaps::Weights {
        idx: vec![[0, 9, 0, 0]],
        w: vec![[0.5, 0.5, 0.0, 0.0]],
    };
    let ok = ResampleJob {
        src: &src,
        rows: 2,
        cols: 2,
        row_taps: &good,
        col_taps: &good,
        clamp_negative: false,
    };
    assert_eq!(c.render(&ok).unwrap(), vec![1.0]);
    let err = c.render_batch(&[ok, ResampleJob { col_taps: &bad, ..ok }]).unwrap_err();
    assert!(err.to_string().contains("resample job 1"), "{err}");
}

#[test]
fn backend_resolution() {
    match gpu::resolve(Backend::Cpu).unwrap() {
        Resolved::Cpu { notice } => assert!(notice.is_none()),
        Resolved::Gpu(_) => panic!("cpu resolved to gpu"),
    }
    let auto = gpu::resolve(Backend::Auto).unwrap();
    let forced = gpu::resolve(Backend::Gpu);
    match (auto, forced) {
        (Resolved::Gpu(a), Ok(Resolved::Gpu(b))) => assert!(std::ptr::eq(a, b)),
        (Resolved::Cpu { notice: Some(n) }, Err(e)) => {
            assert!(!require_gpu(), "PHOTOSOLID_REQUIRE_GPU=1 but: {e}");
            assert!(n.contains("CPU"), "{n}");
            assert!(e.to_string().contains("backends tried"), "{e}");
            eprintln!("SKIPPED gpu half of backend_resolution: {e}");
        }
        other => panic!("inconsistent resolution: {other:?}"),
    }
}
