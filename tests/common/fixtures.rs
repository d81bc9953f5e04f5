//! Small photometric files the tests build themselves (never copied from the
//! corpus): IES LM-63 of every version with each TILT form and photometric
//! type, EULUMDAT of each symmetry with any lamp sets, TM-33 XML and GLDF
//! containers, and helpers that damage them (truncate at a line, replace a
//! token). The builders write the formats' text field by field, so a test
//! knows which line holds what and can assert the exact error location.

use std::io::Write;
use std::path::Path;

use photosolid::formats::ReadOptions;
use photosolid::model::{Distribution, Format, Luminaire};
use photosolid::ParseError;

/// Read `bytes` as `format`, named `path` in errors (the one place the tests
/// of the fixtures call the readers).
pub fn read(format: Format, path: &Path, bytes: &[u8]) -> Result<photosolid::formats::Document, ParseError> {
    photosolid::formats::parse(bytes, path, format, &ReadOptions::default())
}

/// The distribution of a loaded luminaire (one place to follow the model's accessors).
pub fn distribution(l: &Luminaire) -> &Distribution {
    l.distribution()
}

/// The tilt table of a loaded luminaire, if any.
pub fn tilt_table(l: &Luminaire) -> Option<&photosolid::model::TiltTable> {
    l.tilt().table()
}

/// How many lamp sets a loaded luminaire has.
pub fn lamp_set_count(l: &Luminaire) -> usize {
    l.lamp_sets().len()
}

/// The LM-63 editions: the first line each writes (none in 1986).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IesVersion {
    Lm1986,
    Lm1991,
    Lm1995,
    Lm2002,
    Lm2019,
}

impl IesVersion {
    /// Every edition, oldest first.
    pub const ALL: [IesVersion; 5] = [Self::Lm1986, Self::Lm1991, Self::Lm1995, Self::Lm2002, Self::Lm2019];

    /// The version line, None for 1986 (free-form label lines only).
    pub fn version_line(self) -> Option<&'static str> {
        match self {
            Self::Lm1986 => None,
            Self::Lm1991 => Some("IESNA91"),
            Self::Lm1995 => Some("IESNA:LM-63-1995"),
            Self::Lm2002 => Some("IESNA:LM-63-2002"),
            Self::Lm2019 => Some("IES:LM-63-2019"),
        }
    }

    /// Whether the second value of the ballast record multiplies the candela values.
    pub fn ballast_lamp_factor_applies(self) -> bool {
        matches!(self, Self::Lm1986 | Self::Lm1991)
    }
}

/// The TILT line's three forms.
#[derive(Debug, Clone, PartialEq)]
pub enum IesTilt {
    None,
    /// `TILT=INCLUDE` and the table inline: geometry, angles (degrees), multipliers.
    Include(u8, Vec<f64>, Vec<f64>),
    /// `TILT=<file name>`, resolved next to the photometric file.
    File(String),
}

/// An IES LM-63 file, field by field (angles in degrees, intensities in cd
/// before the multiplier, one row of `vertical.len()` values per horizontal angle).
#[derive(Debug, Clone)]
pub struct IesFile {
    pub version: IesVersion,
    pub tilt: IesTilt,
    pub lamps: f64,
    /// Lumens per lamp; -1 = absolute photometry.
    pub lumens_per_lamp: f64,
    pub multiplier: f64,
    /// 1 = C, 2 = B, 3 = A.
    pub photometric_type: u8,
    /// 1 = feet, 2 = metres.
    pub units: u8,
    /// Width, length, height of the luminous opening in `units`.
    pub size: [f64; 3],
    /// Ballast factor, ballast-lamp factor (1986/1991) or future use, input watts.
    pub ballast: [f64; 3],
    pub vertical: Vec<f64>,
    pub horizontal: Vec<f64>,
    pub cd: Vec<f64>,
}

impl IesFile {
    /// A Type C quadrant-symmetric file (planes 0, 45, 90; gamma 0..180 by 30).
    pub fn type_c(version: IesVersion) -> Self {
        let vertical: Vec<f64> = (0..=6).map(|k| k as f64 * 30.0).collect();
        let horizontal = vec![0.0, 45.0, 90.0];
        let cd = grid_values(&horizontal, &vertical);
        Self {
            version,
            tilt: IesTilt::None,
            lamps: 1.0,
            lumens_per_lamp: 1000.0,
            multiplier: 1.0,
            photometric_type: 1,
            units: 2,
            size: [0.1, 0.2, 0.0],
            ballast: [1.0, 1.0, 12.0],
            vertical,
            horizontal,
            cd,
        }
    }

