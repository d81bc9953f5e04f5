//! The EULUMDAT number stream (line 27 on): angle lists and their checks,
//! the stored planes, the intensities, their units and the model's grid.

use super::{Head, Reader};
use crate::error::{Location, Num, Nums, ParseError, WarningCode};
use crate::formats::ldt::{formula_plane_count, stored_plane_indices};
use crate::formats::scan::Scanner;
use crate::formats::text::Source;
use crate::formats::{angles, LampSetFlux, ReadOptions};
use crate::model::{Distribution, LampSet, Symmetry, ANGLE_EPS};
use crate::numfmt::significant;

impl<'s, 'a> Reader<'s, 'a> {
    /// Lines 27-29: direct ratios, C-angles, γ angles.
    pub(super) fn read_angle_lists(
        &mut self,
        toks: &mut Scanner<'a>,
        head: &Head,
    ) -> Result<AngleLists<'a>, ParseError> {
        let (src, mc, ng) = (self.src, head.mc, head.ng);
        // Every value but the last takes two bytes (a digit and a separator),
        // which bounds the counts before anything is allocated, without a counting pass.
        let max_values = toks.max_remaining();
        let minimum = 10 + mc + ng + ng;
        if minimum > max_values {
            return Err(src.invalid(
                toks.end_location(),
                format!(
                    "at least {minimum} values after the lamp sets (10 direct ratios, {mc} C-angles, {ng} gamma angles, \
                     {ng}+ intensities)"
                ),
                format!("{} values", toks.count_remaining()),
            ));
        }
        let mut direct_ratios = [0.0; 10];
        let ratios = read_list(src, toks, 10, &|i| format!("direct ratio {} of 10 (line 27)", i + 1))?;
        direct_ratios.copy_from_slice(&ratios);
        let c_first = toks.next_line();
        // Marks to point errors about the i-th angle at its own line and column.
        let c_toks = toks.clone();
        let c_file = read_list(src, toks, mc, &|i| {
            format!("C-angle {} of {mc} (line 28, degrees)", i + 1)
        })?;
        let g_first = toks.next_line();
        let g_toks = toks.clone();
        let gamma = read_list(src, toks, ng, &|i| {
            format!("gamma angle {} of {ng} (line 29, degrees)", i + 1)
        })?;
        Ok(AngleLists {
            max_values,
            direct_ratios,
            c_file,
            gamma,
            c_first,
            g_first,
            c_toks,
            g_toks,
        })
    }

    /// Angle lists: in range, in order (or a warned repair), and spaced as Dc and Dg say.
    pub(super) fn check_angle_lists(
        &mut self,
        head: &Head,
        lists: &AngleLists<'_>,
        opts: &ReadOptions,
    ) -> Result<(), ParseError> {
        let src = self.src;
        check_range(src, &lists.c_file, &lists.c_toks, "C", 360.0)?;
        check_range(src, &lists.gamma, &lists.g_toks, "gamma", 180.0)?;
        let c_sorted = strictly_ascending(&lists.c_file);
        let g_sorted = strictly_ascending(&lists.gamma);
        for (ok, at, what) in [(c_sorted, &lists.c_toks, "C"), (g_sorted, &lists.g_toks, "gamma")] {
            if let Err((i, a, b)) = ok {
                let loc = at.nth(i).0;
                if !opts.repair {
                    return Err(src.invalid(
                        loc,
                        format!("strictly ascending {what} angles"),
                        format!(
                            "{what} angle #{} = {} after {} (use the repair option to sort them)",
                            i + 1,
                            Num(b),
                            Num(a)
                        ),
                    ));
                }
                self.warn(
                    loc.line,
                    WarningCode::UnsortedAngles,
                    format!(
                        "{what} angles not strictly ascending (#{} = {} after {}); sorted, duplicates dropped",
                        i + 1,
                        Num(b),
                        Num(a)
                    ),
                );
            }
        }
        let steps = [
            (
                head.dc,
                &lists.c_file,
                c_sorted,
                head.mc_line,
                WarningCode::DcMismatch,
                "Dc",
                "C-angles of line 28",
            ),
            (
                head.dg,
                &lists.gamma,
                g_sorted,
                head.ng_line,
                WarningCode::DgMismatch,
                "Dg",
                "gamma angles of line 29",
            ),
        ];
        for (step, list, sorted, line, code, name, what) in steps {
            let off_step = |(i, &a): (usize, &f64)| (a - list[0] - i as f64 * step).abs() > 1e-3;
            if step > 0.0 && sorted.is_ok() && list.iter().enumerate().any(off_step) {
                self.warn(
                    line + 1,
                    code,
                    format!(
                        "{name} = {} but the {what} are not spaced by it; the list is used",
                        Num(step)
                    ),
                );
            }
        }
        Ok(())
    }

    /// Indices of the stored planes, by angle value (see the module docs), and their count checked against Mc.
    pub(super) fn stored_planes(&mut self, head: &Head, lists: &AngleLists<'_>) -> Result<Vec<usize>, ParseError> {
        let (sym, isym, mc, mc_line) = (head.sym, head.isym, head.mc, head.mc_line);
        let stored = stored_plane_indices(sym, &lists.c_file);
        if stored.is_empty() {
            let (lo, hi) = sym.stored_range();
            return Err(self.src.invalid(
                Location::line(lists.c_first),
                format!("C-angles in [{lo}, {hi}] for Isym {isym}"),
                "none in line 28",
            ));
        }
        match formula_plane_count(sym, mc) {
            None => self.warn(
                mc_line,
                WarningCode::McDivisibility,
                format!(
                    "Mc = {mc} is not divisible as Isym {isym} requires; the stored planes are taken by angle ({} planes)",
                    stored.len()
                ),
            ),
            Some(n) if n != stored.len() => self.warn(
                mc_line,
                WarningCode::PlaneCount,
                format!(
                    "Isym {isym} with Mc = {mc} stores {n} planes by the format's formula, but line 28 has {} angles in the stored range; those are used",
                    stored.len()
                ),
            ),
            _ => {}
        }
        Ok(stored)
    }

    /// Line 30 on: `nstored` planes of Ng intensities (cd/klm), and the line they start on; trailing values warned.
    pub(super) fn read_intensities(
        &mut self,
        toks: &mut Scanner<'_>,
        head: &Head,
        lists: &AngleLists<'_>,
        nstored: usize,
    ) -> Result<(Vec<f64>, usize), ParseError> {
        let (src, mc, ng) = (self.src, head.mc, head.ng);
        let need = nstored * ng;
        let truncated = |found: usize, toks: &Scanner<'_>| {
            src.invalid(
                toks.end_location(),
                format!("{need} intensities ({nstored} C-planes × {ng} gamma angles, line 30 on)"),
                format!("{found} values before the end of the file"),
            )
        };
        if 10 + mc + ng + need > lists.max_values {
            return Err(truncated(toks.count_remaining(), toks));
        }
        let cd_first = toks.next_line();
        let mut cd = Vec::with_capacity(need);
        toks.fill(need, &mut cd).map_err(|s| {
            if s.at_end {
                truncated(s.read, toks)
            } else {
                let what = format!(
                    "intensity in cd/klm (plane {} of {nstored}, gamma {} of {ng})",
                    s.read / ng + 1,
                    s.read % ng + 1
                );
                src.invalid(s.location, what, s.found)
            }
        })?;
        if toks.has_more() {
            let extra = toks.count_remaining();
            self.warn(
                toks.next_line(),
                WarningCode::ExtraValues,
                format!("{extra} values after the {need} intensities were ignored"),
            );
        }
        Ok((cd, cd_first))
    }

    /// Units: cd = cd/klm × CFLI × Φ_ref / 1000, applied to `cd`; the values must then lie in the model's range.
    pub(super) fn candela_units(
        &mut self,
        head: &Head,
        lamp_sets: &[LampSet],
        opts: &ReadOptions,
        cd: &mut [f64],
        cd_first: usize,
        nstored: usize,
    ) -> Result<Units, ParseError> {
        let (cfli, ng) = (head.cfli, head.ng);
        let absolute = lamp_sets[0].count < 0.0;
        let mut phi = match opts.lamp_set_flux {
            LampSetFlux::First => lamp_sets[0].flux_lm,
            LampSetFlux::Sum => lamp_sets.iter().map(|s| s.flux_lm).sum(),
        };
        // A subnormal flux would scale every intensity to 0 (or overflow cd/klm × flux).
        let flux_ok = phi.is_normal() && phi > 0.0;
        if !flux_ok {
            self.warn(
                head.n_line + 1,
                WarningCode::ZeroLampFlux,
                format!(
                    "reference flux is {} lm; intensities taken as cd (1000 lm assumed)",
                    Num(phi)
                ),
            );
            phi = 1000.0;
        }
        let scale = cfli * phi / 1000.0;
        let negatives = crate::formats::negative_intensities(cd, "cd/klm");
        for v in cd.iter_mut() {
            *v *= scale;
        }
        let snapped = crate::formats::into_model_range(cd);
        if let Ok(Some(note)) = &snapped {
            self.warn(cd_first, WarningCode::RangeSnapped, note.clone());
        }
        if let Err((i, why)) = snapped {
            return Err(self.src.invalid(
                Location::line(cd_first),
                format!(
                    "intensities whose candela values (cd/klm × flux {} lm × CFLI {} / 1000) \
                     lie in the model's range",
                    Num(phi),
                    Num(cfli)
                ),
                format!("plane {} of {nstored}, gamma {} of {ng}: {why}", i / ng + 1, i % ng + 1),
            ));
        }
        if let Some(note) = negatives {
            self.warn(cd_first, WarningCode::NegativeIntensity, note);
        }
        Ok(Units {
            absolute,
            flux_ok,
            phi,
            scale,
        })
    }

    /// The model's grid: planes relabelled into the symmetry's range, ordered,
    /// a duplicate C360 dropped; repaired lists sorted.
    pub(super) fn model_grid(
        &mut self,
        head: &Head,
        lists: &mut AngleLists<'_>,
        stored: &[usize],
        mut cd: Vec<f64>,
        opts: &ReadOptions,
    ) -> Result<Distribution, ParseError> {
        let (sym, isym, ng, c_first) = (head.sym, head.isym, head.ng, lists.c_first);
        let c_file = &lists.c_file;
        let mut c_model: Vec<f64> = stored
            .iter()
            .map(|&i| match sym {
                Symmetry::None => c_file[i],
                _ => sym.fold(c_file[i]),
            })
            .collect();
        if sym == Symmetry::None && c_model.len() > 1 && c_model[c_model.len() - 1] >= 360.0 - ANGLE_EPS {
            let last = c_model.len() - 1;
            let diff = (0..ng).map(|g| (cd[last * ng + g] - cd[g]).abs()).fold(0.0, f64::max);
            self.warn(
                c_first,
                WarningCode::C360Plane,
                format!(
                    "C = 360 duplicates C = 0 and was dropped (largest difference {} cd)",
                    crate::numfmt::significant(diff, 6)
                ),
            );
            c_model.pop();
            cd.truncate(last * ng);
        }
        if is_strictly_descending(&c_model) {
            // Isym 3: file order C270 ... C345, C0 ... C90 is model C270 down to C90.
            c_model.reverse();
            reverse_planes(&mut cd, ng);
        }
        if strictly_ascending(&c_model).is_err() {
            if !opts.repair {
                return Err(self.src.invalid(
                    Location::line(c_first),
                    "stored C-planes with distinct, ordered angles",
                    format!("{} after mapping Isym {isym} planes", Nums(&c_model)),
                ));
            }
            (c_model, cd) = sort_planes(&c_model, &cd, ng);
        }
        let mut gamma = std::mem::take(&mut lists.gamma);
        if strictly_ascending(&gamma).is_err() {
            (gamma, cd) = sort_gamma(&gamma, &cd);
        }
        Distribution::new(c_model, gamma, cd, sym).map_err(|e| {
            self.src.invalid(
                Location::line(c_first),
                format!("a valid Isym {isym} grid"),
                e.to_string(),
            )
        })
    }

    /// The nadir and zenith are one direction each: values that differ between planes are warned about.
    pub(super) fn warn_pole_spread(&mut self, dist: &Distribution, g_first: usize) {
        let (nadir, zenith) = dist.pole_spread_cd();
        let ng = dist.gamma_angles_deg().len();
        for (spread, name, ig) in [(nadir, "nadir (gamma 0)", 0), (zenith, "zenith (gamma 180)", ng - 1)] {
            // Differences at float-noise level are no mismatch.
            if spread > 0.0 && spread > 1e-9 * dist.max_cd().abs().max(1.0) {
                let mean = (0..dist.n_c()).map(|ic| dist.value_cd(ic, ig)).sum::<f64>() / dist.n_c() as f64;
                self.warn(
                    g_first,
                    WarningCode::PoleMismatch,
                    format!(
                        "{name} values differ between planes by {} cd ({} % of their mean {} cd); kept",
                        significant(spread, 7),
                        significant(
                            if mean.abs() > 0.0 {
                                100.0 * spread / mean.abs()
                            } else {
                                0.0
                            },
                            4
                        ),
                        significant(mean, 7)
                    ),
                );
            }
        }
    }
}

