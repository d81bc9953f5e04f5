//! Perceptual colour maps for per-vertex colours.

/// A perceptually uniform colour map from [0, 1] to sRGB.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ColorMap {
    /// matplotlib's viridis (dark blue-violet at 0, yellow at 1): perceptually
    /// uniform and readable by colour-blind viewers. Evaluated through Matt
    /// Zucker's degree-6 polynomial fit (CC0, shadertoy WlfXRN), within about
    /// 1/255 of the matplotlib table.
    #[default]
    Viridis,
}

/// Degree-6 fit of viridis per channel, Horner order c0 + t (c1 + t (c2 + ...)).
const VIRIDIS: [[f64; 3]; 7] = [
    [
        0.277_727_327_223_417_7,
        0.005_407_344_544_966_578,
        0.334_099_805_335_306_1,
    ],
    [0.105_093_043_108_577_4, 1.404_613_529_898_575, 1.384_590_162_594_685],
    [
        -0.330_861_828_725_556_3,
        0.214_847_559_468_213,
        0.095_095_163_028_236_59,
    ],
    [-4.634_230_498_983_486, -5.799_100_973_351_585, -19.332_440_956_279_87],
    [6.228_269_936_347_081, 14.179_933_366_805_09, 56.690_552_600_681_05],
    [4.776_384_997_670_288, -13.745_145_377_746_01, -65.353_032_633_372_34],
    [-5.435_455_855_934_631, 4.645_852_612_178_535, 26.312_435_249_583_2],
];

impl ColorMap {
    /// Colour at `t` (clamped to [0, 1]; NaN maps to 0), channels in [0, 1].
    pub fn rgb(self, t: f64) -> [f64; 3] {
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        match self {
            ColorMap::Viridis => {
                let mut out = [0.0; 3];
                for (ch, o) in out.iter_mut().enumerate() {
                    let mut acc = VIRIDIS[6][ch];
                    for k in (0..6).rev() {
                        acc = acc * t + VIRIDIS[k][ch];
                    }
                    *o = acc.clamp(0.0, 1.0);
                }
                out
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
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Anchors from matplotlib's `_viridis_data` (entries 0, 128, 255).
    #[test]
    fn viridis_matches_matplotlib_anchors() {
        let anchors = [
            (0.0, [0.267004, 0.004874, 0.329415]),
            (128.0 / 255.0, [0.127568, 0.566949, 0.550556]),
            (1.0, [0.993248, 0.906157, 0.143936]),
        ];
        for (t, want) in anchors {
            let got = ColorMap::Viridis.rgb(t);
            for ch in 0..3 {
                assert!((got[ch] - want[ch]).abs() < 0.015, "t = {t}: {got:?} vs {want:?}");
            }
        }
        assert_eq!(ColorMap::Viridis.rgb8(f64::NAN), ColorMap::Viridis.rgb8(0.0));
    }
}
