//! `photosolid convert IN OUT [--ies-version 2002|2019] [--rotate-c DEG] [--mirror]`.
//!
//! IN may be any readable photometry (IES, EULUMDAT, TM-33, `FILE.gldf#ID`);
//! OUT's extension picks the writer: `.ies`, `.ldt` or `.xml` (TM-33-23).
//!
//! Both formats put C0 along the luminaire's length and count C
//! counter-clockwise seen from above, so the default keeps the C angles as
//! they are. `--rotate-c` and `--mirror` change the convention when a pair
//! of files disagrees (a lab that mounted the luminaire turned, or measured
//! clockwise): each plane at C moves to (mirror ? −C : C) + rotate, and the
//! luminaire's front with it. When the target format's convention puts the
//! front elsewhere than this luminaire's (an IES road luminaire, front C0,
//! written as EULUMDAT, whose readers take C90), a `front-differs` warning
//! names the `--front` / `street_side_c_deg` to use with the converted file.

use std::path::PathBuf;

use clap::Args;
use photosolid::formats::WriteOptions;
use photosolid::jobs::{self, ConvertSettings, Loaded};

use super::ReadArgs;

#[derive(Args, Debug)]
pub struct ConvertArgs {
    /// Input: .ies, .ldt, TM-33 .xml, or a GLDF photometry (FILE.gldf#ID; FILE.gldf when it holds one).
    input: PathBuf,
    /// Output file; .ies, .ldt or .xml (TM-33-23) decides the format.
    output: PathBuf,
    /// IES version to write.
    #[arg(long, value_enum, default_value = "2002")]
    ies_version: super::choice::IesVersionArg,
    /// Rotate the C angles by this many degrees (counter-clockwise seen from above).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true, value_parser = super::parse::finite)]
    rotate_c: f64,
    /// Mirror C -> -C (before rotating).
    #[arg(long)]
    mirror: bool,
    /// Print what was written as JSON: `output` and `warnings` (what the target format does not keep).
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    read: ReadArgs,
}

pub fn run(a: ConvertArgs) -> anyhow::Result<i32> {
    super::check_output("OUT", &a.output)?;
    let input = Loaded::load(&a.input, &a.read.options())?;
    let settings = ConvertSettings {
        write: WriteOptions {
            ies_version: a.ies_version.into(),
        },
        rotate_c_deg: a.rotate_c,
        mirror: a.mirror,
    };
    let written = jobs::convert(input.named(), &a.output, &settings)?;
    for w in &written.warnings {
        eprintln!("warning: {w}");
    }
    if a.json {
        super::emit(true, &written, "")?;
    }
    eprintln!("wrote {}", a.output.display());
    Ok(0)
}
