//! OpenEXR output of a [`Rendered`] texture and reading it back.
//!
//! One layer, one float32 channel `Y` (I / I_max), `width` columns (C) by
//! `height` rows (γ), row 0 at γ ≈ 0. Custom header attributes (layer
//! attributes, names prefixed `photosolid.`):
//!
//! | attribute | type | meaning |
//! |---|---|---|
//! | `photosolid.source` | text | source file (UTF-8 bytes), empty when none |
//! | `photosolid.filter` | text | filter, CLI spelling |
//! | `photosolid.factor` | i32 | oversampling factor |
//! | `photosolid.i_max_cd` | f64 | I_max in cd (texel × I_max = cd) |
//! | `photosolid.gamma_range_deg` | text | `"0 180"`: γ range the rows cover |
//! | `photosolid.c_range_deg` | text | `"0 360"`: C range the columns cover |
//! | `photosolid.measured_gamma_deg` | text | measured γ band, `"from to"` |
//! | `photosolid.mapping` | text | texel centres and texture coordinates |
//! | `photosolid.handedness` | text | frame handedness |
//! | `photosolid.clamped` | i32 | texels clamped to 0 |
//!
//! Writes are atomic: the file is written next to the target under a
//! temporary name, then renamed over it.

use std::path::Path;

use exr::prelude::{
    AnyChannel, AnyChannels, AttributeValue, Encoding, FlatSamples, Image, Layer, LayerAttributes, SmallVec, Text,
    WritableImage,
};

use crate::error::{Error, ErrorKind, Location, ParseError};

use super::filter::Filter;
use super::texture::{Rendered, TexelMapping};

const CHANNEL: &str = "Y";

/// The header attributes of a texture file written by this crate.
#[derive(Debug, Clone, PartialEq)]
pub struct ExrMeta {
    /// The source file, if any.
    pub source: Option<String>,
}

/// exr's `Text` holds bytes; carry UTF-8 by mapping each byte to one char
/// (the inverse of reading the bytes back as UTF-8).
#[allow(
    clippy::expect_used,
    reason = "every char made from one byte is Latin-1, which `Text` holds"
)]
pub fn text(s: &str) -> Text {
    Text::new_or_none(s.bytes().map(char::from).collect::<String>()).expect("every byte is a Latin-1 char")
}

fn untext(t: &Text) -> String {
    String::from_utf8_lossy(t.bytes()).into_owned()
}

/// Write `tex` to `path` (atomically), recording `meta.source`.
///
/// # Errors
/// [`Error::Io`] when the file cannot be written.
pub fn write_exr(path: impl AsRef<Path>, tex: &Rendered, meta: &ExrMeta) -> Result<(), Error> {
    let path = path.as_ref();
    let (w, h) = (tex.mapping.width, tex.mapping.height);
    let mut attrs = LayerAttributes::named("photosolid-ldt");
    let mut put = |k: &str, v: AttributeValue| {
        attrs.other.insert(Text::from(k), v);
    };
    put(
        "photosolid.source",
        AttributeValue::Text(text(meta.source.as_deref().unwrap_or(""))),
    );
    put("photosolid.filter", AttributeValue::Text(text(&tex.filter.to_string())));
    put("photosolid.factor", AttributeValue::I32(tex.factor as i32));
    put("photosolid.i_max_cd", AttributeValue::F64(tex.i_max_cd));
    put("photosolid.gamma_range_deg", AttributeValue::Text(text("0 180")));
    put("photosolid.c_range_deg", AttributeValue::Text(text("0 360")));
    put(
        "photosolid.measured_gamma_deg",
        AttributeValue::Text(text(&format!("{} {}", tex.measured_gamma.0, tex.measured_gamma.1))),
    );
    put(
        "photosolid.mapping",
        AttributeValue::Text(text(TexelMapping::DESCRIPTION)),
    );
    put(
        "photosolid.handedness",
        AttributeValue::Text(text(TexelMapping::HANDEDNESS)),
    );
    put(
        "photosolid.clamped",
        AttributeValue::I32(tex.clamped.min(i32::MAX as usize) as i32),
    );
    write_layer(path, (w, h), attrs, CHANNEL, FlatSamples::F32(tex.data.clone()))
}

/// Write one layer with one channel (`samples`, row-major, `size` = (width,
/// height)) and the layer attributes `attrs` to `path`, atomically (a
/// temporary file next to it, renamed over it). The one EXR writer of the
/// crate: light textures and the engines' layouts (`photosolid::engines`) go through it.
///
/// # Errors
/// [`Error::Io`] when the file cannot be written, [`Error::Encode`] when the
/// encoder fails, [`crate::ModelError::Parameter`] for a sample count that is not width × height.
pub fn write_layer(
    path: &Path,
    size: (usize, usize),
    attrs: LayerAttributes,
    channel: &str,
    samples: FlatSamples,
) -> Result<(), Error> {
    write_layer_channels(path, size, attrs, vec![(channel, samples)])
}

