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
//! [`dds`] wraps the blocks in a DirectDraw Surface container (what
//! `photosolid texture -o OUT.dds` writes, [`write_dds`]), which engines and
//! texture tools load as is.
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
    use rayon::prelude::*;
    let (pw, ph) = (4 * width.div_ceil(4), 4 * height.div_ceil(4));
    // A block's bytes depend on its own 16 texels only: strips of block rows
    // are encoded in parallel (the slowest settings take about a second for
    // a 5x render of a 72 x 181 grid on one core) and joined in order.
    let strips: Vec<Vec<u8>> = (0..ph / 4)
        .collect::<Vec<_>>()
        .par_chunks(BLOCK_ROWS_PER_STRIP)
        .map(|rows| encode_rows(texels, (width, height), pw, rows))
        .collect();
    strips.concat()
}

/// Block rows encoded per parallel task (16 texel rows).
#[cfg(feature = "bc6h")]
const BLOCK_ROWS_PER_STRIP: usize = 4;

/// The blocks of the block rows `rows` (consecutive) of the surface padded
/// to `pw` texels wide, as [`encode`] lays them out.
#[cfg(feature = "bc6h")]
fn encode_rows(texels: &[f64], (width, height): (usize, usize), pw: usize, rows: &[usize]) -> Vec<u8> {
    let (Some(&first), Some(&last)) = (rows.first(), rows.last()) else {
        return Vec::new();
    };
    // RGBA16F, edge texels repeated into the padding; alpha 1 (BC6H has none).
    let one = half::f16::ONE.to_bits().to_le_bytes();
    let texel_rows = 4 * first..4 * (last + 1);
    let mut surface = Vec::with_capacity(pw * texel_rows.len() * 8);
    for y in texel_rows.clone() {
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
        height: texel_rows.len() as u32,
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

/// Bytes of the BC6H blocks of a `width` × `height` texture: 16 per 4 × 4
/// block, the sides rounded up to whole blocks (`None` on overflow).
pub fn block_bytes(width: usize, height: usize) -> Option<usize> {
    width.div_ceil(4).checked_mul(height.div_ceil(4))?.checked_mul(16)
}

/// `DXGI_FORMAT_BC6H_UF16` in the DXGI_FORMAT enumeration.
pub const DXGI_FORMAT_BC6H_UF16: u32 = 95;

/// The DirectDraw Surface (DDS) file of BC6H_UF16 `blocks` laid out as
/// [`encode`] writes them, for a `width` × `height` texture (the real size;
/// the blocks cover it rounded up to whole 4 × 4 blocks, as the format
/// requires): the magic `DDS `, the 124-byte `DDS_HEADER` (flags caps,
/// height, width, pixel format and linear size; pixel format FourCC `DX10`;
/// caps `DDSCAPS_TEXTURE`), the 20-byte `DDS_HEADER_DXT10`
/// (`DXGI_FORMAT_BC6H_UF16`, a 2D texture, one array element), then the
/// blocks. One mip level. The layout is Microsoft's "DDS" programming guide
/// (`DDS_HEADER`, `DDS_PIXELFORMAT`, `DDS_HEADER_DXT10`).
///
/// Returns `None` when a side does not fit the header's 32 bits or the
/// blocks are not exactly the ones the size needs.
pub fn dds(blocks: &[u8], width: usize, height: usize) -> Option<Vec<u8>> {
    let (w, h) = (u32::try_from(width).ok()?, u32::try_from(height).ok()?);
    let linear_size = block_bytes(width, height)?;
    if width == 0 || height == 0 || blocks.len() != linear_size {
        return None;
    }
    const DDSD_CAPS_HEIGHT_WIDTH_PIXELFORMAT_LINEARSIZE: u32 = 0x1 | 0x2 | 0x4 | 0x1000 | 0x8_0000;
    const DDPF_FOURCC: u32 = 0x4;
    const DDSCAPS_TEXTURE: u32 = 0x1000;
    const D3D10_RESOURCE_DIMENSION_TEXTURE2D: u32 = 3;
    let mut header = [0u32; 31]; // DDS_HEADER, 124 bytes
    header[0] = 124;
    header[1] = DDSD_CAPS_HEIGHT_WIDTH_PIXELFORMAT_LINEARSIZE;
    header[2] = h;
    header[3] = w;
    header[4] = u32::try_from(linear_size).ok()?;
    // header[5] depth, [6] mip count (0: one level), [7..18] reserved.
    header[18] = 32; // DDS_PIXELFORMAT.dwSize
    header[19] = DDPF_FOURCC;
    header[20] = u32::from_le_bytes(*b"DX10");
    header[26] = DDSCAPS_TEXTURE;
    let dxt10 = [DXGI_FORMAT_BC6H_UF16, D3D10_RESOURCE_DIMENSION_TEXTURE2D, 0, 1, 0];
    let mut out = Vec::with_capacity(4 + 124 + 20 + blocks.len());
    out.extend_from_slice(b"DDS ");
    for v in header.iter().chain(dxt10.iter()) {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(blocks);
    Some(out)
}

/// The BC6H_UF16 blocks and size (width, height) of a DDS file as [`dds`]
/// writes it; `None` for anything else (another format, a truncated file).
pub fn read_dds(bytes: &[u8]) -> Option<(Vec<u8>, usize, usize)> {
    let word = |k: usize| -> Option<u32> {
        let b = bytes.get(4 + 4 * k..8 + 4 * k)?;
        Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    };
    if bytes.get(..4)? != b"DDS " || word(0)? != 124 || word(20)? != u32::from_le_bytes(*b"DX10") {
        return None;
    }
    if word(31)? != DXGI_FORMAT_BC6H_UF16 {
        return None;
    }
    let (height, width) = (word(2)? as usize, word(3)? as usize);
    if width == 0 || height == 0 {
        return None;
    }
    let blocks = bytes.get(4 + 124 + 20..)?;
    (blocks.len() == block_bytes(width, height)?).then(|| (blocks.to_vec(), width, height))
}

/// How far the BC6H texels of a written texture are from the float texels,
/// as fractions of I_max (the texels are I / I_max), read back by bcdec.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockError {
    /// Largest |decoded − float| over the texels.
    pub max: f64,
    /// Root mean square of decoded − float over the texels.
    pub rms: f64,
}

/// Write `tex` (I / I_max) block-compressed to BC6H_UF16 in a DDS file
/// ([`dds`]), atomically, and say how far its decoded texels are from
/// `tex`'s. The file has no place for I_max (cd), which the caller reports
/// beside it.
///
/// # Errors
/// [`Error::Io`](crate::Error::Io) naming `path` when it cannot be written,
/// the texture is empty or too large for the header, or this build has no
/// encoder ([`available`]).
pub fn write_dds(path: &std::path::Path, tex: &super::texture::Rendered) -> Result<BlockError, crate::Error> {
    let (w, h) = (tex.mapping.width, tex.mapping.height);
    let refuse = |why: String| crate::Error::io(path, std::io::Error::new(std::io::ErrorKind::InvalidInput, why));
    if w == 0 || h == 0 || tex.data.len() != w * h {
        return Err(refuse(format!("a {w} x {h} texture with {} texels", tex.data.len())));
    }
    let (blocks, error) =
        encoded(tex).ok_or_else(|| refuse("this build has no BC6H encoder (feature `bc6h`)".into()))?;
    let bytes = dds(&blocks, w, h).ok_or_else(|| refuse(format!("a {w} x {h} texture has no DDS header")))?;
    crate::formats::write_atomic(path, &bytes)?;
    Ok(error)
}

/// The BC6H blocks of a rendered texture and their error (`None` without the encoder).
fn encoded(tex: &super::texture::Rendered) -> Option<(Vec<u8>, BlockError)> {
    #[cfg(feature = "bc6h")]
    {
        let (w, h) = (tex.mapping.width, tex.mapping.height);
        let texels: Vec<f64> = tex.data.iter().map(|&v| f64::from(v)).collect();
        let blocks = encode(&texels, w, h);
        let decoded = decode(&blocks, w, h);
        let (mut max, mut sum2) = (0.0f64, 0.0f64);
        for (&d, &t) in decoded.iter().zip(&texels) {
            // Negative texels (an unclamped render) are stored as 0: BC6H_UF16 has no sign.
            let e = (f64::from(d) - t).abs();
            max = max.max(e);
            sum2 += e * e;
        }
        let rms = (sum2 / texels.len().max(1) as f64).sqrt();
        Some((blocks, BlockError { max, rms }))
    }
    #[cfg(not(feature = "bc6h"))]
    {
        let _ = tex;
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Encoding in parallel strips of block rows gives the bytes of one
    /// encode of the whole surface: sizes with and without padding, with a
    /// last strip shorter than the others, and a single block row.
    #[cfg(feature = "bc6h")]
    #[test]
    fn strips_encode_as_the_whole_surface() {
        for (w, h) in [(37, 23), (40, 64), (9, 3), (4, 4 * BLOCK_ROWS_PER_STRIP * 3 + 4)] {
            let texels: Vec<f64> = (0..w * h)
                .map(|k| {
                    let (x, y) = ((k % w) as f64, (k / w) as f64);
                    (0.3 * x).sin().abs() * (0.2 * y).cos().abs() + 0.01 * ((k * 7919) % 13) as f64
                })
                .collect();
            let pw = 4 * w.div_ceil(4);
            let rows: Vec<usize> = (0..h.div_ceil(4)).collect();
            assert_eq!(
                encode(&texels, w, h),
                encode_rows(&texels, (w, h), pw, &rows),
                "{w} x {h}"
            );
        }
    }

    /// The container's fixed fields sit where the DDS programming guide puts
    /// them, and `read_dds` gives back what `dds` was given.
    #[test]
    fn dds_header_layout_and_round_trip() {
        let (w, h) = (6, 9); // not whole blocks: 2 x 3 blocks
        let blocks: Vec<u8> = (0..2 * 3 * 16).map(|k| (k % 251) as u8).collect();
        let file = dds(&blocks, w, h).unwrap();
        assert_eq!(file.len(), 4 + 124 + 20 + blocks.len());
        assert_eq!(&file[..4], b"DDS ");
        let word = |at: usize| u32::from_le_bytes(file[at..at + 4].try_into().unwrap());
        assert_eq!(word(4), 124); // dwSize
        assert_eq!(word(12), 9); // dwHeight
        assert_eq!(word(16), 6); // dwWidth
        assert_eq!(word(20), 96); // dwPitchOrLinearSize: the top level's bytes
        assert_eq!(word(76), 32); // ddspf.dwSize
        assert_eq!(&file[84..88], b"DX10"); // ddspf.dwFourCC
        assert_eq!(word(108), 0x1000); // dwCaps: DDSCAPS_TEXTURE
        assert_eq!(word(128), DXGI_FORMAT_BC6H_UF16);
        assert_eq!(word(132), 3); // TEXTURE2D
        assert_eq!(word(140), 1); // arraySize
        assert_eq!(read_dds(&file), Some((blocks.clone(), w, h)));
        // Wrong block counts, empty sizes, other formats and truncations are refused.
        assert_eq!(dds(&blocks[16..], w, h), None);
        assert_eq!(dds(&[], 0, 4), None);
        assert_eq!(read_dds(&file[..file.len() - 1]), None);
        assert_eq!(read_dds(&file[..100]), None);
        let mut empty = dds(&blocks, w, h).unwrap()[..148].to_vec();
        empty[16..20].copy_from_slice(&0u32.to_le_bytes()); // width 0, no blocks
        assert_eq!(read_dds(&empty), None);
        let mut bc7 = file.clone();
        bc7[128] = 98; // DXGI_FORMAT_BC7_UNORM
        assert_eq!(read_dds(&bc7), None);
    }
}
