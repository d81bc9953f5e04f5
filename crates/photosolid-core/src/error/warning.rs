//! Warnings: recoverable oddities of a file or a calculation, each with a
//! stable [`WarningCode`] (docs/warnings.md lists them).

use std::fmt;

use serde::Serialize;

/// The stable code of a [`Warning`], serialised as its kebab-case string
/// (`extra-values`, `lor-mismatch`, ...), the codes files and tools rely on.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum WarningCode {
    /// `angles-repaired`.
    AnglesRepaired,
    /// `blank-number`.
    BlankNumber,
    /// `c360-plane`.
    C360Plane,
    /// `cfli`.
    Cfli,
    /// `dc-mismatch`.
    DcMismatch,
    /// `dff-mismatch`.
    DffMismatch,
    /// `dg-mismatch`.
    DgMismatch,
    /// `extra-values`.
    ExtraValues,
    /// `flux-above-lamp`: a declared luminaire flux above the lamp flux (declared separately).
    FluxAboveLamp,
    /// `flux-mismatch`.
    FluxMismatch,
    /// `header-junk`.
    HeaderJunk,
    /// `invalid-ballast-factor`.
    InvalidBallastFactor,
    /// `invalid-blpf`.
    InvalidBlpf,
    /// `invalid-lumens`.
    InvalidLumens,
    /// `ityp`.
    Ityp,
    /// `lamp-set-layout`.
    LampSetLayout,
    /// `lor-above-100`: a declared or computed light output ratio above 100.5 % (relative photometry).
    #[serde(rename = "lor-above-100")]
    LorAbove100,
    /// `lor-mismatch`.
    LorMismatch,
    /// `luminous-area-larger-than-luminaire`: the luminous area exceeds the luminaire's own dimensions.
    LuminousAreaLargerThanLuminaire,
    /// `mc-divisibility`.
    McDivisibility,
    /// `missing-ballast-line`.
    MissingBallastLine,
    /// `negative-intensity`.
    NegativeIntensity,
    /// `not-a-number`.
    NotANumber,
    /// `plane-count`.
    PlaneCount,
    /// `pole-mismatch`.
    PoleMismatch,
    /// `range-snapped`.
    RangeSnapped,
    /// `seam-mismatch`.
    SeamMismatch,
    /// `single-plane`.
    SinglePlane,
    /// `symmetry-repaired`: a declared symmetry code that the angles do not fit, read by the angles (`--repair`).
    SymmetryRepaired,
    /// `efficacy-above-limit`: luminous efficacy above 683 lm/W, the theoretical maximum.
    EfficacyAboveLimit,
    /// `beam-angle-undefined`: no beam or field angle (the peak is not downward, or the angle would pass 180°).
    BeamAngleUndefined,
    /// `front-mismatch`: the downward light leans away from the front BUG rates with.
    FrontMismatch,
    /// `front-differs`: a conversion whose target format's convention puts the front elsewhere.
    FrontDiffers,
    /// `field-not-kept`: a conversion whose target format cannot hold a field as the source has it.
    FieldNotKept,
    /// `tilt-extra-values`.
    TiltExtraValues,
    /// `tilt-file-keyword`.
    TiltFileKeyword,
    /// `unknown-version`.
    UnknownVersion,
    /// `unsorted-angles`.
    UnsortedAngles,
    /// `zero-lamp-flux`.
    ZeroLampFlux,
    /// `receiver-unlit`: a scene receiver gets no light at any of its points.
    ReceiverUnlit,
    /// `deprecated-spelling`: a scene or road value written in an old spelling (the message names the one to use).
    DeprecatedSpelling,
    /// `observer-sees-nothing`: a road observer sees no luminance on the field.
    ObserverSeesNothing,
    /// `r-table-blank-cells`: r-table look-ups read cells the CIE table leaves blank.
    RTableBlankCells,
    /// `ti-luminaires-left-out`: luminaires within 1.5° of a TI line of sight were left out of TI.
    TiLuminairesLeftOut,
    /// `street-side-mismatch`: a road luminaire's downward light leans away from its street side.
    StreetSideMismatch,
    /// `layout-limit`: an engine's layout cannot hold the file within 5 % radial max.
    LayoutLimit,
    /// `ignored-option`: an option given that has no effect on this job (the message says why).
    IgnoredOption,
}

