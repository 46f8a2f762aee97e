//! Impact and wear statistics of one shock's sampled history: the numerics of Code_Aster's
//! POST_DYNA_MODA_T (CHOC, OPTION='IMPACT' and 'USURE'). Pure numerics: no SQL, no
//! keywords; the operator reads the archived samples and writes the table.
//!
//! Definitions, on the archived samples t_k, FN_k (Code_Aster's, written here from its
//! documentation of the table's columns):
//! - a sample is *in contact* when |FN_k| > s, s the threshold SEUIL_FORCE;
//! - a *contact* (Code_Aster's rebound) is a maximal run of samples in contact: it begins
//!   at its first sample and ends at the first sample after it out of contact;
//! - an *impact* (Code_Aster's global shock) gathers the contacts separated by rests
//!   shorter than DUREE_REPOS: it ends at a sample k out of contact when no sample in
//!   (t_k, t_k + DUREE_REPOS] is in contact. Its duration T_CHOC is t_k minus the instant of
//!   its first sample; an impact still open at the last sample is not counted;
//! - per impact: F_MAX the largest FN of its samples (INSTANT where it is reached, the last
//!   one on a tie), IMPULSION = Σ FN_k (t_{k+1} − t_{k−1})/2 over its samples in contact
//!   (the trapezoidal rule of ∫FN dt when FN vanishes at the samples around), V_IMPACT the
//!   normal velocity VN at its first sample, NB_IMPACT its number of contacts;
//! - over the impacts: F_MAX_ABS the largest FN in contact (open impact included),
//!   F_MAX_MOY the mean of the F_MAX, F_MAX_ETYPE their standard deviation (population:
//!   divided by the number of impacts), and the histogram of the F_MAX in NB_CLASSE equal
//!   classes between the smallest and the largest (PROBA: the share of impacts in each);
//! - wear (OPTION='USURE'), the samples cut into NB_BLOC blocks of ⌊n/NB_BLOC⌋ samples,
//!   each block's statistics averaged: mean, standard deviation, RMS, extremes of the local
//!   displacements DXLOC, DYLOC, DZLOC, of the radial one √(DYLOC² + DZLOC²), of the polar
//!   angle atan2(DZLOC, DYLOC) in degrees, of FT1 and FT2; FN's mean and RMS over the block
//!   (T_TOTAL) and over its samples in contact (T_CHOC); impacts per second, contacts per
//!   impact, durations, share of time in contact; and the wear power (Archard) PUIS_USURE,
//!   the time average of |FN| √(VT1² + VT2²) by the trapezoidal rule over the intervals
//!   that start from a sliding sample: Code_Aster (`pusure`) leaves out each interval
//!   whose first sample sticks (its stick flag, VINT13), so a stick's creep in the
//!   tangential spring RIGI_TAN wears nothing.

/// One impact (a global shock).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Impact {
    /// Index of its first sample in contact.
    pub first: usize,
    /// Index of the sample out of contact that ends it (`None` while it is open).
    pub end: Option<usize>,
    /// INSTANT: where F_MAX is reached.
    pub t_peak: f64,
    /// F_MAX.
    pub f_max: f64,
    /// IMPULSION.
    pub impulse: f64,
    /// T_CHOC (0 while open).
    pub duration: f64,
    /// V_IMPACT.
    pub v_impact: f64,
    /// NB_IMPACT: its contacts (rebounds) that ended.
    pub contacts: usize,
}

/// A contact (rebound): first sample in contact, first sample after it out of contact.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Contact {
    pub first: usize,
    pub end: usize,
}

/// The impacts and contacts of a history.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Detection {
    /// The impacts that ended, in time order.
    pub impacts: Vec<Impact>,
    /// The impact still open at the last sample, if any.
    pub open: Option<Impact>,
    /// Every contact that ended.
    pub contacts: Vec<Contact>,
    /// F_MAX_ABS: the largest FN of the samples in contact (0 if none).
    pub f_max_abs: f64,
}