/// Lines 27-29 as read, with marks at the first C and γ angle and their lines.
pub(super) struct AngleLists<'a> {
    /// Bound on the values of the number stream (from line 27 on).
    pub(super) max_values: usize,
    pub(super) direct_ratios: [f64; 10],
    pub(super) c_file: Vec<f64>,
    pub(super) gamma: Vec<f64>,
    pub(super) c_first: usize,
    pub(super) g_first: usize,
    pub(super) c_toks: Scanner<'a>,
    pub(super) g_toks: Scanner<'a>,
}

/// The flux the intensities refer to and the factor applied.
#[derive(Clone, Copy)]
pub(super) struct Units {
    pub(super) absolute: bool,
    /// Whether the lamp sets' flux was usable (otherwise 1000 lm was assumed).
    pub(super) flux_ok: bool,
    /// Reference flux Φ_ref, lm.
    pub(super) phi: f64,
    /// cd per cd/klm: CFLI × Φ_ref / 1000.
    pub(super) scale: f64,
}

/// The next `n` numbers, `what(i)` naming the i-th in errors.
fn read_list(
    src: &Source<'_>,
    toks: &mut Scanner<'_>,
    n: usize,
    what: &dyn Fn(usize) -> String,
) -> Result<Vec<f64>, ParseError> {
    let mut v = Vec::with_capacity(n);
    toks.fill(n, &mut v)
        .map_err(|s| src.invalid(s.location, what(s.read), s.found))?;
    Ok(v)
}

