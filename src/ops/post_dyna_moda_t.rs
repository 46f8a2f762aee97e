//! POST_DYNA_MODA_T: impact and wear statistics of the shocks of a DYNA_VIBRA result
//! (CHOC, OPTION='IMPACT' or 'USURE'), in Code_Aster's table layout. The samples are the
//! result's shocks' table `<result>_CHOC` (store/tran_gene.rs); the statistics are
//! `transient::impact_stats`.

use super::common::tran_gene as common_tran_gene;
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::store::tran_gene::{self, StoredShock};
use crate::store::{table as table_store, Store};
use crate::table::{Cell, ColKind, Table};
use crate::transient::impact_stats::{self, Moments, Series};

/// Code_Aster's columns of OPTION='IMPACT', in its order.
const IMPACT_COLUMNS: &[(&str, ColKind)] = &[
    ("INTITULE", ColKind::K),
    ("NOEUD", ColKind::K),
    ("CALCUL", ColKind::K),
    ("CHOC", ColKind::I),
    ("INSTANT", ColKind::R),
    ("F_MAX", ColKind::R),
    ("IMPULSION", ColKind::R),
    ("T_CHOC", ColKind::R),
    ("V_IMPACT", ColKind::R),
    ("NB_IMPACT", ColKind::I),
    ("F_MAX_ABS", ColKind::R),
    ("F_MAX_MOY", ColKind::R),
    ("F_MAX_ETYPE", ColKind::R),
    ("CLASSE", ColKind::I),
    ("DEBUT", ColKind::R),
    ("FIN", ColKind::R),
    ("PROBA", ColKind::R),
];

/// Code_Aster's columns of OPTION='USURE', in its order.
const WEAR_COLUMNS: &[(&str, ColKind)] = &[
    ("INTITULE", ColKind::K),
    ("NOEUD", ColKind::K),
    ("CALCUL", ColKind::K),
    ("MOYEN", ColKind::R),
    ("ECART_TYPE", ColKind::R),
    ("RMS", ColKind::R),
    ("MAXI", ColKind::R),
    ("MINI", ColKind::R),
    ("MOYEN_T_TOTAL", ColKind::R),
    ("MOYEN_T_CHOC", ColKind::R),
    ("RMS_T_TOTAL", ColKind::R),
    ("RMS_T_CHOC", ColKind::R),
    ("NB_CHOC_S", ColKind::I),
    ("NB_REBON_CHOC", ColKind::I),
    ("T_CHOC_MOYEN", ColKind::R),
    ("T_CHOC_MAXI", ColKind::R),
    ("T_CHOC_MINI", ColKind::R),
    ("T_REBON_MOYEN", ColKind::R),
    ("%_T_CHOC", ColKind::I),
    ("PUIS_USURE", ColKind::R),
];

/// The columns of a shock's samples the statistics read.
const SAMPLES: [&str; 9] = [
    "FN", "FT1", "FT2", "VN", "VT1", "VT2", "DXLOC", "DYLOC", "DZLOC",
];

/// The stick flag of a shock with friction in `<result>_CHOC` (Code_Aster's VINT13), which
/// the wear power reads (impact_stats.rs); absent without friction.
const STICK_FLAG: &str = "VINT13";

/// The crush of a FLAMBAGE shock in `<result>_CHOC` (Code_Aster's DEFPLA), whose last
/// value and first positive instant are the FLAMBAGE row's ECRAS_RESI and INST_FLAMB.
const CRUSH: &str = "ECRAS_RESI";

/// Code_Aster's columns of a buckled shock's row (CALCUL='FLAMBAGE'), after IMPACT's.
const BUCKLING_COLUMNS: &[(&str, ColKind)] = &[
    ("FLAMBAGE", ColKind::K),
    ("ECRAS_RESI", ColKind::R),
    ("INST_FLAMB", ColKind::R),
];

/// One shock's archived samples: instants, the columns of [`SAMPLES`], the stick flag and
/// (FLAMBAGE) the crush.
struct History {
    t: Vec<f64>,
    cols: [Vec<f64>; 9],
    sticking: Option<Vec<f64>>,
    crush: Option<Vec<f64>>,
}