/// The weight of sample k in the trapezoidal rule over the samples `t`.
fn trapezoid_weight(t: &[f64], k: usize) -> f64 {
    let n = t.len();
    if n < 2 {
        return 0.0;
    }
    let lo = t[k.saturating_sub(1)];
    let hi = t[(k + 1).min(n - 1)];
    0.5 * (hi - lo)
}

/// The impacts of the history (t, FN, VN): threshold `threshold` (SEUIL_FORCE ≥ 0) and
/// rest `rest` (DUREE_REPOS ≥ 0). The slices are read up to the shortest.
pub fn detect(t: &[f64], f_n: &[f64], v_n: &[f64], threshold: f64, rest: f64) -> Detection {
    let n = t.len().min(f_n.len()).min(v_n.len());
    let (t, f_n, v_n) = (&t[..n], &f_n[..n], &v_n[..n]);
    let in_contact = |k: usize| f_n[k].abs() > threshold;
    // A rest is short when a sample in contact follows within `rest` (a hair of relative
    // slack, so that a rest of exactly DUREE_REPOS on a constant step is counted short,
    // as Code_Aster's count of steps does).
    let resumes_after = |k: usize| {
        rest > 0.0
            && (k + 1..n)
                .take_while(|&j| t[j] - t[k] <= rest * (1.0 + 1e-9))
                .any(in_contact)
    };
    let mut out = Detection::default();
    let mut current: Option<Impact> = None;
    let mut contact_start: Option<usize> = None;
    for k in 0..n {
        if in_contact(k) {
            let imp = current.get_or_insert(Impact {
                first: k,
                end: None,
                t_peak: t[k],
                f_max: f_n[k],
                impulse: 0.0,
                duration: 0.0,
                v_impact: v_n[k],
                contacts: 0,
            });
            contact_start.get_or_insert(k);
            imp.impulse += f_n[k] * trapezoid_weight(t, k);
            if f_n[k] >= imp.f_max {
                imp.f_max = f_n[k];
                imp.t_peak = t[k];
            }
            out.f_max_abs = out.f_max_abs.max(f_n[k]);
        } else {
            if let Some(first) = contact_start.take() {
                out.contacts.push(Contact { first, end: k });
                if let Some(imp) = current.as_mut() {
                    imp.contacts += 1;
                }
            }
            if current.is_some() && !resumes_after(k) {
                if let Some(mut imp) = current.take() {
                    imp.end = Some(k);
                    imp.duration = t[k] - t[imp.first];
                    out.impacts.push(imp);
                }
            }
        }
    }
    out.open = current;
    out
}

/// Mean and standard deviation (population) of `values`; (0, 0) if empty. The mean is
/// corrected by the mean of the residuals, and the deviation taken about it (not as
/// mean(v²) − mean², which cancels): equal values give their value and 0.
pub fn mean_and_deviation(values: &[f64]) -> (f64, f64) {
    if values.is_empty() {
        return (0.0, 0.0);
    }
    let n = values.len() as f64;
    let first = values.iter().sum::<f64>() / n;
    let mean = first + values.iter().map(|v| v - first).sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    (mean, var.sqrt())
}

/// One class of a histogram: [lower, upper] and the share of the values in it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Class {
    pub lower: f64,
    pub upper: f64,
    pub proba: f64,
}

