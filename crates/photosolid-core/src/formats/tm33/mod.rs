//! ANSI/IES TM-33 luminaire optical data (XML): TM-33-18 (root element
//! `LuminaireOpticalData`, also ATLA S001 / UNI 11733) and TM-33-23 (root
//! element `IESTM33-22`, schema version 1.1). Reader and TM-33-23 writer.
//!
//! What is read (element names as in the published TM-33-23 examples, e.g.
//! the `crates/atla/tests/samples/tm33-23/*.xml` files of the eulumdat-rs
//! repository, and the TM-33-18 `IntensityDistribution` / `LuminousIntensity`
//! spelling of that repository's `LuminaireOpticalData` samples):
//!
//! - `Header`: `Manufacturer`, `CatalogNumber`, `Description`,
//!   `ReportNumber`, `ReportDate` (or `TestDate`, `IssueDate`);
//! - `Luminaire/Dimensions`: `Length`, `Width`, `Height` in millimetres;
//! - one `Emitter` with intensity data (a document with several is read one
//!   emitter at a time, `FILE.xml#ID`: see [`emitters`]): `Quantity`, `RatedLumens` (lm per
//!   emitter), `InputWattage` (or `InputWatts`, W), `CCT` (or `FixedCCT`, K),
//!   `ColorRendering/Ra`, and its intensity block (`LuminousData`,
//!   `LuminousIntensity` or `IntensityDistribution`) with `PhotometryType`
//!   (Type C only), `Metric` (`Luminous` only), `SymmType` (or `Symm`),
//!   `Multiplier`, `AbsolutePhotometry` and one `IntensityData horz="C"
//!   vert="γ"` element per grid point (cd before the multiplier).
//!
//! The loaded [`Luminaire`](crate::model::Luminaire) holds absolute candela
//! (values × `Multiplier`); `AbsolutePhotometry` sets
//! [`Declared::absolute`](crate::model::Declared::absolute), and when it is
//! false (or absent while `RatedLumens` is given) the lamp flux is
//! `Quantity` × `RatedLumens`. The writer always writes `Multiplier` 1 and
//! the absolute candela with Rust's shortest round-trip decimal form, so a
//! written file reads back to the same values bit for bit.
//!
//! Symmetry codes (`Symm _ None`, `Symm _ Full`, `Symm _ Bi _ 0`,
//! `Symm _ Bi _ 90`, `Symm _ Quad`, `Symm _ Arbitrary`; spaces and
//! underscores are ignored when matching) map to the model's
//! [`Symmetry`](crate::model::Symmetry): none, rotational, C0-C180,
//! C90-C270, quadrant, none. Without a code the symmetry follows from the
//! set of `horz` angles as for IES LM-63.

pub mod emitters;
mod read;
mod write;

pub use emitters::{emitter_ids, expand, split_reference};
pub use read::{read, read_emitter};
pub use write::write;

/// `UniqueIdentifier` of the `CustomData` item in which the writer keeps
/// what TM-33-23 has no element for (luminous area, declared LOR/DFF/flux,
/// lamp colour texts) and the reader restores it.
pub const DECLARATIONS_ID: &str = "urn:photosolid:declarations:v1";

/// Which TM-33 edition a document follows, from its root element.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tm33Edition {
    /// ANSI/IES TM-33-18: root element `LuminaireOpticalData`.
    Tm33_18,
    /// ANSI/IES TM-33-23: root element `IESTM33-22`.
    Tm33_23,
}

impl Tm33Edition {
    /// The root element's name.
    pub fn root(self) -> &'static str {
        match self {
            Tm33Edition::Tm33_18 => "LuminaireOpticalData",
            Tm33Edition::Tm33_23 => "IESTM33-22",
        }
    }

    /// The edition as [`Luminaire::version`](crate::model::Luminaire::version) spells it.
    pub fn version(self) -> &'static str {
        match self {
            Tm33Edition::Tm33_18 => "TM-33-18",
            Tm33Edition::Tm33_23 => "TM-33-23",
        }
    }
}

/// Whether `bytes` look like a TM-33 document: the root element (the first
/// element after the XML declaration and comments, within the first 64 KiB)
/// is `LuminaireOpticalData` or `IESTM33-22`, with or without a prefix.
pub fn looks_like(bytes: &[u8]) -> bool {
    let head = String::from_utf8_lossy(&bytes[..bytes.len().min(64 * 1024)]);
    let mut rest: &str = &head;
    while let Some(i) = rest.find('<') {
        rest = &rest[i + 1..];
        if rest.starts_with('?') || rest.starts_with('!') {
            continue;
        }
        let name: String = rest
            .chars()
            .take_while(|c| !c.is_whitespace() && *c != '>' && *c != '/')
            .collect();
        let local = name.rsplit(':').next().unwrap_or("");
        return local == Tm33Edition::Tm33_18.root() || local == Tm33Edition::Tm33_23.root();
    }
    false
}

#[cfg(test)]
mod tests;
