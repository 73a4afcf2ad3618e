//! Tunings kept on disk ([`super::tuning`]), so that a new process skips the search another
//! process of the same build already ran: a farm rendering frame 120 alone, a scene opened
//! again, a second Blender. The search takes seconds to tens of seconds for a cable or lace
//! repeat on 2 cores; reading its result takes microseconds.
//!
//! A tuning is a pure function of its key (the pattern tuned and the quantised proportions)
//! and of the code that computes it, so a file written by one process is exactly what any
//! other process of the same build would compute: the output stays bit-identical whether the
//! store held the key or not. Each file names the build ([`BUILD`], a hash of the crate's
//! sources, made by `build.rs`) and holds the whole key as text; a file of another build,
//! another key (a hash collision), or one cut short or damaged is ignored and written anew.
//! Values are words ([`super::tuning`] writes each `f32` as its bits, never rounded through
//! decimals).
//!
//! Where: [`set_dir`] (the add-on gives each user's extension folder), else the
//! `KNITWEAR_TUNING_STORE` environment variable (a folder shared by a farm's nodes), else
//! nowhere (a library writes no files unless asked). Writing is best effort: a folder that
//! cannot be written costs only the time the store would have saved. A file appears whole or
//! not at all (written under a temporary name, then renamed), so processes may share a
//! folder.

use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};
use std::sync::RwLock;

/// The build the stored tunings were computed by: a hash of the crate's sources and lock
/// file (`build.rs`). A different build may tune differently, so it reads none of them.
pub const BUILD: &str = env!("KNITWEAR_SOURCE_HASH");

/// The environment variable naming the store's folder where [`set_dir`] names none.
pub const ENV_VAR: &str = "KNITWEAR_TUNING_STORE";

/// First line of every file: the format.
const MAGIC: &str = "knitwear tuning store 1";

/// The folder set by [`set_dir`]: `None` until set (then the environment decides), `Some(None)`
/// for no store.
static DIR: RwLock<Option<Option<PathBuf>>> = RwLock::new(None);

/// Sets the store's folder for this process (`None`: keep no tunings on disk), overriding
/// `KNITWEAR_TUNING_STORE`.
pub fn set_dir(dir: Option<PathBuf>) {
    if let Ok(mut d) = DIR.write() {
        *d = Some(dir);
    }
}

/// The store's folder: the one [`set_dir`] set, else `KNITWEAR_TUNING_STORE` (when set and
/// not empty), else `None`.
pub fn dir() -> Option<PathBuf> {
    if let Some(set) = DIR.read().ok().and_then(|d| d.clone()) {
        return set;
    }
    std::env::var_os(ENV_VAR)
        .filter(|v| !v.is_empty())
        .map(PathBuf::from)
}

/// The file of `key` (the tuning's cache key as text) in `dir`.
fn file_of(dir: &Path, key: &str) -> PathBuf {
    // Any hash will do: the file holds the key itself, which is checked.
    let mut h = std::collections::hash_map::DefaultHasher::new();
    BUILD.hash(&mut h);
    key.hash(&mut h);
    dir.join(format!("{:016x}.tuning", h.finish()))
}

/// The words stored for `key`, if the store has them, written by this build for exactly it.
pub fn load(key: &str) -> Option<Vec<u32>> {
    let dir = dir()?;
    let text = std::fs::read_to_string(file_of(&dir, key)).ok()?;
    decode(&text, key)
}

/// Stores `words` for `key`, best effort (see the module docs).
pub fn save(key: &str, words: &[u32]) {
    let Some(dir) = dir() else { return };
    if key.contains('\n') || std::fs::create_dir_all(&dir).is_err() {
        return;
    }
    let file = file_of(&dir, key);
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.subsec_nanos());
    let tmp = file.with_extension(format!("{}-{nanos}.partial", std::process::id()));
    if std::fs::write(&tmp, encode(key, words)).is_err() || std::fs::rename(&tmp, &file).is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
}

/// The file's text: the format, the build, the key, then the words in hexadecimal.
fn encode(key: &str, words: &[u32]) -> String {
    let value: Vec<String> = words.iter().map(|w| format!("{w:08x}")).collect();
    format!(
        "{MAGIC}\nbuild {BUILD}\nkey {key}\nvalue {}\n",
        value.join(" ")
    )
}

/// The words in `text` if it is a whole file of this build for exactly `key`.
fn decode(text: &str, key: &str) -> Option<Vec<u32>> {
    let mut lines = text.split('\n');
    if lines.next()? != MAGIC
        || lines.next()?.strip_prefix("build ")? != BUILD
        || lines.next()?.strip_prefix("key ")? != key
    {
        return None;
    }
    let words = lines
        .next()?
        .strip_prefix("value ")?
        .split(' ')
        .map(|w| {
            (w.len() == 8)
                .then(|| u32::from_str_radix(w, 16).ok())
                .flatten()
        })
        .collect::<Option<Vec<u32>>>()?;
    // Only the final newline may follow.
    if !lines.next()?.is_empty() || lines.next().is_some() {
        return None;
    }
    Some(words)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stored_words_read_back_and_nothing_else_does() {
        let words = [0x3f80_0000, 0, 0xdead_beef, 7];
        let text = encode("Key { a }", &words);
        assert_eq!(decode(&text, "Key { a }").as_deref(), Some(&words[..]));
        // Another key, another build, a cut, damaged or longer file: nothing.
        assert_eq!(decode(&text, "Key { b }"), None);
        assert_eq!(decode(&text.replace(BUILD, "other"), "Key { a }"), None);
        for cut in [1, 9, text.len() / 2, text.len() - 1] {
            assert_eq!(
                decode(&text[..text.len() - cut], "Key { a }"),
                None,
                "{cut}"
            );
        }
        assert_eq!(
            decode(&text.replacen("value ", "value x", 1), "Key { a }"),
            None
        );
        let longer = format!("{}\nmore\n", text.trim_end());
        assert_eq!(decode(&longer, "Key { a }"), None);
    }
}