impl WarningCode {
    /// Every code, in declaration order (the table in docs/warnings.md lists each).
    pub const ALL: [WarningCode; 47] = [
        WarningCode::AnglesRepaired,
        WarningCode::BlankNumber,
        WarningCode::C360Plane,
        WarningCode::Cfli,
        WarningCode::DcMismatch,
        WarningCode::DffMismatch,
        WarningCode::DgMismatch,
        WarningCode::ExtraValues,
        WarningCode::FluxAboveLamp,
        WarningCode::FluxMismatch,
        WarningCode::HeaderJunk,
        WarningCode::InvalidBallastFactor,
        WarningCode::InvalidBlpf,
        WarningCode::InvalidLumens,
        WarningCode::Ityp,
        WarningCode::LampSetLayout,
        WarningCode::LorAbove100,
        WarningCode::LorMismatch,
        WarningCode::LuminousAreaLargerThanLuminaire,
        WarningCode::McDivisibility,
        WarningCode::MissingBallastLine,
        WarningCode::NegativeIntensity,
        WarningCode::NotANumber,
        WarningCode::PlaneCount,
        WarningCode::PoleMismatch,
        WarningCode::RangeSnapped,
        WarningCode::SeamMismatch,
        WarningCode::SinglePlane,
        WarningCode::SymmetryRepaired,
        WarningCode::EfficacyAboveLimit,
        WarningCode::BeamAngleUndefined,
        WarningCode::FrontMismatch,
        WarningCode::FrontDiffers,
        WarningCode::FieldNotKept,
        WarningCode::TiltExtraValues,
        WarningCode::TiltFileKeyword,
        WarningCode::UnknownVersion,
        WarningCode::UnsortedAngles,
        WarningCode::ZeroLampFlux,
        WarningCode::ReceiverUnlit,
        WarningCode::DeprecatedSpelling,
        WarningCode::ObserverSeesNothing,
        WarningCode::RTableBlankCells,
        WarningCode::TiLuminairesLeftOut,
        WarningCode::StreetSideMismatch,
        WarningCode::LayoutLimit,
        WarningCode::IgnoredOption,
    ];