impl History {
    fn series(&self) -> Series<'_> {
        let c = &self.cols;
        Series {
            t: &self.t,
            f_n: &c[0],
            f_t: [&c[1], &c[2]],
            v_n: &c[3],
            v_t: [&c[4], &c[5]],
            loc: [&c[6], &c[7], &c[8]],
            sticking: self.sticking.as_deref(),
        }
    }

    /// The samples of [t0, t1] (the ends moved onto the archive when outside it).
    fn window(&self, t0: f64, t1: f64) -> History {
        let step = match (self.t.first(), self.t.last()) {
            (Some(a), Some(b)) if self.t.len() > 1 => (b - a) / (self.t.len() - 1) as f64,
            _ => 0.0,
        };
        // An instant a rounding of the file puts a hair off an archived one is that one.
        let slack = 1e-6 * step;
        let keep: Vec<usize> = (0..self.t.len())
            .filter(|&k| self.t[k] >= t0 - slack && self.t[k] <= t1 + slack)
            .collect();
        let pick = |v: &[f64]| keep.iter().map(|&k| v[k]).collect::<Vec<f64>>();
        History {
            t: pick(&self.t),
            cols: std::array::from_fn(|i| pick(&self.cols[i])),
            sticking: self.sticking.as_deref().map(pick),
            crush: self.crush.as_deref().map(pick),
        }
    }
}

/// The samples of every shock of `result`, by INTITULE: the DIS_CHOC shocks first, then
/// the FLAMBAGE ones, each in the payload's order (Code_Aster's order of the table).
fn histories(store: &Store, result: &str, kw: &str) -> Result<Vec<(StoredShock, History)>> {
    let no_shock = || {
        Error::input(format!(
            "{result} holds no shock history: POST_DYNA_MODA_T reads the shocks of a \
             DYNA_VIBRA result"
        ))
        .keyword(kw.to_string())
        .hint(
            "give the result of a DYNA_VIBRA with COMPORTEMENT (RELATION='DIS_CHOC' or \
             'FLAMBAGE'), CHOC or FLAMBAGE",
        )
    };
    // A result without a shocks' table: not a DYNA_VIBRA result, or one without shocks.
    if tran_gene::owned_concepts(store, result)?.is_empty() {
        return Err(no_shock());
    }
    let payload = tran_gene::load_payload(store, result)?;
    if payload.shocks.is_empty() {
        return Err(no_shock());
    }
    let t = common_tran_gene::shock_table(store, result, &payload)?;
    let mut out = Vec::with_capacity(payload.shocks.len());
    let (buckling, chocs): (Vec<StoredShock>, Vec<StoredShock>) = payload
        .shocks
        .into_iter()
        .partition(StoredShock::is_buckling);
    for shock in chocs.into_iter().chain(buckling) {
        let (times, cols) = common_tran_gene::shock_samples(&t, &shock.intitule, &SAMPLES)?;
        let sticking = match t.col(STICK_FLAG) {
            Some(_) => common_tran_gene::shock_samples(&t, &shock.intitule, &[STICK_FLAG])?
                .1
                .pop(),
            None => None,
        };
        let h = History {
            t: times,
            cols: cols
                .try_into()
                .map_err(|_| Error::internal("shock_samples returns one column per parameter"))?,
            sticking,
            crush: match t.col(CRUSH) {
                Some(_) if shock.is_buckling() => {
                    common_tran_gene::shock_samples(&t, &shock.intitule, &[CRUSH])?
                        .1
                        .pop()
                }
                _ => None,
            },
        };
        if h.t
            .iter()
            .chain(h.cols.iter().flatten())
            .chain(h.sticking.iter().flatten())
            .chain(h.crush.iter().flatten())
            .any(|x| !x.is_finite())
        {
            return Err(Error::store(format!(
                "the samples of shock '{}' in {result}'s shocks' table are not all numbers",
                shock.intitule
            )));
        }
        out.push((shock, h));
    }
    Ok(out)
}

/// The output table: its columns, added as the options need them.
struct Output {
    table: Table,
}

impl Output {
    fn with(&mut self, columns: &[(&str, ColKind)]) -> Result<()> {
        for (name, kind) in columns {
            if self.table.col(name).is_none() {
                self.table.add_column(name, *kind)?;
            }
        }
        Ok(())
    }

    /// A row from (column, value) pairs; the other cells empty.
    fn push(&mut self, shock: &StoredShock, calcul: &str, cells: &[(&str, Cell)]) -> Result<()> {
        let mut row = vec![Cell::Null; self.table.columns.len()];
        let head = [
            ("INTITULE", Cell::K(shock.intitule.clone())),
            ("NOEUD", Cell::K(shock.node1.clone())),
            ("CALCUL", Cell::K(calcul.to_string())),
        ];
        for (name, cell) in head.iter().chain(cells) {
            let j = self.table.req_col(name)?;
            row[j] = cell.clone();
        }
        self.table.push_row(row)
    }
}

/// The analysis of one CHOC occurrence: its parameters, as read.
struct Occurrence {
    t0: f64,
    t1: f64,
    threshold: f64,
    rest: f64,
    blocks: usize,
    classes: usize,
    wear: bool,
}

