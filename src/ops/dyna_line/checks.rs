//! What DYNA_LINE refuses by name before computing anything (docs/dyna_vibra.md,
//! "DYNA_LINE": the departures).

use crate::args::Args;
use crate::error::{Error, Result};

/// What is refused, by name, before anything is computed.
pub(super) fn refuse_unsupported(args: &Args) -> Result<()> {
    if args.text("TYPE_CALCUL") == Some("HARM") {
        return Err(Error::validation("harmonic responses are not computed")
            .keyword("DYNA_LINE/TYPE_CALCUL")
            .hint("TYPE_CALCUL='TRAN' (a transient) is what DYNA_LINE runs here"));
    }
    if args.has("FREQ_COUP_STAT") {
        return Err(Error::validation(
            "a cutoff of the reduced modes is not applied: ORTHO='OUI' keeps every mode of the reduced problem",
        )
        .keyword("DYNA_LINE/FREQ_COUP_STAT")
        .hint("drop FREQ_COUP_STAT"));
    }
    let gene = args.text("BASE_CALCUL") == Some("GENE");
    if let Some(a) = args.fact("AMORTISSEMENT") {
        if a.text("TYPE_AMOR") == Some("MODAL") {
            if !gene {
                return Err(Error::validation("modal damping needs a modal basis")
                    .keyword("DYNA_LINE/AMORTISSEMENT/TYPE_AMOR")
                    .hint("BASE_CALCUL='GENE', or TYPE_AMOR='RAYLEIGH'"));
            }
            if !a.has("AMOR_REDUIT") {
                return Err(
                    Error::validation("TYPE_AMOR='MODAL' needs the damping ratios")
                        .keyword("DYNA_LINE/AMORTISSEMENT/AMOR_REDUIT"),
                );
            }
        }
    }
    for occ in args.facts_or_empty("EXCIT") {
        let key = |k: &str| occ.key_path(k);
        if occ.has("FREQ") {
            return Err(
                Error::validation("FREQ belongs to harmonic responses").keyword(key("FREQ"))
            );
        }
        match occ.text("TYPE_APPUI") {
            Some("MULTI") => {
                return Err(Error::validation(
                    "multi-support excitation is not run by DYNA_LINE",
                )
                .keyword(key("TYPE_APPUI"))
                .hint("run the chain yourself: MODE_STATIQUE (MODE_STAT), CALC_CHAR_SEISME, PROJ_BASE, DYNA_VIBRA with EXCIT MULT_APPUI='OUI' (docs/dyna_vibra.md, \"Moving supports\")"))
            }
            Some(_) => {
                for k in ["GROUP_NO", "NOEUD", "ACCE", "VITE", "DEPL", "CHARGE"] {
                    if occ.has(k) {
                        return Err(Error::validation(
                            "TYPE_APPUI='MONO' is run as every support accelerated together, by FONC_MULT along DIRECTION",
                        )
                        .keyword(key(k))
                        .hint("give the acceleration as FONC_MULT and drop this keyword"));
                    }
                }
                let d = occ.reals("DIRECTION").unwrap_or_default();
                if d.len() != 3 {
                    return Err(Error::validation(format!(
                        "expected the three translations of the direction, got {} value(s)",
                        d.len()
                    ))
                    .keyword(key("DIRECTION")));
                }
                if !occ.has("FONC_MULT") {
                    return Err(Error::validation("expected the support acceleration")
                        .keyword(key("FONC_MULT")));
                }
            }
            None => {
                for (k, what) in [("CHARGE", "the load"), ("FONC_MULT", "its function of time")] {
                    if !occ.has(k) {
                        return Err(Error::validation(format!(
                            "without TYPE_APPUI, EXCIT is a load times a function: expected {what}"
                        ))
                        .keyword(key(k)));
                    }
                }
                for k in ["DIRECTION", "GROUP_NO", "NOEUD", "ACCE", "VITE", "DEPL"] {
                    if occ.has(k) {
                        return Err(Error::validation("this keyword goes with TYPE_APPUI")
                            .keyword(key(k)));
                    }
                }
            }
        }
    }
    Ok(())
}
