//! The differences the writers' round-trip check finds ([`super::Error::RoundTrip`]).

/// A written luminaire that does not read back as it was
/// ([`crate::formats::roundtrip`]): the first difference found.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Difference {
    /// The γ angles differ.
    #[error("gamma angles {orig:?} came back as {back:?}")]
    GammaAngles {
        /// The original's γ angles, degrees.
        orig: Vec<f64>,
        /// The copy's, degrees.
        back: Vec<f64>,
    },
    /// A full-circle plane of the original is not in the copy.
    #[error("plane C = {c} is missing (planes back: {back:?})")]
    MissingPlane {
        /// The plane, degrees.
        c: f64,
        /// The copy's C angles, degrees.
        back: Vec<f64>,
    },
    /// A value differs by more than the writer's tolerance (or is not finite).
    #[error("I(C = {c}, gamma = {gamma}) = {want} cd came back as {got} cd (allowed difference {allowed:e} cd)")]
    Value {
        /// C, degrees.
        c: f64,
        /// γ, degrees.
        gamma: f64,
        /// The original value, cd.
        want: f64,
        /// The value read back, cd.
        got: f64,
        /// The allowed difference, cd.
        allowed: f64,
    },
}