    /// A Type B (2) or Type A (3) file over H -90..90, V -90..90 by 45.
    pub fn type_ab(version: IesVersion, photometric_type: u8) -> Self {
        let axis: Vec<f64> = (-2..=2).map(|k| k as f64 * 45.0).collect();
        let cd = grid_values(&axis, &axis);
        Self {
            photometric_type,
            vertical: axis.clone(),
            horizontal: axis,
            cd,
            ..Self::type_c(version)
        }
    }

    /// Line number (1-based) of the first line of each part, in the order written.
    pub fn lines(&self) -> IesLines {
        let labels = if self.version.version_line().is_some() { 3 } else { 2 };
        let tilt = labels + 1;
        let table = match self.tilt {
            IesTilt::Include(..) => 4,
            _ => 0,
        };
        let counts = tilt + table + 1;
        IesLines {
            tilt,
            counts,
            ballast: counts + 1,
            vertical: counts + 2,
            horizontal: counts + 3,
            cd: counts + 4,
        }
    }

    /// The file's text (LF line ends).
    pub fn text(&self) -> String {
        let mut s = String::new();
        if let Some(v) = self.version.version_line() {
            s.push_str(v);
            s.push('\n');
        }
        if self.version == IesVersion::Lm1986 {
            s.push_str("PHOTOSOLID FIXTURE\nA generated test file\n");
        } else {
            s.push_str("[TEST] photosolid fixture\n[MANUFAC] photosolid\n");
        }
        match &self.tilt {
            IesTilt::None => s.push_str("TILT=NONE\n"),
            IesTilt::File(name) => s.push_str(&format!("TILT={name}\n")),
            IesTilt::Include(geometry, angles, multipliers) => s.push_str(&format!(
                "TILT=INCLUDE\n{geometry}\n{}\n{}\n{}\n",
                angles.len(),
                list(angles),
                list(multipliers)
            )),
        }
        let [w, l, h] = self.size;
        s.push_str(&format!(
            "{} {} {} {} {} {} {} {w} {l} {h}\n",
            self.lamps,
            self.lumens_per_lamp,
            self.multiplier,
            self.vertical.len(),
            self.horizontal.len(),
            self.photometric_type,
            self.units
        ));
        s.push_str(&format!(
            "{} {} {}\n",
            self.ballast[0], self.ballast[1], self.ballast[2]
        ));
        s.push_str(&format!("{}\n{}\n", list(&self.vertical), list(&self.horizontal)));
        for row in self.cd.chunks(self.vertical.len().max(1)) {
            s.push_str(&list(row));
            s.push('\n');
        }
        s
    }
}

/// Where the parts of an [`IesFile`] start (1-based lines).
#[derive(Debug, Clone, Copy)]
pub struct IesLines {
    pub tilt: usize,
    pub counts: usize,
    pub ballast: usize,
    pub vertical: usize,
    pub horizontal: usize,
    pub cd: usize,
}

/// One EULUMDAT lamp set (lines 26a-26f).
#[derive(Debug, Clone)]
pub struct LampSet {
    pub lamps: i32,
    pub kind: String,
    pub flux_lm: f64,
    pub colour: String,
    pub cri: String,
    pub watts: f64,
}

impl LampSet {
    /// `lamps` lamps of `flux_lm` in all, `watts` W.
    pub fn new(lamps: i32, flux_lm: f64, watts: f64) -> Self {
        Self {
            lamps,
            kind: "LED".into(),
            flux_lm,
            colour: "3000K".into(),
            cri: "80".into(),
            watts,
        }
    }
}

/// A EULUMDAT file, field by field: `cd_per_klm` holds the stored planes
/// (see [`LdtFile::stored_planes`]) one after the other, `ng` values each.
#[derive(Debug, Clone)]
pub struct LdtFile {
    pub isym: u8,
    pub mc: usize,
    pub ng: usize,
    pub lamp_sets: Vec<LampSet>,
    pub c_angles: Vec<f64>,
    pub gamma: Vec<f64>,
    pub cd_per_klm: Vec<f64>,
}

