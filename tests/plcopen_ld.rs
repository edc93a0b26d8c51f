//! LD bodies of PLCopen XML projects (issue #29, point 2): lowered to ST
//! by the importer, a ladder program runs like its hand-written ST twin on
//! random stimulus; edge contacts, edge coils, set/reset coils and a
//! seal-in rung follow traces derived by hand; malformed rungs get coded
//! diagnostics.

use crate::support::graphic;

use graphic::*;

const LD: &str = "tests/plcopen/ld_elements.xml";
const LD_OUTPUTS: &str = "motor,lamp,dark,pulse,fell,latched,up,down,ran,cnt,timed,skipped,mixed";

#[test]
fn every_ld_element_runs_like_its_st_twin() {
    for seed in [3, 4242, 77_777] {
        let stimulus = random_stimulus(&["start", "stop", "s1", "s2", "s3"], &[], 150, seed);
        let xml = trace_of(&[LD], LD_OUTPUTS, &stimulus, 150);
        let st = trace_of(
            &["tests/plcopen/ld_elements.st"],
            LD_OUTPUTS,
            &stimulus,
            150,
        );
        assert_same(&xml, &st, &format!("seed {seed}"));
        for name in [
            "motor", "pulse", "fell", "latched", "up", "down", "timed", "skipped", "mixed",
        ] {
            assert!(
                column(&xml, name).iter().any(|c| c == "TRUE"),
                "{name} never TRUE"
            );
        }
    }
}

/// The trace of the fixture's `names` for BOOL inputs given as bit strings.
fn ld_trace(inputs: &[(&str, &str)], names: &str) -> String {
    let stimulus = bit_stimulus(inputs);
    let cycles = inputs.iter().map(|c| c.1.len()).max().unwrap_or(0) as u64;
    trace_of(&[LD], names, &stimulus, cycles)
}

#[test]
fn edge_contacts_pass_power_for_one_cycle_on_a_transition() {
    let trace = ld_trace(&[("s3", "0110110"), ("s1", "0111001")], "pulse,fell");
    assert_eq!(bits(&trace, "pulse"), "0100100");
    assert_eq!(bits(&trace, "fell"), "0000100");
}

#[test]
fn edge_coils_write_one_cycle_on_a_transition_of_their_power() {
    let trace = ld_trace(&[("s2", "0110100")], "up,down");
    assert_eq!(bits(&trace, "up"), "0100100");
    assert_eq!(bits(&trace, "down"), "0001010");
}

#[test]
fn set_and_reset_coils_latch_and_the_lower_rung_wins() {
    // Set on s1 (upper rung), reset on s2 (lower rung): when both, reset.
    let trace = ld_trace(&[("s1", "0100010"), ("s2", "0001011")], "latched");
    assert_eq!(bits(&trace, "latched"), "0110000");
}

#[test]
fn a_seal_in_rung_holds_its_coil_through_a_parallel_branch() {
    let trace = ld_trace(&[("start", "0100000"), ("stop", "0000100")], "motor");
    assert_eq!(bits(&trace, "motor"), "0111000");
}

#[test]
fn a_jump_skips_the_rungs_up_to_its_label() {
    // skipped := s2 unless s3 jumps over the rung.
    let trace = ld_trace(&[("s2", "0100100"), ("s3", "0011000")], "skipped");
    assert_eq!(bits(&trace, "skipped"), "0111100");
}

/// A program `P` with an LD body.
fn ladder(elements: &[String]) -> String {
    let iface = format!(
        "{}{}{}",
        vars("inputVars", &["a", "b"]),
        vars("outputVars", &["q"]),
        vars("localVars", &["m"])
    );
    project(&graphic_pou("P", "program", &iface, "LD", elements))
}

fn rail() -> String {
    "<leftPowerRail localId=\"1\"><position x=\"0\" y=\"0\"/><connectionPointOut formalParameter=\"\"/></leftPowerRail>".to_string()
}