/// The histogram of `values` in `classes` equal classes from their smallest to their
/// largest (Code_Aster's PROBA rows): value v falls in class ⌊(v − min)/Δ⌋ + 1, the last
/// class closed; all values in the first class when they are equal. No value: every class
/// [0, 0] with share 0.
pub fn histogram(values: &[f64], classes: usize) -> Vec<Class> {
    let classes = classes.max(1);
    if values.is_empty() {
        return vec![
            Class {
                lower: 0.0,
                upper: 0.0,
                proba: 0.0,
            };
            classes
        ];
    }
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let width = (hi - lo) / classes as f64;
    let mut counts = vec![0usize; classes];
    for v in values {
        let c = if width > 0.0 {
            // (v − lo)/width is finite and ≥ 0 here; the cast saturates.
            (((v - lo) / width) as usize).min(classes - 1)
        } else {
            0
        };
        counts[c] += 1;
    }
    let share = 1.0 / values.len() as f64;
    counts
        .iter()
        .enumerate()
        .map(|(i, &c)| Class {
            lower: lo + i as f64 * width,
            upper: lo + (i + 1) as f64 * width,
            proba: c as f64 * share,
        })
        .collect()
}

/// Mean, standard deviation, RMS and extremes (Code_Aster's MOYEN, ECART_TYPE, RMS, MAXI,
/// MINI).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Moments {
    pub mean: f64,
    pub deviation: f64,
    pub rms: f64,
    pub max: f64,
    pub min: f64,
}

fn moments(values: &[f64]) -> Moments {
    let (mean, deviation) = mean_and_deviation(values);
    let n = values.len().max(1) as f64;
    Moments {
        mean,
        deviation,
        rms: (values.iter().map(|v| v * v).sum::<f64>() / n).sqrt(),
        max: values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        min: values.iter().copied().fold(f64::INFINITY, f64::min),
    }
}

/// Blocks' moments combined: means averaged, deviations and RMS averaged in square.
fn combine(blocks: &[Moments]) -> Moments {
    let n = blocks.len().max(1) as f64;
    let avg = |f: &dyn Fn(&Moments) -> f64| blocks.iter().map(f).sum::<f64>() / n;
    Moments {
        mean: avg(&|m| m.mean),
        deviation: avg(&|m| m.deviation * m.deviation).sqrt(),
        rms: avg(&|m| m.rms * m.rms).sqrt(),
        max: blocks
            .iter()
            .map(|m| m.max)
            .fold(f64::NEG_INFINITY, f64::max),
        min: blocks.iter().map(|m| m.min).fold(f64::INFINITY, f64::min),
    }
}

/// FN's statistics (FORCE_NORMALE): over the whole time (T_TOTAL: sums over the samples
/// in contact divided by all the samples) and over the samples in contact (T_CHOC).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalForce {
    pub mean_total: f64,
    pub mean_contact: f64,
    pub rms_total: f64,
    pub rms_contact: f64,
    /// The largest FN in contact (0 if never in contact).
    pub max: f64,
}

fn normal_force(f_n: &[f64], threshold: f64) -> NormalForce {
    let on: Vec<f64> = f_n
        .iter()
        .copied()
        .filter(|f| f.abs() > threshold)
        .collect();
    let all = f_n.len().max(1) as f64;
    let hits = on.len() as f64;
    let (sum, sum2) = (
        on.iter().sum::<f64>(),
        on.iter().map(|f| f * f).sum::<f64>(),
    );
    let per_hit = |s: f64| if on.is_empty() { 0.0 } else { s / hits };
    NormalForce {
        mean_total: sum / all,
        mean_contact: per_hit(sum),
        rms_total: (sum2 / all).sqrt(),
        rms_contact: per_hit(sum2).sqrt(),
        max: on.iter().copied().fold(0.0, f64::max),
    }
}

/// Impact counts and durations (STAT_CHOC).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImpactCounts {
    /// NB_CHOC_S: impacts per second of the analysed time, truncated to an integer.
    pub per_second: i64,
    /// NB_REBON_CHOC: contacts per impact, integer division.
    pub contacts_per_impact: i64,
    /// T_CHOC_MOYEN, T_CHOC_MAXI, T_CHOC_MINI (0 without impact).
    pub duration_mean: f64,
    pub duration_max: f64,
    pub duration_min: f64,
    /// T_REBON_MOYEN: mean duration of a contact.
    pub contact_mean: f64,
    /// %_T_CHOC: share of the analysed time spent in impacts, in percent, truncated.
    pub percent_in_impact: i64,
}

