//! BC6H block compression of a stored texture ([`super::Precision::Bc6h`]):
//! what a renderer's texture unit reads from a `BC6H_UF16` texture.
//!
//! The texels (I / I_max, non-negative) are written as half floats into the
//! red, green and blue channels of an RGBA16F surface padded to whole 4 × 4
//! blocks (edge texels repeated), encoded by Intel's ISPC texture compressor
//! (`intel_tex_2`, its slowest and best settings), and decoded block by block
//! by bcdec (`bcdec_rs`), an implementation independent of the encoder. The
//! red channel is what a lookup reads. BC6H keeps per block two half-float
//! endpoints (one or two partitions) and 3- or 4-bit indices between them, so
//! its error grows with the variation inside a block, not with the value.
//!
//! Without the `bc6h` feature (no C++ runtime at hand) the spelling `+bc6h`
//! is refused, the trade table has no BC6H row, and a texture asked for in
//! BC6H through the API is stored in f16 and named so; [`available`] says which.

/// Whether textures are really block-compressed (feature `bc6h`).
pub fn available() -> bool {
    cfg!(feature = "bc6h")
}

/// `texels` (row-major, `width` × `height`, I / I_max) as stored in BC6H and
/// read back, f32.
#[cfg(feature = "bc6h")]
pub fn round_trip(texels: &[f64], width: usize, height: usize) -> Vec<f32> {
    if width == 0 || height == 0 || texels.len() != width * height {
        return texels.iter().map(|&v| v as f32).collect();
    }
    decode(&encode(texels, width, height), width, height)
}

/// The BC6H_UF16 blocks of `texels` (row-major, `width` × `height` > 0,
/// I / I_max): 16 bytes per 4 × 4 block, blocks row-major, the surface padded
/// to whole blocks with its edge texels (what a renderer uploads).
#[cfg(feature = "bc6h")]
pub fn encode(texels: &[f64], width: usize, height: usize) -> Vec<u8> {
    let (pw, ph) = (4 * width.div_ceil(4), 4 * height.div_ceil(4));
    // RGBA16F, edge texels repeated into the padding; alpha 1 (BC6H has none).
    let one = half::f16::ONE.to_bits().to_le_bytes();
    let mut surface = Vec::with_capacity(pw * ph * 8);
    for y in 0..ph {
        for x in 0..pw {
            let v = texels
                .get(y.min(height.saturating_sub(1)) * width + x.min(width.saturating_sub(1)))
                .copied()
                .unwrap_or(0.0);
            let v = if v.is_finite() { v.max(0.0) } else { 0.0 };
            let h = half::f16::from_f64(v).to_bits().to_le_bytes();
            for _ in 0..3 {
                surface.extend_from_slice(&h);
            }
            surface.extend_from_slice(&one);
        }
    }
    let rgba = intel_tex_2::RgbaSurface {
        width: pw as u32,
        height: ph as u32,
        stride: (pw * 8) as u32,
        data: &surface,
    };
    intel_tex_2::bc6h::compress_blocks(&intel_tex_2::bc6h::very_slow_settings(), &rgba)
}

/// The texels (`width` × `height`, the red channel) of BC6H_UF16 `blocks`
/// laid out as [`encode`] writes them, decoded by bcdec.
#[cfg(feature = "bc6h")]
pub fn decode(blocks: &[u8], width: usize, height: usize) -> Vec<f32> {
    let bw = width.div_ceil(4);
    let mut out = vec![0.0f32; width * height];
    let mut block = [0.0f32; 4 * 4 * 3];
    for (k, bytes) in blocks.chunks_exact(16).enumerate() {
        let (bx, by) = (4 * (k % bw.max(1)), 4 * (k / bw.max(1)));
        bcdec_rs::bc6h_float(bytes, &mut block, 4 * 3, false);
        for i in 0..4 {
            for j in 0..4 {
                let (y, x) = (by + i, bx + j);
                if y < height && x < width {
                    out[y * width + x] = block[i * 12 + j * 3];
                }
            }
        }
    }
    out
}
