//! Closed sets of command-line values as clap `ValueEnum`s, for the library
//! types that live in `photosolid::formats` (the library keeps no clap
//! dependency there). Library enums with a CLI spelling of their own derive
//! `ValueEnum` where they are defined, behind the `cli` feature
//! (`reconstruct::Backend`, `compare::Normalize`, `fit::ErrorMetric`).

use clap::ValueEnum;
use photosolid::formats::{ies::IesWriteVersion, Handedness, LampSetFlux};

/// `--handedness ccw|cw`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum HandednessArg {
    /// Counter-clockwise seen from above: C90 = +y.
    Ccw,
    /// Clockwise.
    Cw,
}

impl From<HandednessArg> for Handedness {
    fn from(h: HandednessArg) -> Self {
        match h {
            HandednessArg::Ccw => Handedness::CounterClockwise,
            HandednessArg::Cw => Handedness::Clockwise,
        }
    }
}

/// `--lamp-sets first|sum`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum LampSetsArg {
    /// cd/klm refer to the first lamp set's flux.
    First,
    /// cd/klm refer to the sum of the lamp sets' fluxes.
    Sum,
}

impl From<LampSetsArg> for LampSetFlux {
    fn from(l: LampSetsArg) -> Self {
        match l {
            LampSetsArg::First => LampSetFlux::First,
            LampSetsArg::Sum => LampSetFlux::Sum,
        }
    }
}

/// `--ies-version 2002|2019`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum IesVersionArg {
    /// IES LM-63-2002.
    #[value(name = "2002")]
    Lm63_2002,
    /// IES LM-63-2019.
    #[value(name = "2019")]
    Lm63_2019,
}

impl From<IesVersionArg> for IesWriteVersion {
    fn from(v: IesVersionArg) -> Self {
        match v {
            IesVersionArg::Lm63_2002 => IesWriteVersion::Lm63_2002,
            IesVersionArg::Lm63_2019 => IesWriteVersion::Lm63_2019,
        }
    }
}

/// An angle in degrees given on the command line (`--front`): any finite number, negative
/// ones included (wrapped into [0, 360) by the library).
pub fn parse_angle_deg(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!(
            "{s:?}: expected an angle in degrees, a finite number such as 90 or -90"
        )),
    }
}