impl LdtFile {
    /// A file of symmetry `isym` (0..=4): 8 C-planes by 45 degrees, gamma 0..180 by 30, one lamp set.
    pub fn isym(isym: u8) -> Self {
        let mc = 8;
        let c_angles: Vec<f64> = (0..mc).map(|k| k as f64 * 45.0).collect();
        let gamma: Vec<f64> = (0..=6).map(|k| k as f64 * 30.0).collect();
        let mut f = Self {
            isym,
            mc,
            ng: gamma.len(),
            lamp_sets: vec![LampSet::new(1, 1000.0, 12.0)],
            c_angles,
            gamma,
            cd_per_klm: Vec::new(),
        };
        let stored: Vec<f64> = f.stored_planes().iter().map(|&i| f.c_angles[i]).collect();
        f.cd_per_klm = grid_values(&stored, &f.gamma);
        f
    }

    /// Indices (into `c_angles`) of the planes the file stores for its Isym,
    /// in file order (Isym 3: C270 ... C345, C0 ... C90).
    pub fn stored_planes(&self) -> Vec<usize> {
        let mc = self.mc;
        match self.isym {
            1 => vec![0],
            2 => (0..=mc / 2).collect(),
            3 => (3 * mc / 4..mc).chain(0..=mc / 4).collect(),
            4 => (0..=mc / 4).collect(),
            _ => (0..mc).collect(),
        }
    }

    /// Line number (1-based) where each part starts.
    pub fn lines(&self) -> LdtLines {
        let sets = 26 + 1;
        let ratios = sets + 6 * self.lamp_sets.len();
        LdtLines {
            isym: 3,
            mc: 4,
            ng: 6,
            n_sets: 26,
            sets,
            ratios,
            c_angles: ratios + 10,
            gamma: ratios + 10 + self.c_angles.len(),
            cd: ratios + 10 + self.c_angles.len() + self.gamma.len(),
        }
    }

    /// The file's text (CRLF line ends, one value per line as the format has it).
    pub fn text(&self) -> String {
        let dc = if self.mc > 1 { 360.0 / self.mc as f64 } else { 0.0 };
        let dg = if self.ng > 1 { 180.0 / (self.ng - 1) as f64 } else { 0.0 };
        let mut l: Vec<String> = vec![
            "photosolid fixture".into(),
            "1".into(),
            self.isym.to_string(),
            self.mc.to_string(),
            dc.to_string(),
            self.ng.to_string(),
            dg.to_string(),
            "report".into(),
            "luminaire".into(),
            "number".into(),
            "fixture.ldt".into(),
            "2026-01-01".into(),
        ];
        // Dimensions (mm), DFF, LOR, conversion factor, tilt.
        l.extend(
            [
                "600", "300", "50", "600", "300", "0", "0", "0", "0", "100", "80", "1", "0",
            ]
            .map(String::from),
        );
        l.push(self.lamp_sets.len().to_string());
        for s in &self.lamp_sets {
            l.extend([
                s.lamps.to_string(),
                s.kind.clone(),
                s.flux_lm.to_string(),
                s.colour.clone(),
                s.cri.clone(),
                s.watts.to_string(),
            ]);
        }
        l.extend((0..10).map(|k| format!("0.{}", 30 + 5 * k)));
        l.extend(self.c_angles.iter().map(|v| v.to_string()));
        l.extend(self.gamma.iter().map(|v| v.to_string()));
        l.extend(self.cd_per_klm.iter().map(|v| v.to_string()));
        let mut s = l.join("\r\n");
        s.push_str("\r\n");
        s
    }
}

/// Where the parts of an [`LdtFile`] start (1-based lines).
#[derive(Debug, Clone, Copy)]
pub struct LdtLines {
    pub isym: usize,
    pub mc: usize,
    pub ng: usize,
    pub n_sets: usize,
    pub sets: usize,
    pub ratios: usize,
    pub c_angles: usize,
    pub gamma: usize,
    pub cd: usize,
}

