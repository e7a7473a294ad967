//! Every option enum reads back the words it writes, and refuses others
//! with the list of its words.

use meshloom::algo::laplacian::LaplaceWeights;
use meshloom::algo::Keep;
use meshloom::io::gltf::GltfEncoding;
use meshloom::io::{Format, PlyEncoding, StlEncoding};
use meshloom::shapes::GridFaces;
use std::fmt::Display;
use std::str::FromStr;

fn round_trips<T>(words: &[&str])
where
    T: FromStr<Err = meshloom::choice::UnknownChoice> + Display + PartialEq + std::fmt::Debug,
{
    assert!(!words.is_empty());
    for w in words {
        let v: T = w.parse().unwrap();
        assert_eq!(&v.to_string(), w);
        assert_eq!(
            w.to_ascii_uppercase()
                .replace('-', "_")
                .parse::<T>()
                .unwrap(),
            v
        );
    }
    let err = "no-such-word".parse::<T>().unwrap_err();
    assert_eq!(err.given, "no-such-word");
    assert_eq!(err.choices, words);
    assert!(err.to_string().contains(&words.join(", ")), "{err}");
}

#[test]
fn every_option_enum_reads_back_its_words() {
    round_trips::<Keep>(Keep::WORDS);
    round_trips::<LaplaceWeights>(LaplaceWeights::WORDS);
    round_trips::<Format>(Format::WORDS);
    round_trips::<GltfEncoding>(GltfEncoding::WORDS);
    round_trips::<PlyEncoding>(PlyEncoding::WORDS);
    round_trips::<StlEncoding>(StlEncoding::WORDS);
    round_trips::<GridFaces>(GridFaces::WORDS);
}

#[test]
fn words_are_distinct_and_lower_case() {
    for words in [
        Keep::WORDS,
        LaplaceWeights::WORDS,
        Format::WORDS,
        PlyEncoding::WORDS,
        GridFaces::WORDS,
    ] {
        for (i, a) in words.iter().enumerate() {
            assert_eq!(a.to_ascii_lowercase(), *a);
            assert!(words[i + 1..].iter().all(|b| a != b));
        }
    }
}