fn occurrence(occ: &Args) -> Result<Occurrence> {
    Ok(Occurrence {
        t0: occ.req_real("INST_INIT")?,
        t1: occ.req_real("INST_FIN")?,
        threshold: occ.req_real("SEUIL_FORCE")?,
        rest: occ.req_real("DUREE_REPOS")?,
        blocks: occ.req_count("NB_BLOC")?,
        classes: occ.req_count("NB_CLASSE")?,
        wear: occ.req_text("OPTION")? == "USURE",
    })
}

fn impact_rows(
    out: &mut Output,
    shock: &StoredShock,
    h: &History,
    o: &Occurrence,
) -> Result<usize> {
    out.with(IMPACT_COLUMNS)?;
    let s = h.series();
    let d = impact_stats::detect(s.t, s.f_n, s.v_n, o.threshold, o.rest);
    let rows: Vec<(i64, impact_stats::Impact)> = if d.impacts.is_empty() {
        // As Code_Aster: one row CHOC=0, with the impact still open if there is one.
        let open = d.open.map(|mut i| {
            i.contacts = 0;
            i
        });
        vec![(
            0,
            open.unwrap_or(impact_stats::Impact {
                first: 0,
                end: None,
                t_peak: 0.0,
                f_max: 0.0,
                impulse: 0.0,
                duration: 0.0,
                v_impact: 0.0,
                contacts: 0,
            }),
        )]
    } else {
        (1..).zip(d.impacts.iter().copied()).collect()
    };
    for (n, imp) in rows {
        out.push(
            shock,
            "IMPACT",
            &[
                ("CHOC", Cell::I(n)),
                ("INSTANT", Cell::R(imp.t_peak)),
                ("F_MAX", Cell::R(imp.f_max)),
                ("IMPULSION", Cell::R(imp.impulse)),
                ("T_CHOC", Cell::R(imp.duration)),
                ("V_IMPACT", Cell::R(imp.v_impact)),
                ("NB_IMPACT", Cell::I(imp.contacts as i64)),
            ],
        )?;
    }
    let peaks: Vec<f64> = d.impacts.iter().map(|i| i.f_max).collect();
    let (mean, dev) = impact_stats::mean_and_deviation(&peaks);
    out.push(
        shock,
        "GLOBAL",
        &[
            ("F_MAX_ABS", Cell::R(d.f_max_abs)),
            ("F_MAX_MOY", Cell::R(mean)),
            ("F_MAX_ETYPE", Cell::R(dev)),
        ],
    )?;
    for (c, class) in (1..).zip(impact_stats::histogram(&peaks, o.classes)) {
        out.push(
            shock,
            "PROBA",
            &[
                ("CLASSE", Cell::I(c)),
                ("DEBUT", Cell::R(class.lower)),
                ("FIN", Cell::R(class.upper)),
                ("PROBA", Cell::R(class.proba)),
            ],
        )?;
    }
    Ok(d.impacts.len())
}

/// OPTION='IMPACT', a FLAMBAGE shock buckled at the last instant analysed (crush > 0):
/// Code_Aster's row CALCUL='FLAMBAGE' (its `statim`): CHOC the shock's rank in the table,
/// FLAMBAGE='OUI', ECRAS_RESI the crush at that instant, INST_FLAMB the first archived
/// instant where the crush is positive (the step the element buckled, to the archive's
/// resolution). Between two nodes the crush is shared: half on each, one row per node.
fn buckling_rows(out: &mut Output, shock: &StoredShock, index: i64, h: &History) -> Result<()> {
    let Some(crush) = &h.crush else {
        return Ok(());
    };
    let Some(&last) = crush.last().filter(|&&c| c > 0.0) else {
        return Ok(());
    };
    let onset = crush.iter().position(|&c| c > 0.0).map_or(0.0, |k| h.t[k]);
    out.with(BUCKLING_COLUMNS)?;
    let mut rows = vec![(shock.node1.clone(), last)];
    if let Some(n2) = &shock.node2 {
        rows = vec![(shock.node1.clone(), last / 2.0), (n2.clone(), last / 2.0)];
    }
    for (node, ecras) in rows {
        let on_node = StoredShock {
            node1: node,
            ..shock.clone()
        };
        out.push(
            &on_node,
            "FLAMBAGE",
            &[
                ("CHOC", Cell::I(index)),
                ("FLAMBAGE", Cell::K("OUI".to_string())),
                ("ECRAS_RESI", Cell::R(ecras)),
                ("INST_FLAMB", Cell::R(onset)),
            ],
        )?;
    }
    Ok(())
}

