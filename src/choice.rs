//! Option enums spelled as words, and options built by chained setters.
//!
//! Every unit-only option enum (a boundary rule, a subdivision scheme, a
//! smoothing method) gets its words from one table through the crate-internal `choices!` macro:
//! `Display` writes the word, `FromStr` reads it, and `WORDS` lists them,
//! so the CLI and Python take the same words as Rust and neither restates
//! names or defaults.
//!
//! ```
//! use meshloom::algo::Keep;
//! assert_eq!("lock".parse::<Keep>()?, Keep::Lock);
//! assert_eq!(Keep::Slide.to_string(), "slide");
//! let err = "locked".parse::<Keep>().unwrap_err();
//! assert!(err.to_string().contains("free, slide, lock"));
//! # Ok::<(), meshloom::choice::UnknownChoice>(())
//! ```

use std::fmt;

/// A word that is not one of an option's words.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownChoice {
    /// The option's type, as Rust names it (`Keep`, `Scheme`).
    pub option: &'static str,
    /// The word given.
    pub given: String,
    /// The words it takes.
    pub choices: &'static [&'static str],
}

impl fmt::Display for UnknownChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "unknown {} '{}': expected one of {}",
            self.option,
            self.given,
            self.choices.join(", ")
        )
    }
}

impl std::error::Error for UnknownChoice {}

/// Whether `given` spells `word`: ASCII case and `_` for `-` are ignored,
/// so Python's `"catmull_clark"` reads as `"catmull-clark"`.
pub(crate) fn spells(given: &str, word: &str) -> bool {
    given.len() == word.len()
        && given
            .bytes()
            .zip(word.bytes())
            .all(|(g, w)| g.to_ascii_lowercase() == w || (g == b'_' && w == b'-'))
}

/// Give a unit-only enum its words: `WORDS`, `word()`, `Display` and
/// `FromStr` (error [`UnknownChoice`]).
///
/// ```ignore
/// choices!(Keep { Free = "free", Slide = "slide", Lock = "lock" });
/// ```
macro_rules! choices {
    ($ty:ident { $($variant:ident = $word:literal),+ $(,)? }) => {
        impl $ty {
            /// Every word this option takes, in declaration order.
            pub const WORDS: &'static [&'static str] = &[$($word),+];

            /// This value's word.
            pub fn word(&self) -> &'static str {
                match self {
                    $($ty::$variant => $word),+
                }
            }
        }

        impl ::core::fmt::Display for $ty {
            fn fmt(&self, f: &mut ::core::fmt::Formatter<'_>) -> ::core::fmt::Result {
                f.write_str(self.word())
            }
        }

        impl ::core::str::FromStr for $ty {
            type Err = $crate::choice::UnknownChoice;

            fn from_str(s: &str) -> ::core::result::Result<Self, Self::Err> {
                $(if $crate::choice::spells(s, $word) {
                    return Ok($ty::$variant);
                })+
                Err($crate::choice::UnknownChoice {
                    option: stringify!($ty),
                    given: s.to_owned(),
                    choices: Self::WORDS,
                })
            }
        }
    };
}
pub(crate) use choices;

/// Give an options struct one chainable setter per field: same name as
/// the field, taking `self` and returning `Self`, so that options (which
/// are `#[non_exhaustive]`) are built as
/// `SmoothOptions::default().iterations(3).boundary(Keep::Slide)`.
///
/// ```ignore
/// setters!(CurvatureOptions { boundary: BoundaryCurvature });
/// ```
macro_rules! setters {
    ($ty:ident { $($field:ident : $fty:ty),+ $(,)? }) => {
        impl $ty {
            $(
                #[doc = concat!("These options with [`", stringify!($field), "`](Self::", stringify!($field), ") set to `", stringify!($field), "`.")]
                #[must_use]
                pub fn $field(mut self, $field: $fty) -> Self {
                    self.$field = $field;
                    self
                }
            )+
        }
    };
}
pub(crate) use setters;

#[cfg(test)]
mod tests {
    use super::spells;

    #[test]
    fn words_ignore_case_and_underscores_but_not_length() {
        assert!(spells("catmull_clark", "catmull-clark"));
        assert!(spells("LOCK", "lock"));
        assert!(!spells("locked", "lock"));
        assert!(!spells("lock-", "lock"));
        assert!(!spells("lo-k", "lock"));
    }
}