/// A TM-33-23 document (`IESTM33-22` root) with a C-type grid `(horz, vert, cd)`.
pub fn tm33_text(points: &[(f64, f64, f64)]) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<IESTM33-22>\n<Version>1.1</Version>\n<Header>\n\
         <Manufacturer>photosolid</Manufacturer>\n<CatalogNumber>F-1</CatalogNumber>\n</Header>\n\
         <Emitter>\n<Quantity>1</Quantity>\n<RatedLumens>1000</RatedLumens>\n<InputWattage>12</InputWattage>\n\
         <LuminousData>\n<PhotometryType>CIE _ C</PhotometryType>\n<Metric>Luminous</Metric>\n\
         <SymmType>Symm _ Quad</SymmType>\n",
    );
    for (h, v, cd) in points {
        s.push_str(&format!(
            "<IntensityData horz=\"{h}\" vert=\"{v}\">{cd}</IntensityData>\n"
        ));
    }
    s.push_str("</LuminousData>\n</Emitter>\n</IESTM33-22>\n");
    s
}

/// The points of a quadrant TM-33 grid: planes 0, 45, 90, gamma 0..180 by 30.
pub fn tm33_points() -> Vec<(f64, f64, f64)> {
    let (hs, vs) = ([0.0, 45.0, 90.0], (0..=6).map(|k| k as f64 * 30.0).collect::<Vec<_>>());
    let values = grid_values(&hs, &vs);
    hs.iter()
        .flat_map(|&h| vs.iter().map(move |&v| (h, v)))
        .zip(values)
        .map(|((h, v), cd)| (h, v, cd))
        .collect()
}

/// A GLDF container (zip bytes): `product.xml` and its members `(name, bytes)`.
pub fn gldf_bytes(product_xml: &str, members: &[(&str, Vec<u8>)]) -> Vec<u8> {
    let mut z = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let opts = zip::write::SimpleFileOptions::default();
    z.start_file("product.xml", opts).unwrap();
    z.write_all(product_xml.as_bytes()).unwrap();
    for (name, bytes) in members {
        z.start_file(*name, opts).unwrap();
        z.write_all(bytes).unwrap();
    }
    z.finish().unwrap().into_inner()
}

/// A GLDF product.xml with one photometry `id` referencing the member file `ldc/<file>`.
pub fn gldf_product(id: &str, file: &str, content_type: &str) -> String {
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Root>\n<Header/>\n<GeneralDefinitions>\n<Files>\n\
         <File id=\"f1\" contentType=\"{content_type}\" type=\"localFileName\">{file}</File>\n</Files>\n\
         <Photometries>\n<Photometry id=\"{id}\"><PhotometryFileReference fileId=\"f1\"/></Photometry>\n\
         </Photometries>\n</GeneralDefinitions>\n</Root>\n"
    )
}

/// Intensities that differ at every grid point (so a misplaced value shows):
/// `100 + 0.5 * a + 0.25 * b` over the rows of `rows` x `cols`.
pub fn grid_values(rows: &[f64], cols: &[f64]) -> Vec<f64> {
    rows.iter()
        .flat_map(|&a| cols.iter().map(move |&b| 100.0 + 0.5 * a.abs() + 0.25 * b.abs()))
        .collect()
}

/// Values separated by single blanks.
pub fn list(v: &[f64]) -> String {
    v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(" ")
}

/// The first `lines` lines of `text` (with their line ends).
pub fn first_lines(text: &str, lines: usize) -> String {
    text.split_inclusive('\n').take(lines).collect()
}

/// `text` with line `line` (1-based) replaced by `with` (its line end kept).
pub fn replace_line(text: &str, line: usize, with: &str) -> String {
    text.split_inclusive('\n')
        .enumerate()
        .map(|(i, l)| {
            if i + 1 == line {
                let body = l.trim_end_matches(['\r', '\n']);
                format!("{with}{}", &l[body.len()..])
            } else {
                l.to_string()
            }
        })
        .collect()
}

/// `text` with the `k`-th blank-separated token (0-based) of line `line` (1-based) replaced by `with`.
pub fn replace_token(text: &str, line: usize, k: usize, with: &str) -> String {
    let body: &str = text.lines().nth(line - 1).expect("line exists");
    let mut toks: Vec<&str> = body.split_whitespace().collect();
    toks[k] = with;
    replace_line(text, line, &toks.join(" "))
}