/// The statistics of OPTION='USURE'.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wear {
    /// DEPL_X, DEPL_Y, DEPL_Z: DXLOC, DYLOC, DZLOC.
    pub displacement: [Moments; 3],
    /// DEPL_RADIAL: √(DYLOC² + DZLOC²).
    pub radial: Moments,
    /// DEPL_ANGULAIRE: atan2(DZLOC, DYLOC) in degrees (0 at the origin).
    pub angle: Moments,
    /// FORCE_NORMALE.
    pub normal: NormalForce,
    /// FORCE_TANG_1, FORCE_TANG_2.
    pub tangential: [Moments; 2],
    /// STAT_CHOC.
    pub counts: ImpactCounts,
    /// PUIS_USURE.
    pub wear_power: f64,
}

/// One shock's sampled history, every slice as long as `t` (strictly increasing).
#[derive(Clone, Copy, Debug)]
pub struct Series<'a> {
    pub t: &'a [f64],
    pub f_n: &'a [f64],
    pub f_t: [&'a [f64]; 2],
    pub v_n: &'a [f64],
    pub v_t: [&'a [f64]; 2],
    /// DXLOC, DYLOC, DZLOC.
    pub loc: [&'a [f64]; 3],
    /// The stick flag of each sample (VINT13: nonzero while sticking); `None` when the
    /// shock has no friction (nothing sticks).
    pub sticking: Option<&'a [f64]>,
}

/// Why the wear statistics cannot be computed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StatsError {
    /// Fewer than two samples per block.
    TooFewSamples { samples: usize, blocks: usize },
    /// The slices of the series differ in length.
    Lengths,
}

impl std::fmt::Display for StatsError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StatsError::TooFewSamples { samples, blocks } => write!(
                f,
                "{samples} archived instants in {blocks} block(s) leave fewer than 2 per block"
            ),
            StatsError::Lengths => write!(f, "the shock's histories differ in length"),
        }
    }
}

/// The wear power of one block: ∫|FN| |V_T| dt / (t_end − t_start), trapezoidal rule,
/// the intervals starting from a sticking sample left out (Code_Aster's `pusure`, its
/// order of operations).
fn wear_power(t: &[f64], f_n: &[f64], v_t: [&[f64]; 2], sticking: Option<&[f64]>) -> f64 {
    let p = |k: usize| (f_n[k] * (v_t[0][k] * v_t[0][k] + v_t[1][k] * v_t[1][k]).sqrt()).abs();
    let span = match (t.first(), t.last()) {
        (Some(a), Some(b)) if b > a => b - a,
        _ => return 0.0,
    };
    let sticks = |k: usize| sticking.is_some_and(|s| s[k] != 0.0);
    let sum: f64 = (1..t.len())
        .filter(|&k| !sticks(k - 1))
        .map(|k| (p(k) + p(k - 1)) * (t[k] - t[k - 1]))
        .sum();
    sum / 2.0 / span
}

