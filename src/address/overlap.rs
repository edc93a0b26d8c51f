//! Which located addresses share bytes of the image under a convention:
//! the checker warns of each (W231), since two variables of different
//! sizes on the same bytes usually mean a program written for another
//! convention (`%QX0.0` beside `%QW0` is OpenPLC's habit, a conflict
//! under `iec`).

use super::{Addressing, ImageSpot, IoAddress};

/// For each address of `addresses` (in their order) that shares bits with
/// an earlier one under `addressing`: its index, the first earlier one it
/// overlaps, and how many earlier ones it overlaps in all. Two spellings
/// of the same place (`%IX0.1`, `%I0.0.0.0.1`) are not an overlap, nor
/// are addresses that have no place in the image.
pub fn overlapping(addresses: &[IoAddress], addressing: Addressing) -> Vec<(usize, usize, usize)> {
    let spots: Vec<Option<ImageSpot>> = addresses.iter().map(|a| addressing.spot(a).ok()).collect();
    // By table and first byte, so that each address meets only those
    // starting within the widest size (8 bytes) before it.
    let mut order: Vec<usize> = (0..spots.len()).filter(|&i| spots[i].is_some()).collect();
    order.sort_by_key(|&i| spots[i].map(|s| (s.table.index(), s.byte)));
    let mut found: Vec<(usize, usize, usize)> = Vec::new();
    for (k, &j) in order.iter().enumerate() {
        let Some(sj) = spots[j] else { continue };
        let mut first: Option<usize> = None;
        let mut count = 0;
        let mut visit = |i: usize| {
            let Some(si) = spots[i] else { return };
            if i < j && si != sj && si.overlaps(&sj) {
                count += 1;
                first = Some(first.map_or(i, |f: usize| f.min(i)));
            }
        };
        for &i in order[..k].iter().rev() {
            let si = spots[i].unwrap_or(sj);
            if si.table != sj.table || si.byte + 8 <= sj.byte {
                break;
            }
            visit(i);
        }
        for &i in &order[k + 1..] {
            let si = spots[i].unwrap_or(sj);
            if si.table != sj.table || si.byte >= sj.end() {
                break;
            }
            visit(i);
        }
        if let Some(i) = first {
            found.push((j, i, count));
        }
    }
    found.sort_unstable();
    found
}

#[cfg(test)]
mod tests {
    use super::super::parse;
    use super::*;

    fn pairs(texts: &[&str], addressing: Addressing) -> Vec<(usize, usize, usize)> {
        let addresses: Vec<IoAddress> = texts.iter().map(|t| parse(t).unwrap()).collect();
        overlapping(&addresses, addressing)
    }

    #[test]
    fn openplc_style_declarations_overlap_under_iec_only() {
        let texts = ["%QX0.0", "%QX0.1", "%QW0", "%QW1", "%MW0", "%MD0"];
        // %QW0 covers %QX0.0 and %QX0.1; %MD0 covers %MW0.
        assert_eq!(pairs(&texts, Addressing::Iec), vec![(2, 0, 2), (5, 4, 1)]);
        assert_eq!(pairs(&texts, Addressing::OpenPlc), vec![]);
        // Under byte, %QW1 (bytes 1-2) also meets %QW0.
        assert_eq!(
            pairs(&texts, Addressing::Byte),
            vec![(2, 0, 2), (3, 2, 1), (5, 4, 1)]
        );
    }

    #[test]
    fn a_bit_declared_after_its_byte_names_the_byte() {
        assert_eq!(
            pairs(&["%QB0", "%QX0.3", "%QX1.0"], Addressing::Iec),
            vec![(1, 0, 1)]
        );
    }

    #[test]
    fn two_spellings_of_one_place_are_not_an_overlap() {
        assert_eq!(
            pairs(&["%IX0.1", "%I0.0.0.0.1", "%IX1"], Addressing::Iec),
            vec![]
        );
    }

    #[test]
    fn far_apart_addresses_do_not_meet_even_in_a_long_list() {
        let texts: Vec<String> = (0..200).map(|n| format!("%MD{n}")).collect();
        let refs: Vec<&str> = texts.iter().map(String::as_str).collect();
        assert_eq!(pairs(&refs, Addressing::Iec), vec![]);
        // Under byte, each %MDn meets the three before it.
        let found = pairs(&refs, Addressing::Byte);
        assert_eq!(found.len(), 199);
        assert_eq!(found[10], (11, 8, 3));
    }
}
