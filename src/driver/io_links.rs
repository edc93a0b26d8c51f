//! The links a TwinCAT solution's I/O configuration makes between a PLC's
//! own outputs and inputs: in the `.tsproj`, `<Mappings>` holds, per pair
//! of owners, `<Link VarA="PlcTask Inputs^MAIN.fbPump.i_iTemp"
//! VarB="PlcTask Outputs^MAIN.q_iTemp"/>`. When both owners are the same
//! PLC instance the link is a loopback TwinCAT's test projects use to feed
//! a block's `AT %I*` input from a variable the test writes: at every
//! cycle the input takes the output's value of the cycle before. Links to
//! other devices (EtherCAT terminals) have no counterpart in plcrun and
//! are left out.

use super::project::{plcproj_of, solution};
use crate::address::IoLink;
use std::path::PathBuf;

/// The loopback links of the solutions of the TwinCAT projects among
/// `paths` (each `.plcproj`'s `.tsproj`, the folder above), in their
/// order; a solution read twice gives its links once.
pub fn project_io_links(paths: &[PathBuf]) -> Vec<IoLink> {
    let mut seen: Vec<PathBuf> = Vec::new();
    let mut links = Vec::new();
    for path in paths {
        let Some(tsproj) = plcproj_of(path).as_deref().and_then(solution) else {
            continue;
        };
        if seen.contains(&tsproj) {
            continue;
        }
        if let Ok(text) = std::fs::read_to_string(&tsproj) {
            links.extend(loopback_links(&text));
        }
        seen.push(tsproj);
    }
    links
}

/// The links of a `.tsproj`'s `<Mappings>` between an `OwnerA` and an
/// `OwnerB` of the same name, from a task's outputs to a task's inputs.
pub(crate) fn loopback_links(text: &str) -> Vec<IoLink> {
    let Ok(doc) = crate::syntax::plcopen::read_xml(text.trim_start_matches('\u{FEFF}')) else {
        return Vec::new();
    };
    let mut links = Vec::new();
    for mappings in doc.descendants().filter(|n| n.has_tag_name("Mappings")) {
        for a in mappings.children().filter(|n| n.has_tag_name("OwnerA")) {
            let owner = a.attribute("Name");
            for b in a.children().filter(|n| n.has_tag_name("OwnerB")) {
                if owner.is_none() || b.attribute("Name") != owner {
                    continue;
                }
                for link in b.children().filter(|n| n.has_tag_name("Link")) {
                    let (Some(x), Some(y)) = (link.attribute("VarA"), link.attribute("VarB"))
                    else {
                        continue;
                    };
                    match (side(x), side(y)) {
                        (Some((true, input)), Some((false, output)))
                        | (Some((false, output)), Some((true, input))) => links.push(IoLink {
                            input: input.to_string(),
                            output: output.to_string(),
                        }),
                        _ => {}
                    }
                }
            }
        }
    }
    links
}

/// A link end `Task Inputs^path` or `Task Outputs^path`: (input?, path).
fn side(end: &str) -> Option<(bool, &str)> {
    let (image, path) = end.split_once('^')?;
    let image = image.trim();
    let input = if image.ends_with("Inputs") {
        true
    } else if image.ends_with("Outputs") {
        false
    } else {
        return None;
    };
    let path = path.trim();
    (!path.is_empty()).then_some((input, path))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_links_within_one_plc_from_outputs_to_inputs_are_kept() {
        let text = r#"<TcSmProject><Mappings>
  <OwnerA Name="TIPC^Plc^Plc Instance">
    <OwnerB Name="TIPC^Plc^Plc Instance">
      <Link VarA="PlcTask Inputs^P.fbTest.fbPump.i_iTemp" VarB="PlcTask Outputs^P.fbTest.q_iTemp"/>
      <Link VarA="PlcTask Outputs^P.q_x" VarB="PlcTask Inputs^P.i_x"/>
      <Link VarA="PlcTask Inputs^P.a" VarB="PlcTask Inputs^P.b"/>
    </OwnerB>
    <OwnerB Name="TIID^Device 1 (EtherCAT)^Term 2 (EL1008)">
      <Link VarA="PlcTask Inputs^P.i_di" VarB="Channel 1^Input"/>
    </OwnerB>
  </OwnerA>
</Mappings></TcSmProject>"#;
        assert_eq!(
            loopback_links(text),
            [
                IoLink {
                    input: "P.fbTest.fbPump.i_iTemp".into(),
                    output: "P.fbTest.q_iTemp".into()
                },
                IoLink {
                    input: "P.i_x".into(),
                    output: "P.q_x".into()
                },
            ]
        );
        assert!(loopback_links("not xml").is_empty());
    }
}
