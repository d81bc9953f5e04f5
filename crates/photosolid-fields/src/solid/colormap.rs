//! The crate's one colour map module: perceptual colour maps from [0, 1] to
//! sRGB, used for per-vertex mesh colours and every plot
//! (`photosolid::report::plot`); and the sRGB transfer function ([`srgb_encode`],
//! the one copy: lamp colours in the reports, Godot's `*_SRGB` textures).

/// The sRGB transfer function (linear → encoded), for values in [0, 1].
pub fn srgb_encode(v: f64) -> f64 {
    let v = v.clamp(0.0, 1.0);
    if v <= 0.0031308 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

/// A colour map from [0, 1] to sRGB.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ColorMap {
    /// matplotlib's viridis (dark blue-violet at 0, yellow at 1): perceptually
    /// uniform and readable by colour-blind viewers. Every 8th entry of
    /// matplotlib's 256-entry table (and the last), linearly interpolated:
    /// exact at those entries, within 1.7/255 of the table elsewhere.
    #[default]
    Viridis,
    /// ColorBrewer's 11-class RdBu, reversed (blue at 0, near-white at 0.5,
    /// red at 1), as matplotlib's `RdBu_r`: for signed errors.
    RdBu,
}

/// (matplotlib table index 0..=255, linear sRGB-encoded colour in [0, 1]).
const VIRIDIS: [(u8, [f64; 3]); 33] = [
    (0, [0.267004, 0.004874, 0.329415]),
    (8, [0.277018, 0.050344, 0.375715]),
    (16, [0.282327, 0.094955, 0.417331]),
    (24, [0.282884, 0.135920, 0.453427]),
    (32, [0.278826, 0.175490, 0.483397]),
    (40, [0.270595, 0.214069, 0.507052]),
    (48, [0.258965, 0.251537, 0.524736]),
    (56, [0.244972, 0.287675, 0.537260]),
    (64, [0.229739, 0.322361, 0.545706]),
    (72, [0.214298, 0.355619, 0.551184]),
    (80, [0.199430, 0.387607, 0.554642]),
    (88, [0.185556, 0.418570, 0.556753]),
    (96, [0.172719, 0.448791, 0.557885]),
    (104, [0.160665, 0.478540, 0.558115]),
    (112, [0.149039, 0.508051, 0.557250]),
    (120, [0.137770, 0.537492, 0.554906]),
    (128, [0.127568, 0.566949, 0.550556]),
    (135, [0.121148, 0.592739, 0.544641]),
    (143, [0.120081, 0.622161, 0.534946]),
    (151, [0.130067, 0.651384, 0.521608]),
    (159, [0.153894, 0.680203, 0.504172]),
    (167, [0.191090, 0.708366, 0.482284]),
    (175, [0.239374, 0.735588, 0.455688]),
    (183, [0.296479, 0.761561, 0.424223]),
    (191, [0.360741, 0.785964, 0.387814]),
    (199, [0.430983, 0.808473, 0.346476]),
    (207, [0.506271, 0.828786, 0.300362]),
    (215, [0.585678, 0.846661, 0.249897]),
    (223, [0.668054, 0.861999, 0.196293]),
    (231, [0.751884, 0.874951, 0.143228]),
    (239, [0.835270, 0.886029, 0.102646]),
    (247, [0.916242, 0.896091, 0.100717]),
    (255, [0.993248, 0.906157, 0.143936]),
];

/// ColorBrewer RdBu (11 classes) from blue to red, 8-bit sRGB, evenly spaced.
const RDBU: [[u8; 3]; 11] = [
    [5, 48, 97],
    [33, 102, 172],
    [67, 147, 195],
    [146, 197, 222],
    [209, 229, 240],
    [247, 247, 247],
    [253, 219, 199],
    [244, 165, 130],
    [214, 96, 77],
    [178, 24, 43],
    [103, 0, 31],
];

