//! A row whose whole body says to work another row again: `Row 4: Rep row 2.`, `Rnd 3:
//! Repeat rnd 1.`, `Row 6: Work as row 2.`, `Row 5: Same as row 1.`. Written patterns say
//! so rather than write a row out twice; the row is worked with the named row's instructions
//! on its own side, as a knitter works it.

use super::numbers;

/// The row number `body` refers to, if the body is only such a reference (any case, an
/// optional full stop).
pub(super) fn same_as(body: &str) -> Option<usize> {
    let lower = body.trim().trim_end_matches('.').trim().to_lowercase();
    let rest = [
        "repeat ",
        "rep ",
        "work as for ",
        "work as ",
        "work same as ",
        "same as ",
    ]
    .iter()
    .find_map(|p| lower.strip_prefix(p))?;
    let rest = rest.trim_start_matches("for ").trim();
    let number = ["row ", "rnd ", "round "]
        .iter()
        .find_map(|p| rest.strip_prefix(p))?
        .trim();
    if number.starts_with(|c: char| c.is_ascii_digit()) {
        number.parse().ok()
    } else {
        numbers::count(number)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_body_that_names_another_row_is_read_as_its_number() {
        for (text, row) in [
            ("Rep row 2.", 2),
            ("Repeat Rnd 1", 1),
            ("Work as row 12.", 12),
            ("work as for row 3", 3),
            ("Same as Row 1.", 1),
            ("Rep round two.", 2),
        ] {
            assert_eq!(same_as(text), Some(row), "{text}");
        }
    }

    #[test]
    fn stitches_and_other_repeats_are_no_reference() {
        for text in [
            "K2, p2.",
            "rep from * to end",
            "Repeat rows 1-4.",
            "rep row",
            "Knit.",
        ] {
            assert_eq!(same_as(text), None, "{text}");
        }
    }
}