    /// The code as written in JSON and text (kebab-case).
    pub fn as_str(self) -> &'static str {
        match self {
            WarningCode::AnglesRepaired => "angles-repaired",
            WarningCode::BlankNumber => "blank-number",
            WarningCode::C360Plane => "c360-plane",
            WarningCode::Cfli => "cfli",
            WarningCode::DcMismatch => "dc-mismatch",
            WarningCode::DffMismatch => "dff-mismatch",
            WarningCode::DgMismatch => "dg-mismatch",
            WarningCode::ExtraValues => "extra-values",
            WarningCode::FluxAboveLamp => "flux-above-lamp",
            WarningCode::FluxMismatch => "flux-mismatch",
            WarningCode::HeaderJunk => "header-junk",
            WarningCode::InvalidBallastFactor => "invalid-ballast-factor",
            WarningCode::InvalidBlpf => "invalid-blpf",
            WarningCode::InvalidLumens => "invalid-lumens",
            WarningCode::Ityp => "ityp",
            WarningCode::LampSetLayout => "lamp-set-layout",
            WarningCode::LorAbove100 => "lor-above-100",
            WarningCode::LorMismatch => "lor-mismatch",
            WarningCode::LuminousAreaLargerThanLuminaire => "luminous-area-larger-than-luminaire",
            WarningCode::McDivisibility => "mc-divisibility",
            WarningCode::MissingBallastLine => "missing-ballast-line",
            WarningCode::NegativeIntensity => "negative-intensity",
            WarningCode::NotANumber => "not-a-number",
            WarningCode::PlaneCount => "plane-count",
            WarningCode::PoleMismatch => "pole-mismatch",
            WarningCode::RangeSnapped => "range-snapped",
            WarningCode::SeamMismatch => "seam-mismatch",
            WarningCode::SinglePlane => "single-plane",
            WarningCode::SymmetryRepaired => "symmetry-repaired",
            WarningCode::EfficacyAboveLimit => "efficacy-above-limit",
            WarningCode::BeamAngleUndefined => "beam-angle-undefined",
            WarningCode::FrontMismatch => "front-mismatch",
            WarningCode::FrontDiffers => "front-differs",
            WarningCode::FieldNotKept => "field-not-kept",
            WarningCode::TiltExtraValues => "tilt-extra-values",
            WarningCode::TiltFileKeyword => "tilt-file-keyword",
            WarningCode::UnknownVersion => "unknown-version",
            WarningCode::UnsortedAngles => "unsorted-angles",
            WarningCode::ZeroLampFlux => "zero-lamp-flux",
            WarningCode::ReceiverUnlit => "receiver-unlit",
            WarningCode::DeprecatedSpelling => "deprecated-spelling",
            WarningCode::ObserverSeesNothing => "observer-sees-nothing",
            WarningCode::RTableBlankCells => "r-table-blank-cells",
            WarningCode::TiLuminairesLeftOut => "ti-luminaires-left-out",
            WarningCode::StreetSideMismatch => "street-side-mismatch",
            WarningCode::LayoutLimit => "layout-limit",
            WarningCode::IgnoredOption => "ignored-option",
        }
    }
}

impl fmt::Display for WarningCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl PartialEq<&str> for WarningCode {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

/// A recoverable oddity found while reading or checking a file.
///
/// Serialised as `{"line": 12, "code": "nadir-mismatch", "message": "..."}`
/// (`line` is `null` when the warning concerns the whole file).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Warning {
    /// 1-based line number, when the warning has one.
    pub line: Option<usize>,
    /// Stable machine-readable code, kebab-case (e.g. `extra-values`).
    pub code: WarningCode,
    /// Human explanation with the numbers involved.
    pub message: String,
}

/// A warning as `validate --json` writes it, in the shape of an
/// [`ErrorRecord`](super::ErrorRecord): `{line, column, code, message}` (`line` and `column`
/// `null` when the warning has none; warnings carry no column today).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct WarningRecord {
    /// 1-based line in the file, when the warning has one.
    pub line: Option<usize>,
    /// 1-based column, when the warning has one.
    pub column: Option<usize>,
    /// Stable machine-readable code, kebab-case.
    pub code: WarningCode,
    /// Human explanation with the numbers involved.
    pub message: String,
}

impl From<&Warning> for WarningRecord {
    fn from(w: &Warning) -> Self {
        Self {
            line: w.line,
            column: None,
            code: w.code,
            message: w.message.clone(),
        }
    }
}

impl Warning {
    /// A warning about the file as a whole.
    pub fn new(code: WarningCode, message: impl Into<String>) -> Self {
        Self {
            line: None,
            code,
            message: message.into(),
        }
    }
    /// A warning about one line.
    pub fn at(line: usize, code: WarningCode, message: impl Into<String>) -> Self {
        Self {
            line: Some(line),
            code,
            message: message.into(),
        }
    }
}

impl fmt::Display for WarningRecord {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(l) => write!(f, "line {l}: [{}] {}", self.code, self.message),
            None => write!(f, "[{}] {}", self.code, self.message),
        }
    }
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(l) => write!(f, "line {l}: [{}] {}", self.code, self.message),
            None => write!(f, "[{}] {}", self.code, self.message),
        }
    }
}
