//! Counts as knitters write them: in digits (`3`) or in words (`three`), as in `[k1, p1]
//! three times`, `rep from * two more times`, `to last two sts` or `(six sts)`.

/// Number words up to twenty, the most a written pattern spells out.
const WORDS: [&str; 21] = [
    "zero",
    "one",
    "two",
    "three",
    "four",
    "five",
    "six",
    "seven",
    "eight",
    "nine",
    "ten",
    "eleven",
    "twelve",
    "thirteen",
    "fourteen",
    "fifteen",
    "sixteen",
    "seventeen",
    "eighteen",
    "nineteen",
    "twenty",
];

/// `s` (lower case, trimmed) read as a count: digits or a number word. `None` for anything
/// else, zero included where it is written in digits too (`0` and `zero` both read as 0; the
/// caller decides whether 0 means anything).
pub(in crate::pattern) fn count(s: &str) -> Option<usize> {
    let s = s.trim();
    if !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()) {
        return s.parse().ok();
    }
    WORDS.iter().position(|w| *w == s)
}

#[cfg(test)]
mod tests {
    use super::count;

    #[test]
    fn reads_digits_and_words_and_nothing_else() {
        assert_eq!(count("3"), Some(3));
        assert_eq!(count(" twelve "), Some(12));
        assert_eq!(count("twenty"), Some(20));
        assert_eq!(count("zero"), Some(0));
        assert_eq!(count("3x"), None);
        assert_eq!(count("-1"), None);
        assert_eq!(count("twentyone"), None);
        assert_eq!(count(""), None);
    }
}
