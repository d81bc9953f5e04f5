//! The jobs that write a file: `synth`, `convert` and `export`. Each writes
//! atomically and returns what it wrote, the document their `--json` prints.

use std::path::Path;

use serde::Serialize;

use crate::engines::{export as export_layout, measure, Engine, EngineOptions, EnginesOptions};
use crate::error::{Result, Warning};
use crate::formats::{Header, WriteOptions};
use crate::model::Format;
use crate::reconstruct::Filter;
use crate::synth::{GridSpec, Synth, Truth};

use super::Named;

/// What a writing job wrote.
#[derive(Clone, Debug, Serialize)]
pub struct Written {
    /// The file written.
    pub output: String,
    /// `synth`: the distribution's exact luminous flux, lm (None where it has no closed form).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exact_flux_lm: Option<f64>,
    /// `export`: the engine and its layout in words.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub engine: Option<Engine>,
    /// `export`: the layout in words.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub layout: Option<String>,
    /// `export`: the image size (width, height), for image layouts.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub size: Option<(usize, usize)>,
    /// `export` for pbrt: 4π × the image mean, lm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pbrt_flux_lm: Option<f64>,
    /// What the written file loses or changes (`convert`'s `front-differs`,
    /// `field-not-kept`; `export`'s `layout-limit`).
    pub warnings: Vec<Warning>,
}

impl Written {
    fn file(output: &Path) -> Written {
        Written {
            output: output.display().to_string(),
            exact_flux_lm: None,
            engine: None,
            layout: None,
            size: None,
            pbrt_flux_lm: None,
            warnings: vec![],
        }
    }
}

/// The options of `synth` (the CLI's flags).
#[derive(Clone, Debug)]
pub struct SynthSettings {
    /// The distribution.
    pub kind: Synth,
    /// `--intensity`: the peak intensity, cd. Default 1000.
    pub intensity_cd: f64,
    /// The measurement grid (`--c-step`/`--gamma-step` or `--c-list`/`--gamma-list`).
    pub grid: GridSpec,
}

/// `photosolid synth KIND -o OUTPUT`: the distribution measured on the grid,
/// written in the format of `output`'s extension (the roadway's street side
/// where that format's readers take its front).
pub fn synth(output: &Path, settings: &SynthSettings) -> Result<Written> {
    let format = Format::from_extension(output).unwrap_or(Format::Ldt);
    let lum = settings.kind.build_for(format, &settings.grid, settings.intensity_cd)?;
    crate::save(&lum.into(), output, &WriteOptions::default())?;
    Ok(Written {
        exact_flux_lm: settings.kind.exact_flux(settings.intensity_cd),
        ..Written::file(output)
    })
}

/// The options of `convert` (the CLI's flags).
#[derive(Clone, Debug, Default)]
pub struct ConvertSettings {
    /// `--ies-version`.
    pub write: WriteOptions,
    /// `--rotate-c`: each plane at C moves to C + this, degrees.
    pub rotate_c_deg: f64,
    /// `--mirror`: each plane at C moves to −C first.
    pub mirror: bool,
}

/// `photosolid convert IN OUT`: `input` written in the format of `output`'s
/// extension, turned as `settings` says (the front turns with the planes).
pub fn convert(input: Named<'_>, output: &Path, settings: &ConvertSettings) -> Result<Written> {
    let mut doc = input.document.clone();
    if settings.rotate_c_deg != 0.0 || settings.mirror {
        // Setting the distribution drops the Type A/B source grid; the raw
        // header describes the old orientation too: writers derive a fresh one.
        let turned = doc.distribution().reoriented(settings.rotate_c_deg, settings.mirror)?;
        doc.luminaire.set_distribution(turned);
        doc.header = Header::None;
        let front = doc.luminaire.front().reoriented(settings.rotate_c_deg, settings.mirror);
        doc.luminaire.set_front(front);
    }
    let warnings = Format::from_extension(output)
        .map(|target| crate::formats::conversion_warnings(&doc.luminaire, target))
        .unwrap_or_default();
    crate::save(&doc, output, &settings.write)?;
    Ok(Written {
        warnings,
        ..Written::file(output)
    })
}

/// The options of `export` (the CLI's flags).
#[derive(Clone, Debug)]
pub struct ExportSettings {
    /// `--engine`.
    pub engine: Engine,
    /// `--resolution` where the engine's resolution is a choice.
    pub resolution: Option<usize>,
    /// `--filter` of pbrt's and godot's bakes. Default catmull-rom.
    pub filter: Filter,
}

/// `photosolid export FILE --engine E -o OUTPUT`: the engine's layout written,
/// and what it costs in accuracy (`layout-limit` above 5 % radial max).
pub fn export(input: Named<'_>, output: &Path, settings: &ExportSettings) -> Result<Written> {
    let want = settings.engine.extension();
    let ext = output
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if ext != want {
        return Err(super::option_error(
            "-o",
            format!(
                "{}: the {} layout is written as .{want}",
                output.display(),
                settings.engine
            ),
        ));
    }
    let layout = EngineOptions {
        resolution: settings.resolution,
        filter: settings.filter,
    };
    let e = export_layout(settings.engine, input.document, output, &layout)?;
    // The engines measurement of this engine alone.
    let measured = measure(
        input.document,
        &EnginesOptions {
            engines: vec![settings.engine],
            truth: Truth::of_luminaire(input.document),
            layout,
            ..Default::default()
        },
    )?;
    Ok(Written {
        engine: Some(e.engine),
        layout: Some(e.layout),
        size: e.size,
        pbrt_flux_lm: e.pbrt_flux_lm,
        warnings: measured.warnings,
        ..Written::file(output)
    })
}