/// The statistics of OPTION='USURE' over `blocks` blocks (NB_BLOC ≥ 1): each block's, then
/// averaged (means and powers), averaged in square (deviations, RMS), or their extreme;
/// counts summed. The samples beyond `blocks` × ⌊n/blocks⌋ are left out, as Code_Aster.
pub fn wear(s: &Series<'_>, threshold: f64, rest: f64, blocks: usize) -> Result<Wear, StatsError> {
    let n = s.t.len();
    let all = [s.f_n, s.f_t[0], s.f_t[1], s.v_n, s.v_t[0], s.v_t[1]];
    if all
        .iter()
        .chain(s.loc.iter())
        .chain(s.sticking.iter())
        .any(|x| x.len() != n)
    {
        return Err(StatsError::Lengths);
    }
    let blocks = blocks.max(1);
    let per = n / blocks;
    if per < 2 {
        return Err(StatsError::TooFewSamples { samples: n, blocks });
    }
    let radial: Vec<f64> = (0..n).map(|k| s.loc[1][k].hypot(s.loc[2][k])).collect();
    let angle: Vec<f64> = (0..n)
        .map(|k| {
            let (y, z) = (s.loc[1][k], s.loc[2][k]);
            if y == 0.0 && z == 0.0 {
                0.0
            } else {
                z.atan2(y).to_degrees()
            }
        })
        .collect();
    let ranges: Vec<std::ops::Range<usize>> = (0..blocks).map(|b| b * per..(b + 1) * per).collect();
    let stat = |x: &[f64]| -> Moments {
        combine(
            &ranges
                .iter()
                .map(|r| moments(&x[r.clone()]))
                .collect::<Vec<_>>(),
        )
    };
    let nb = blocks as f64;
    let forces: Vec<NormalForce> = ranges
        .iter()
        .map(|r| normal_force(&s.f_n[r.clone()], threshold))
        .collect();
    let normal = NormalForce {
        mean_total: forces.iter().map(|f| f.mean_total).sum::<f64>() / nb,
        mean_contact: forces.iter().map(|f| f.mean_contact).sum::<f64>() / nb,
        rms_total: (forces.iter().map(|f| f.rms_total.powi(2)).sum::<f64>() / nb).sqrt(),
        rms_contact: (forces.iter().map(|f| f.rms_contact.powi(2)).sum::<f64>() / nb).sqrt(),
        max: forces.iter().map(|f| f.max).fold(0.0, f64::max),
    };
    // Impacts and contacts, block by block.
    let (mut impacts, mut contacts) = (Vec::new(), Vec::new());
    for r in &ranges {
        let (t, f) = (&s.t[r.clone()], &s.f_n[r.clone()]);
        let d = detect(t, f, &s.v_n[r.clone()], threshold, rest);
        impacts.extend(d.impacts.iter().map(|i| i.duration));
        contacts.extend(d.contacts.iter().map(|c| t[c.end] - t[c.first]));
    }
    // The analysed time: the samples used times the mean step.
    let step = (s.t[n - 1] - s.t[0]) / (n - 1) as f64;
    let acquired = step * (blocks * per) as f64;
    let in_impact: f64 = impacts.iter().sum();
    let mean_of = |v: &[f64]| {
        if v.is_empty() {
            0.0
        } else {
            v.iter().sum::<f64>() / v.len() as f64
        }
    };
    let per_time = |x: f64| {
        if acquired > 0.0 {
            (x / acquired).floor() as i64
        } else {
            0
        }
    };
    let counts = ImpactCounts {
        per_second: per_time(impacts.len() as f64),
        contacts_per_impact: if impacts.is_empty() {
            0
        } else {
            (contacts.len() / impacts.len()) as i64
        },
        duration_mean: mean_of(&impacts),
        duration_max: impacts.iter().copied().fold(0.0, f64::max),
        duration_min: if impacts.is_empty() {
            0.0
        } else {
            impacts.iter().copied().fold(f64::INFINITY, f64::min)
        },
        contact_mean: mean_of(&contacts),
        percent_in_impact: per_time(100.0 * in_impact),
    };
    let wear_power = ranges
        .iter()
        .map(|r| {
            let r = r.clone();
            wear_power(
                &s.t[r.clone()],
                &s.f_n[r.clone()],
                [&s.v_t[0][r.clone()], &s.v_t[1][r.clone()]],
                s.sticking.map(|f| &f[r]),
            )
        })
        .sum::<f64>()
        / nb;
    Ok(Wear {
        displacement: [stat(s.loc[0]), stat(s.loc[1]), stat(s.loc[2])],
        radial: stat(&radial),
        angle: stat(&angle),
        normal,
        tangential: [stat(s.f_t[0]), stat(s.f_t[1])],
        counts,
        wear_power,
    })
}