#[test]
fn malformed_rungs_get_coded_errors() {
    let floating = ladder(&[
        rail(),
        "<contact localId=\"2\"><position x=\"0\" y=\"0\"/><connectionPointIn/><connectionPointOut/><variable>a</variable></contact>".to_string(),
        format!("<coil localId=\"3\"><position x=\"0\" y=\"0\"/>{}<connectionPointOut/><variable>q</variable></coil>", point(&["2"])),
    ]);
    let found = errors(&floating);
    assert_eq!(found.len(), 1, "{found:#?}");
    assert_eq!(
        (found[0].0.as_str(), found[0].1.clone()),
        ("E818", location_of(&floating, "<contact"))
    );

    let nameless = ladder(&[
        rail(),
        format!(
            "<contact localId=\"2\"><position x=\"0\" y=\"0\"/>{}<connectionPointOut/><variable></variable></contact>",
            point(&["1"])
        ),
    ]);
    let found = errors(&nameless);
    assert_eq!(found.len(), 1, "{found:#?}");
    assert_eq!(
        (found[0].0.as_str(), found[0].1.clone()),
        ("E814", location_of(&nameless, "<contact"))
    );

    // A coil on something that is not a BOOL variable: the checker says so,
    // at the coil's variable.
    let wrong = ladder(&[
        rail(),
        format!(
            "<coil localId=\"2\"><position x=\"0\" y=\"0\"/>{}<connectionPointOut/><variable>T#1s</variable></coil>",
            point(&["1"])
        ),
    ]);
    let found = errors(&wrong);
    assert!(!found.is_empty(), "{found:#?}");
}

#[test]
fn a_coil_read_further_right_passes_its_power_on() {
    // m -> (/ m) -> ( q ): the power after the first coil is m as it was
    // before the coil toggled it, so q is 0, 1, 0, 1 (not 1, 0, 1, 0).
    let text = ladder(&[
        rail(),
        format!(
            "<contact localId=\"2\"><position x=\"0\" y=\"0\"/>{}<connectionPointOut/><variable>m</variable></contact>",
            point(&["1"])
        ),
        format!(
            "<coil localId=\"3\" negated=\"true\"><position x=\"0\" y=\"0\"/>{}<connectionPointOut/><variable>m</variable></coil>",
            point(&["2"])
        ),
        format!(
            "<coil localId=\"4\"><position x=\"10\" y=\"0\"/>{}<connectionPointOut/><variable>q</variable></coil>",
            point(&["3"])
        ),
    ]);
    let trace = trace_text(&text, "q", "", 4);
    assert_eq!(bits(&trace, "q"), "0101");
}

#[test]
fn each_instance_of_a_ladder_function_block_has_its_own_edge_memory() {
    // FUNCTION_BLOCK Edge (LD): x -|P|- ( q ). Two instances on two inputs.
    let edge = graphic_pou(
        "Edge",
        "functionBlock",
        &format!(
            "{}{}",
            vars("inputVars", &["x"]),
            vars("outputVars", &["q"])
        ),
        "LD",
        &[
            rail(),
            format!(
                "<contact localId=\"2\" edge=\"rising\"><position x=\"0\" y=\"0\"/>{}<connectionPointOut/><variable>x</variable></contact>",
                point(&["1"])
            ),
            format!(
                "<coil localId=\"3\"><position x=\"10\" y=\"0\"/>{}<connectionPointOut/><variable>q</variable></coil>",
                point(&["2"])
            ),
        ],
    );
    let main = format!(
        "<pou name=\"P\" pouType=\"program\"><interface>{}{}{}</interface><body><ST><xhtml:p>e1(x := a); e2(x := b); qa := e1.q; qb := e2.q;</xhtml:p></ST></body></pou>",
        vars("inputVars", &["a", "b"]),
        vars("outputVars", &["qa", "qb"]),
        vars("localVars", &["e1:Edge", "e2:Edge"])
    );
    let text = project(&format!("{edge}\n{main}"));
    let stimulus = bit_stimulus(&[("a", "01101"), ("b", "00110")]);
    let trace = trace_text(&text, "qa,qb", &stimulus, 5);
    assert_eq!(bits(&trace, "qa"), "01001");
    assert_eq!(bits(&trace, "qb"), "00100");
}