impl ColorMap {
    /// Colour at `t` (clamped to [0, 1]; NaN maps to 0), channels in [0, 1].
    pub fn rgb(self, t: f64) -> [f64; 3] {
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        match self {
            ColorMap::Viridis => {
                let x = t * 255.0;
                let k = VIRIDIS
                    .windows(2)
                    .position(|w| x <= f64::from(w[1].0))
                    .unwrap_or(VIRIDIS.len() - 2);
                let ((ia, a), (ib, b)) = (VIRIDIS[k], VIRIDIS[k + 1]);
                let f = ((x - f64::from(ia)) / f64::from(ib - ia)).clamp(0.0, 1.0);
                [0, 1, 2].map(|i| a[i] + f * (b[i] - a[i]))
            }
            ColorMap::RdBu => {
                let x = t * (RDBU.len() - 1) as f64;
                let k = (x.floor() as usize).min(RDBU.len() - 2);
                let f = x - k as f64;
                let (a, b) = (RDBU[k], RDBU[k + 1]);
                [0, 1, 2].map(|i| (f64::from(a[i]) + f * (f64::from(b[i]) - f64::from(a[i]))) / 255.0)
            }
        }
    }

    /// Colour at `t` as 8-bit sRGB.
    pub fn rgb8(self, t: f64) -> [u8; 3] {
        let c = self.rgb(t);
        [0, 1, 2].map(|i| (c[i] * 255.0).round() as u8)
    }

    /// The CLI / metadata name.
    pub fn name(self) -> &'static str {
        match self {
            ColorMap::Viridis => "viridis",
            ColorMap::RdBu => "rdbu",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Entries of matplotlib's `_viridis_data` (3.x): table stops 0, 128, 255
    /// and entries 37, 100, 200 that fall between stops.
    #[test]
    fn viridis_matches_matplotlib_anchors() {
        let anchors = [
            (0.0, [0.267004, 0.004874, 0.329415], 1e-6),
            (128.0 / 255.0, [0.127568, 0.566949, 0.550556], 1e-6),
            (1.0, [0.993248, 0.906157, 0.143936], 1e-6),
            (37.0 / 255.0, [0.274128, 0.199721, 0.498911], 2.0 / 255.0),
            (100.0 / 255.0, [0.166617, 0.463708, 0.558119], 2.0 / 255.0),
            (200.0 / 255.0, [0.440137, 0.811138, 0.340967], 2.0 / 255.0),
        ];
        for (t, want, tol) in anchors {
            let got = ColorMap::Viridis.rgb(t);
            for ch in 0..3 {
                assert!((got[ch] - want[ch]).abs() < tol, "t = {t}: {got:?} vs {want:?}");
            }
        }
        assert_eq!(ColorMap::Viridis.rgb8(0.0), [68, 1, 84]);
        assert_eq!(ColorMap::Viridis.rgb8(1.0), [253, 231, 37]);
        assert_eq!(ColorMap::Viridis.rgb8(f64::NAN), ColorMap::Viridis.rgb8(0.0));
    }

    /// matplotlib's `RdBu_r` at 0, 0.3, 0.5, 0.55, 1, within 2 of 255 (matplotlib
    /// quantises the ColorBrewer stops through a 256-entry table).
    #[test]
    fn rdbu_matches_matplotlib() {
        let want = [
            (0.0, [5.0, 48.0, 97.0]),
            (0.3, [0.566474 * 255.0, 0.768704 * 255.0, 0.868512 * 255.0]),
            (0.5, [247.0, 247.0, 247.0]),
            (0.55, [0.980161 * 255.0, 0.914802 * 255.0, 0.876355 * 255.0]),
            (1.0, [103.0, 0.0, 31.0]),
        ];
        for (t, w) in want {
            let got = ColorMap::RdBu.rgb(t);
            for ch in 0..3 {
                assert!((got[ch] * 255.0 - w[ch]).abs() <= 2.0, "t = {t}: {got:?} vs {w:?}");
            }
        }
    }
}
