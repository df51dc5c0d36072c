//! Scene files the page has sent, kept under a short key: the page sends a file's text once
//! (`POST /api/keep`) and then names it in each view's address (`scene-key=KEY`), so that a file
//! of any size the command line accepts (up to its 1 MB) works in the explorer, whose addresses
//! are short. The most recently used [`MAX_KEPT`] files are kept, [`MAX_KEPT_BYTES`] in all; a
//! key forgotten is answered 410 and the page sends its text again.

use std::collections::VecDeque;
use std::hash::{BuildHasher, RandomState};
use std::sync::{Arc, Mutex};

/// Most scene files kept.
pub const MAX_KEPT: usize = 64;
/// Most bytes of scene files kept, in all.
pub const MAX_KEPT_BYTES: usize = 32 << 20;

/// The scene files kept, the most recently used last.
pub struct Kept {
    files: Mutex<VecDeque<(String, Arc<str>)>>,
    /// Two hashers keyed at random when the server starts: a key names one text, and no page can
    /// make up another text of the same key.
    hashers: (RandomState, RandomState),
}

impl Default for Kept {
    fn default() -> Kept {
        Kept {
            files: Mutex::new(VecDeque::new()),
            hashers: (RandomState::new(), RandomState::new()),
        }
    }
}

impl Kept {
    /// Keeps `text`; its key (the same key for the same text).
    pub fn keep(&self, text: &str) -> String {
        let key = format!(
            "{:016x}{:016x}",
            self.hashers.0.hash_one(text),
            self.hashers.1.hash_one(text)
        );
        let mut files = self.files.lock().unwrap_or_else(|e| e.into_inner());
        match files.iter().position(|(k, _)| *k == key) {
            Some(i) => {
                let file = files.remove(i).expect("a position found");
                files.push_back(file);
            }
            None => files.push_back((key.clone(), Arc::from(text))),
        }
        let mut total: usize = files.iter().map(|(_, t)| t.len()).sum();
        while files.len() > MAX_KEPT || (total > MAX_KEPT_BYTES && files.len() > 1) {
            let (_, oldest) = files.pop_front().expect("more than one");
            total -= oldest.len();
        }
        key
    }

    /// The text kept under `key`, if it still is.
    pub fn get(&self, key: &str) -> Option<Arc<str>> {
        let mut files = self.files.lock().unwrap_or_else(|e| e.into_inner());
        let i = files.iter().position(|(k, _)| k == key)?;
        let file = files.remove(i).expect("a position found");
        let text = Arc::clone(&file.1);
        files.push_back(file);
        Some(text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texts_are_kept_by_key_and_the_least_recently_used_forgotten() {
        let kept = Kept::default();
        let a = kept.keep("a");
        assert_eq!(kept.keep("a"), a);
        assert_eq!(a.len(), 32);
        let b = kept.keep("b");
        assert_ne!(a, b);
        assert_eq!(kept.get(&a).as_deref(), Some("a"));
        // "a" was used last: filling the store forgets "b" first.
        for k in 0..MAX_KEPT - 1 {
            kept.keep(&format!("file {k}"));
        }
        assert!(kept.get(&b).is_none());
        assert_eq!(kept.get(&a).as_deref(), Some("a"));
        assert!(kept.get("no such key").is_none());
    }

    #[test]
    fn kept_bytes_are_bounded() {
        let kept = Kept::default();
        let big = "x".repeat(MAX_KEPT_BYTES / 3 + 1);
        let first = kept.keep(&big);
        kept.keep(&(big.clone() + "y"));
        kept.keep(&(big.clone() + "z"));
        assert!(kept.get(&first).is_none());
    }
}
