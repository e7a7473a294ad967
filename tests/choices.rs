//! Every option enum reads back the words it writes, and refuses others
//! with the list of its words.

use meshloom::algo::curvature::BoundaryCurvature;
use meshloom::algo::decimate::StopReason;
use meshloom::algo::fair::FairRegion;
use meshloom::algo::laplacian::LaplaceWeights;
use meshloom::algo::normals::NormalWeight;
use meshloom::algo::smooth::SmoothMethod;
use meshloom::algo::subdivision::{Boundary, MidpointFaces, VertexInterpolation};
use meshloom::algo::{Keep, Scheme};
use meshloom::buffers::{ColumnSource, IndexWidth, Weld};
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
    round_trips::<SmoothMethod>(SmoothMethod::WORDS);
    round_trips::<NormalWeight>(NormalWeight::WORDS);
    round_trips::<BoundaryCurvature>(BoundaryCurvature::WORDS);
    round_trips::<IndexWidth>(IndexWidth::WORDS);
    round_trips::<ColumnSource>(ColumnSource::WORDS);
    round_trips::<StopReason>(StopReason::WORDS);
    round_trips::<Scheme>(Scheme::WORDS);
    round_trips::<Boundary>(Boundary::WORDS);
    round_trips::<MidpointFaces>(MidpointFaces::WORDS);
    round_trips::<VertexInterpolation>(VertexInterpolation::WORDS);
}

#[test]
fn the_new_words_name_the_variants() {
    assert_eq!(
        SmoothMethod::WORDS,
        ["uniform", "cotan", "taubin", "implicit"]
    );
    assert_eq!("taubin".parse::<SmoothMethod>(), Ok(SmoothMethod::Taubin));
    assert_eq!(SmoothMethod::default().word(), "uniform");
    assert_eq!(NormalWeight::WORDS, ["angle", "area", "uniform"]);
    assert_eq!("area".parse::<NormalWeight>(), Ok(NormalWeight::Area));
    assert_eq!(NormalWeight::default().word(), "angle");
    assert_eq!(
        "one_sided".parse::<BoundaryCurvature>(),
        Ok(BoundaryCurvature::OneSided)
    );
    assert_eq!(BoundaryCurvature::default().word(), "from-interior");
    assert_eq!("u32".parse::<IndexWidth>(), Ok(IndexWidth::U32));
    assert_eq!(IndexWidth::default().word(), "auto");
    assert_eq!("corner".parse::<ColumnSource>(), Ok(ColumnSource::Corner));
    assert_eq!(StopReason::MaxError.word(), "max-error");
}

/// The enums that carry data: `Weld` is spelled `exact` or by its
/// tolerance; `FairRegion` reads only `all`.
#[test]
fn data_carrying_enums_read_their_words() {
    assert_eq!("exact".parse::<Weld>(), Ok(Weld::Exact));
    assert_eq!("EXACT".parse::<Weld>(), Ok(Weld::Exact));
    assert_eq!("0.25".parse::<Weld>(), Ok(Weld::Tolerance(0.25)));
    assert_eq!("0".parse::<Weld>(), Ok(Weld::Tolerance(0.0)));
    for w in [Weld::Exact, Weld::Tolerance(1e-3)] {
        assert_eq!(w.to_string().parse::<Weld>(), Ok(w));
    }
    for bad in ["-1", "nan", "inf", "loose", ""] {
        let err = bad.parse::<Weld>().unwrap_err();
        assert_eq!(err.option, "Weld");
        assert!(err.to_string().contains("exact"), "{err}");
    }
    assert_eq!(Weld::WORDS, ["exact"]);
    assert_eq!("all".parse::<FairRegion>(), Ok(FairRegion::All));
    assert_eq!("ALL".parse::<FairRegion>(), Ok(FairRegion::All));
    let err = "mask".parse::<FairRegion>().unwrap_err();
    assert_eq!(err.choices, FairRegion::WORDS);
}

#[test]
fn words_are_distinct_and_lower_case() {
    for words in [
        Keep::WORDS,
        LaplaceWeights::WORDS,
        Format::WORDS,
        PlyEncoding::WORDS,
        GridFaces::WORDS,
        SmoothMethod::WORDS,
        NormalWeight::WORDS,
        BoundaryCurvature::WORDS,
        IndexWidth::WORDS,
        ColumnSource::WORDS,
        StopReason::WORDS,
        Scheme::WORDS,
        Boundary::WORDS,
        MidpointFaces::WORDS,
        VertexInterpolation::WORDS,
    ] {
        for (i, a) in words.iter().enumerate() {
            assert_eq!(a.to_ascii_lowercase(), *a);
            assert!(words[i + 1..].iter().all(|b| a != b));
        }
    }
}
