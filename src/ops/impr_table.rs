//! IMPR_TABLE: print a table (FORMAT 'TABLEAU', 'ASTER', 'CSV', 'TABLEAU_CROISE' or
//! 'XMGRACE') after FILTRE, TRI and NOM_PARA; TITRE replaces the table's title.
//! FORMAT='PNG' | 'SVG' (aster-nl) draws it instead: see [`draw`].

use super::common::output::write_unit;
use super::common::plot_args::{picture, Picture};
use super::common::table_args::{apply_tri, filters_for, load_table_arg, titre};
use super::OpContext;
use crate::args::Args;
use crate::error::{Error, Result};
use crate::plot::tables::{
    columns_plot, fe_points, histories, is_mode_non_line, is_time_history, HISTORY_COLUMNS,
    MODE_NON_LINE_COLUMNS,
};
use crate::plot::{
    frequency_energy_spec, phase_portrait_spec, stacked, time_history_specs, xy_plot, HISTORY_SIZE,
};
use crate::table::cross::cross;
use crate::table::filter::apply_all;
use crate::table::print::{aster, csv, grace, tableau, FormatR};
use crate::table::Table;
use crate::value::ConceptRef;

pub fn run(ctx: &mut OpContext<'_>, args: &Args) -> Result<()> {
    let (c, t) = load_table_arg(ctx, args, "TABLE")?;
    let mut t = apply_all(&t, &filters_for(ctx, &t, args, "FILTRE")?)?;
    if let Some(tri) = args.fact("TRI") {
        apply_tri(&mut t, tri)?;
    }
    if let Some(pic) = picture(ctx, args)? {
        return draw(ctx, args, &pic, &c, &t);
    }
    if let Some(names) = args.texts("NOM_PARA") {
        t = t
            .extract(&names)
            .map_err(|e| e.keyword("IMPR_TABLE/NOM_PARA"))?;
    }
    // Defaults are the catalog's (commands/IMPR_TABLE.toml), filled by the validation
    // (SEPARATEUR too: ',' for CSV, ' ' for the text formats, as Code_Aster's TABLEAU).
    let fmt = FormatR::parse(args.req_text("FORMAT_R")?)?;
    let format = args.req_text("FORMAT")?;
    let separateur = args.req_text("SEPARATEUR")?;
    let title = match titre(args) {
        Some(titre) => titre,
        None if t.title.is_empty() => {
            format!("ASTER CONCEPT {} DE TYPE {}", c.name, c.ty.to_uppercase())
        }
        None => t.title.clone(),
    };
    let text = match format {
        "TABLEAU" => tableau(&t, &title, fmt, separateur),
        "ASTER" => aster(&t, &title, fmt, separateur),
        "CSV" => csv(&t, fmt, separateur),
        "TABLEAU_CROISE" => {
            let Some(crossed) = cross(&t, fmt) else {
                // As Code_Aster: an alarm, and nothing printed.
                return ctx.alarm(
                    "TABLE0_36",
                    &format!(
                        "FORMAT='TABLEAU_CROISE' needs a table of three parameters (P1, P2, \
                         P3), {} has {}: nothing printed; choose them with NOM_PARA",
                        c.name,
                        t.columns.len()
                    ),
                );
            };
            let title = titre(args).unwrap_or_else(|| crossed.title.clone());
            tableau(&crossed, &title, fmt, separateur)
        }
        "XMGRACE" => {
            if t.columns.len() != 2 {
                return ctx.alarm(
                    "TABLE0_21",
                    &format!(
                        "FORMAT='XMGRACE' draws two columns, {} has {}: nothing written; \
                         choose them with NOM_PARA=(x, y)",
                        c.name,
                        t.columns.len()
                    ),
                );
            }
            grace(&t, &title, fmt).map_err(|e| e.keyword("IMPR_TABLE/NOM_PARA"))?
        }
        other => {
            // NUMPY and AGRAF: output for other programs that aster-nl does not write. A
            // print never stops the study: the table stays in the database.
            return ctx.alarm(
                "IMPR_TABLE_1",
                &format!(
                    "FORMAT='{other}' is not written by aster-nl: {} was not printed; it \
                     stays in the database (query it with SQL), or print it with \
                     FORMAT='TABLEAU', 'ASTER', 'CSV' or 'PNG'",
                    c.name
                ),
            );
        }
    };
    let unite = args.req_int("UNITE")?;
    write_unit(ctx, unite, &text)
}