/// [`write_layer`] with several channels (e.g. `R`, `G`, `B` for a renderer that reads colour).
///
/// # Errors
/// As [`write_layer`]; every channel must hold width × height samples.
pub fn write_layer_channels(
    path: &Path,
    size: (usize, usize),
    attrs: LayerAttributes,
    channels: Vec<(&str, FlatSamples)>,
) -> Result<(), Error> {
    let mut list = Vec::with_capacity(channels.len());
    for (name, samples) in channels {
        if samples.len() != size.0 * size.1 {
            return Err(crate::error::ModelError::Parameter {
                name: "samples",
                value: format!("{}: {} samples in channel {name}", path.display(), samples.len()),
                reason: format!("a {} x {} image needs {}", size.0, size.1, size.0 * size.1),
            }
            .into());
        }
        list.push(AnyChannel::new(name, samples));
    }
    let layer = Layer::new(
        size,
        attrs,
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(SmallVec::from_vec(list)),
    );
    let image = Image::from_layer(layer);

    // An encoder error travels through the writer as an I/O error and comes
    // back out as what it is.
    let mut encode_error = None;
    let written = crate::formats::write_atomic_with(path, |f| {
        image.write().to_buffered(f).map_err(|e| match e {
            exr::error::Error::Io(io) => io,
            other => {
                let message = other.to_string();
                encode_error = Some(message.clone());
                std::io::Error::other(message)
            }
        })
    });
    match (written, encode_error) {
        (Err(_), Some(message)) => Err(Error::Encode {
            format: "OpenEXR",
            message,
        }),
        (written, _) => written,
    }
}

/// Read a texture written by [`write_exr`]: the texture and its metadata.
///
/// # Errors
/// [`Error::Parse`] (invalid) when the file is not such a texture.
pub fn read_exr(path: impl AsRef<Path>) -> Result<(Rendered, ExrMeta), Error> {
    let path = path.as_ref();
    let bad = |found: String| {
        Error::Parse(ParseError {
            path: path.to_path_buf(),
            location: Location::default(),
            kind: ErrorKind::Invalid,
            expected: "an OpenEXR light distribution texture written by photosolid".into(),
            found,
        })
    };
    let image = exr::prelude::read_first_flat_layer_from_file(path).map_err(|e| match e {
        exr::error::Error::Io(io) if io.kind() != std::io::ErrorKind::UnexpectedEof => Error::io(path, io),
        other => bad(other.to_string()),
    })?;
    let layer = &image.layer_data;
    let other = &layer.attributes.other;
    let get = |k: &str| other.get(&Text::from(k));
    let get_text = |k: &str| match get(k) {
        Some(AttributeValue::Text(t)) => Ok(untext(t)),
        _ => Err(bad(format!("no text attribute `{k}`"))),
    };
    let get_i32 = |k: &str| match get(k) {
        Some(AttributeValue::I32(v)) => Ok(*v),
        _ => Err(bad(format!("no i32 attribute `{k}`"))),
    };
    let filter: Filter = get_text("photosolid.filter")?
        .parse()
        .map_err(|e: crate::error::ModelError| bad(e.to_string()))?;
    let factor = get_i32("photosolid.factor")?;
    let i_max_cd = match get("photosolid.i_max_cd") {
        Some(AttributeValue::F64(v)) => *v,
        _ => return Err(bad("no f64 attribute `photosolid.i_max_cd`".into())),
    };
    let measured = get_text("photosolid.measured_gamma_deg")?;
    let nums: Vec<f64> = measured.split_whitespace().filter_map(|t| t.parse().ok()).collect();
    let [g0, g1] = nums[..] else {
        return Err(bad(format!("measured gamma `{measured}`")));
    };
    let clamped = get_i32("photosolid.clamped")?;
    let source = get_text("photosolid.source")?;
    let channel = layer
        .channel_data
        .list
        .iter()
        .find(|c| c.name.eq(CHANNEL))
        .ok_or_else(|| bad(format!("no channel `{CHANNEL}`")))?;
    let FlatSamples::F32(data) = &channel.sample_data else {
        return Err(bad("channel Y is not float32".into()));
    };
    let size = layer.size;
    Ok((
        Rendered {
            data: data.clone(),
            mapping: TexelMapping {
                height: size.height(),
                width: size.width(),
            },
            i_max_cd,
            filter,
            factor: factor.max(0) as u32,
            measured_gamma: (g0, g1),
            clamped: clamped.max(0) as usize,
        },
        ExrMeta {
            source: (!source.is_empty()).then_some(source),
        },
    ))
}
