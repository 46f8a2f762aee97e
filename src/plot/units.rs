//! The SI unit of a quantity as Code_Aster names it (a table column, a field, a function's
//! parameter), for axis labels: `INST (s)`, `DEPL N2 DX (m)`. aster-nl computes in the
//! units of the data; these are the units of a model given in SI (the testcases, and
//! Code_Aster's examples), the only system the energy in J presumes.

/// The unit of `name` (column, field or parameter); `cmp` (DX, DRZ...) tells a rotation
/// from a translation. `None` for a name of no known unit (a count, a text).
pub fn unit(name: &str, cmp: Option<&str>) -> Option<&'static str> {
    let rotation = cmp.is_some_and(|c| c.starts_with("DR"));
    Some(match name {
        "INST" | "PERIODE" => "s",
        "FREQ" | "FREQUENCE" => "Hz",
        "PULS" | "PULSATION" => "rad/s",
        "ENERGIE" => "J",
        "DEPL" | "DX" | "DY" | "DZ" | "JEU" | "AMPLITUDE" if !rotation => "m",
        "DEPL" | "DRX" | "DRY" | "DRZ" => "rad",
        "VITE" if rotation => "rad/s",
        "VITE" => "m/s",
        "ACCE" if rotation => "rad/s²",
        "ACCE" => "m/s²",
        "FORCE" | "FORC" => "N",
        "RIGI_NOR" => "N/m",
        _ => return None,
    })
}

/// Whether `name` is a DOF component (DX .. DRZ), whose unit depends on the field.
pub fn is_component(name: &str) -> bool {
    matches!(name, "DX" | "DY" | "DZ" | "DRX" | "DRY" | "DRZ")
}

/// `label` followed by the unit of `name` in brackets when it has one.
pub fn with_unit(label: &str, name: &str, cmp: Option<&str>) -> String {
    let label = label.trim();
    match unit(name, cmp) {
        Some(u) => format!("{label} ({u})"),
        None => label.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_of_the_quantities_drawn() {
        assert_eq!(with_unit("INST", "INST", None), "INST (s)");
        assert_eq!(
            with_unit("DEPL N2 DX", "DEPL", Some("DX")),
            "DEPL N2 DX (m)"
        );
        assert_eq!(
            with_unit("DEPL N2 DRZ", "DEPL", Some("DRZ")),
            "DEPL N2 DRZ (rad)"
        );
        assert_eq!(
            with_unit("VITE N2 DX", "VITE", Some("DX")),
            "VITE N2 DX (m/s)"
        );
        assert_eq!(with_unit("FORCE", "FORCE", None), "FORCE (N)");
        assert_eq!(with_unit("FREQUENCE", "FREQUENCE", None), "FREQUENCE (Hz)");
        assert_eq!(with_unit("ENERGIE", "ENERGIE", None), "ENERGIE (J)");
        assert_eq!(with_unit("NUME_ORDRE", "NUME_ORDRE", None), "NUME_ORDRE");
    }
}