/// The picture of a table. NOM_PARA=(x, y, ...) draws columns against a column; without
/// it, a MODE_NON_LINE table gives its frequency–energy plot and a time-history table the
/// displacement and velocity of one node component (COURBE='PHASE': the phase portrait).
fn draw(
    ctx: &mut OpContext<'_>,
    args: &Args,
    pic: &Picture,
    c: &ConceptRef,
    t: &Table,
) -> Result<()> {
    let kw = |k: &str| args.key_path(k);
    let kind = match (args.text("COURBE"), args.texts("NOM_PARA")) {
        (Some(k), _) => k.to_string(),
        (None, Some(_)) => "COLONNES".into(),
        (None, None) if is_mode_non_line(t) => "FREQ_ENER".into(),
        (None, None) if is_time_history(t) => "TEMPS".into(),
        (None, None) => {
            return Err(
                Error::validation(format!("which columns of {} should be drawn?", c.name))
                    .keyword(kw("NOM_PARA"))
                    .hint("give NOM_PARA=(x, y, ...): the abscissa then the ordinates"),
            )
        }
    };
    let title = if t.title.is_empty() {
        c.name.clone()
    } else {
        t.title.clone()
    };
    let summary = match kind.as_str() {
        "FREQ_ENER" => {
            if !is_mode_non_line(t) {
                return Err(not_a(
                    c,
                    "MODE_NON_LINE",
                    &MODE_NON_LINE_COLUMNS,
                    kw("COURBE"),
                ));
            }
            let mut spec = frequency_energy_spec(&fe_points(t)?, &title);
            pic.apply(&mut spec);
            xy_plot(&spec, &pic.path, pic.format)?
        }
        "TEMPS" | "PHASE" => {
            if !is_time_history(t) {
                return Err(not_a(c, "time history", &HISTORY_COLUMNS, kw("COURBE")));
            }
            // A dyna_trans numbers its instants with NUME_ORDRE: its rows are one orbit,
            // one curve (a table of several rows' histories has one curve per NUME_ORDRE).
            let one_orbit;
            let t = if c.ty == "dyna_trans" {
                let keep: Vec<String> = t
                    .columns
                    .iter()
                    .map(|col| col.name.clone())
                    .filter(|n| n != "NUME_ORDRE")
                    .collect();
                one_orbit = t.extract(&keep)?;
                &one_orbit
            } else {
                t
            };
            let (curves, what) = histories(t, args.text("NOEUD"), args.text("NOM_CMP"))
                .map_err(|e| e.keyword(kw("NOEUD")))?;
            if kind == "PHASE" {
                let mut spec = phase_portrait_spec(&curves, &title, &what);
                pic.apply(&mut spec);
                xy_plot(&spec, &pic.path, pic.format)?
            } else {
                let [mut depl, mut vite] = time_history_specs(&curves, &title, &what);
                // TITRE goes on top; the x options apply to both panels, which share INST.
                if let Some(tt) = &pic.title {
                    depl.title = tt.clone();
                }
                pic.apply_x(&mut depl);
                pic.apply_x(&mut vite);
                stacked(&[&depl, &vite], HISTORY_SIZE, &pic.path, pic.format)?
            }
        }
        _ => {
            let names = args.texts("NOM_PARA").unwrap_or_default();
            let Some((x, ys)) = names.split_first() else {
                return Err(
                    Error::validation("COURBE='COLONNES' needs NOM_PARA=(x, y, ...)")
                        .keyword(kw("NOM_PARA")),
                );
            };
            let mut spec = columns_plot(t, x, ys).map_err(|e| e.keyword(kw("NOM_PARA")))?;
            spec.title = title;
            pic.apply(&mut spec);
            xy_plot(&spec, &pic.path, pic.format)?
        }
    };
    pic.report(ctx, &summary)
}

fn not_a(c: &ConceptRef, what: &str, cols: &[&str], key: String) -> Error {
    Error::input(format!("{} is not a {what} table", c.name))
        .keyword(key)
        .hint(format!(
            "that picture needs the columns {}",
            cols.join(", ")
        ))
}