/// Every angle of `v` (marked by `at`) within [0, `hi`] degrees ([`angles::first_outside`]).
fn check_range(src: &Source<'_>, v: &[f64], at: &Scanner<'_>, what: &str, hi: f64) -> Result<(), ParseError> {
    match angles::first_outside(v, hi) {
        None => Ok(()),
        Some(i) => Err(src.invalid(
            at.nth(i).0,
            format!("{what} angles in [0, {hi}] degrees"),
            format!("{what} angle #{} = {}", i + 1, Num(v[i])),
        )),
    }
}

/// Ok, or the first offending index with (previous, value) ([`angles::first_disorder`]).
fn strictly_ascending(v: &[f64]) -> Result<(), (usize, f64, f64)> {
    match angles::first_disorder(v) {
        None => Ok(()),
        Some(i) => Err((i, v[i - 1], v[i])),
    }
}

fn is_strictly_descending(v: &[f64]) -> bool {
    v.len() > 1 && v.windows(2).all(|w| w[1] < w[0] - ANGLE_EPS)
}

/// Reverse the order of the planes of a C-major block in place.
fn reverse_planes(cd: &mut [f64], ng: usize) {
    let n = cd.len() / ng;
    for i in 0..n / 2 {
        let (a, b) = cd.split_at_mut((n - 1 - i) * ng);
        a[i * ng..(i + 1) * ng].swap_with_slice(&mut b[..ng]);
    }
}

/// Repair: planes sorted by angle, duplicates dropped ([`angles::repair_order`]).
fn sort_planes(c: &[f64], cd: &[f64], ng: usize) -> (Vec<f64>, Vec<f64>) {
    let order = angles::repair_order(c);
    (
        order.iter().map(|&i| c[i]).collect(),
        angles::reorder_planes(cd, ng, &order),
    )
}

/// Repair: γ sorted within every plane, duplicates dropped ([`angles::repair_order`]).
fn sort_gamma(g: &[f64], cd: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let order = angles::repair_order(g);
    (
        order.iter().map(|&i| g[i]).collect(),
        angles::reorder_rows(cd, g.len(), &order),
    )
}