fn moment_cells(m: &Moments) -> [(&'static str, Cell); 5] {
    [
        ("MOYEN", Cell::R(m.mean)),
        ("ECART_TYPE", Cell::R(m.deviation)),
        ("RMS", Cell::R(m.rms)),
        ("MAXI", Cell::R(m.max)),
        ("MINI", Cell::R(m.min)),
    ]
}

fn wear_rows(
    out: &mut Output,
    shock: &StoredShock,
    h: &History,
    o: &Occurrence,
    kw_blocks: &str,
) -> Result<()> {
    out.with(WEAR_COLUMNS)?;
    let w = impact_stats::wear(&h.series(), o.threshold, o.rest, o.blocks).map_err(|e| {
        Error::input(format!("shock '{}': {e}", shock.intitule))
            .keyword(kw_blocks.to_string())
            .hint("take fewer blocks, or a longer INST_INIT..INST_FIN")
    })?;
    let named = [
        ("DEPL_X", &w.displacement[0]),
        ("DEPL_Y", &w.displacement[1]),
        ("DEPL_Z", &w.displacement[2]),
        ("DEPL_RADIAL", &w.radial),
        ("DEPL_ANGULAIRE", &w.angle),
    ];
    for (calcul, m) in named {
        out.push(shock, calcul, &moment_cells(m))?;
    }
    let f = &w.normal;
    out.push(
        shock,
        "FORCE_NORMALE",
        &[
            ("MOYEN_T_TOTAL", Cell::R(f.mean_total)),
            ("MOYEN_T_CHOC", Cell::R(f.mean_contact)),
            ("RMS_T_TOTAL", Cell::R(f.rms_total)),
            ("RMS_T_CHOC", Cell::R(f.rms_contact)),
            ("MAXI", Cell::R(f.max)),
        ],
    )?;
    for (calcul, m) in [
        ("FORCE_TANG_1", &w.tangential[0]),
        ("FORCE_TANG_2", &w.tangential[1]),
    ] {
        out.push(shock, calcul, &moment_cells(m))?;
    }
    let c = &w.counts;
    out.push(
        shock,
        "STAT_CHOC",
        &[
            ("NB_CHOC_S", Cell::I(c.per_second)),
            ("NB_REBON_CHOC", Cell::I(c.contacts_per_impact)),
            ("T_CHOC_MOYEN", Cell::R(c.duration_mean)),
            ("T_CHOC_MAXI", Cell::R(c.duration_max)),
            ("T_CHOC_MINI", Cell::R(c.duration_min)),
            ("T_REBON_MOYEN", Cell::R(c.contact_mean)),
            ("%_T_CHOC", Cell::I(c.percent_in_impact)),
        ],
    )?;
    out.push(
        shock,
        "PUIS_USURE",
        &[("PUIS_USURE", Cell::R(w.wear_power))],
    )
}

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let name = ctx.result_name()?.to_string();
    let result = args.req_concept("RESU_GENE")?.name.clone();
    let shocks = histories(ctx.store, &result, &args.key_path("RESU_GENE"))?;
    let mut out = Output {
        table: Table::new(format!("POST_DYNA_MODA_T {name}: shocks of {result}")),
    };
    for occ in args.facts_or_empty("CHOC") {
        let o = occurrence(occ)?;
        for (index, (shock, all)) in (1..).zip(&shocks) {
            let h = all.window(o.t0, o.t1);
            if h.t.len() < 2 {
                return Err(Error::input(format!(
                    "fewer than two archived instants of {result} lie in [{:e}, {:e}]",
                    o.t0, o.t1
                ))
                .keyword(occ.key_path("INST_INIT"))
                .hint(format!(
                    "the result is archived from {:e} to {:e}",
                    all.t.first().copied().unwrap_or(0.0),
                    all.t.last().copied().unwrap_or(0.0)
                )));
            }
            let impacts = if o.wear {
                wear_rows(&mut out, shock, &h, &o, &occ.key_path("NB_BLOC"))?;
                None
            } else {
                let n = impact_rows(&mut out, shock, &h, &o)?;
                buckling_rows(&mut out, shock, index, &h)?;
                Some(n)
            };
            if ctx.info >= 2 {
                let what = impacts
                    .map(|n| format!(", {n} impact(s)"))
                    .unwrap_or_default();
                ctx.say(&format!(
                    "POST_DYNA_MODA_T: shock '{}' (node {}): {} archived instants from {:e} to {:e}{what}",
                    shock.intitule,
                    shock.node1,
                    h.t.len(),
                    h.t[0],
                    h.t[h.t.len() - 1]
                ))?;
            }
        }
    }
    ctx.create(&name, "table_sdaster")?;
    table_store::save_table(ctx.store, &name, &out.table)
}
