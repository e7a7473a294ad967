//! The one entry point: [`subdivide`] checks the options, estimates the
//! size, runs the levels of a [`Scheme`] and hands the result over.

use crate::algo::catmull_clark::CatmullClark;
use crate::algo::loop_subdivision::Loop;
use crate::algo::midpoint::Midpoint;
use crate::algo::progress::Progress;
use crate::algo::sqrt3::Sqrt3;
use crate::error::{Error, Result};
use crate::mesh::Mesh;

use super::{
    check_columns, unsuitable, Counts, LevelReport, SubdivisionOptions, SubdivisionReport,
};

/// A subdivision scheme. Words: `loop`, `catmull-clark`, `sqrt3`,
/// `midpoint` (`catmull_clark` reads too).
///
/// ```
/// use meshloom::algo::Scheme;
/// assert_eq!("sqrt3".parse::<Scheme>()?, Scheme::Sqrt3);
/// assert_eq!("catmull_clark".parse::<Scheme>()?, Scheme::CatmullClark);
/// assert_eq!(Scheme::CatmullClark.to_string(), "catmull-clark");
/// assert!(Scheme::Loop.takes_creases() && !Scheme::Sqrt3.takes_creases());
/// assert!("butterfly".parse::<Scheme>().is_err());
/// # Ok::<(), meshloom::choice::UnknownChoice>(())
/// ```
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
pub enum Scheme {
    /// Loop (1987): triangles only, each into four; C² limit surface (C¹
    /// at extraordinary vertices), semi-sharp creases. The default.
    #[default]
    Loop,
    /// Catmull-Clark (1978): any polygons, each into one quad per corner;
    /// bicubic B-spline limit surface, semi-sharp creases.
    CatmullClark,
    /// Kobbelt's √3 (2000): triangles only, each into three; the boundary
    /// is kept at odd levels and trisected at even ones. No creases.
    Sqrt3,
    /// Linear (midpoint) subdivision: faces cut as Loop or Catmull-Clark
    /// cut them (see [`MidpointFaces`](super::MidpointFaces)), nothing
    /// moves. No creases.
    Midpoint,
}

crate::choice::choices!(Scheme {
    Loop = "loop",
    CatmullClark = "catmull-clark",
    Sqrt3 = "sqrt3",
    Midpoint = "midpoint",
});

impl Scheme {
    /// Whether the scheme takes a
    /// [`crease_column`](SubdivisionOptions::crease_column): Loop and
    /// Catmull-Clark. √3 flips every old edge away, so no child runs along
    /// a crease; midpoint moves nothing, so a crease changes nothing. The
    /// others refuse a crease column with
    /// [`Error::Unsuitable`](crate::Error::Unsuitable).
    pub fn takes_creases(self) -> bool {
        matches!(self, Scheme::Loop | Scheme::CatmullClark)
    }

    /// The name errors and progress reports give: the per-scheme
    /// function's (`"loop_subdivide"`).
    pub(crate) fn algorithm(self) -> &'static str {
        match self {
            Scheme::Loop => "loop_subdivide",
            Scheme::CatmullClark => "catmull_clark",
            Scheme::Sqrt3 => "sqrt3_subdivide",
            Scheme::Midpoint => "midpoint_subdivide",
        }
    }

    /// The journal step's name.
    fn step(self) -> &'static str {
        match self {
            Scheme::Loop => "Loop subdivision",
            Scheme::CatmullClark => "Catmull-Clark",
            Scheme::Sqrt3 => "Sqrt(3) subdivision",
            Scheme::Midpoint => "Midpoint subdivision",
        }
    }

    /// Why the scheme refuses a crease column.
    fn no_creases(self) -> &'static str {
        match self {
            Scheme::Sqrt3 => "√3 flips every old edge away, so it cannot keep creases (use Loop)",
            _ => {
                "midpoint subdivision moves no vertex, so it takes no creases \
                 (use Loop or Catmull-Clark)"
            }
        }
    }
}

/// Apply `options.levels` levels of `scheme` to `mesh`.
///
/// Every scheme runs on one driver: the options are checked first, a
/// result estimated past `options.max_faces` is refused before any work,
/// each level is built wholesale from the previous one, and the last
/// replaces the mesh in one journal step (one undo). See
/// [`subdivision`](crate::algo::subdivision) for the schemes, keys and
/// attributes.
///
/// # Errors
/// [`Error::Unsuitable`] for a face the scheme cannot cut (Loop, √3 and
/// midpoint's triangles take triangles only), an interior vertex of
/// valence 2 between two faces cut into triangles, a NaN sharpness, or a
/// crease column given to a scheme that takes none;
/// [`Error::AttributeMissing`] / [`Error::AttributeType`] for a column
/// named in the options; [`Error::TooLarge`] past `max_faces`;
/// [`Error::NonFinitePosition`] for a vertex at NaN or infinity,
/// [`Error::NonFiniteResult`] for a result that overflows;
/// [`Error::Cancelled`]. On any error the mesh is exactly as it was.
///
/// # Complexity
/// O(output size) time; the result of each level is allocated once.
///
/// ```
/// use meshloom::algo::{subdivide, Progress, Scheme, SubdivisionOptions};
/// let mut mesh = meshloom::shapes::icosahedron();
/// let v = mesh.vertices().next().unwrap();
/// let report = subdivide(&mut mesh, Scheme::Loop, &SubdivisionOptions::default().levels(2), Progress::none())?;
/// assert_eq!(report.levels[0].output.faces, 80);
/// assert_eq!((mesh.vertex_count(), mesh.face_count()), (162, 320));
/// // Vertex keys from before still name their (moved) vertex.
/// assert!(mesh.position(v)?.iter().all(|c| c.is_finite()));
///
/// // A crease column is for Loop and Catmull-Clark only; the mesh is left alone.
/// let options = SubdivisionOptions::default().crease_column(Some("sharpness".into()));
/// assert!(subdivide(&mut mesh, Scheme::Sqrt3, &options, Progress::none()).is_err());
/// assert_eq!(mesh.face_count(), 320);
/// # Ok::<(), meshloom::Error>(())
/// ```
pub fn subdivide(
    mesh: &mut Mesh,
    scheme: Scheme,
    options: &SubdivisionOptions,
    progress: Progress<'_>,
) -> Result<SubdivisionReport> {
    match scheme {
        Scheme::Loop => drive(mesh, &Loop, options, progress),
        Scheme::CatmullClark => drive(mesh, &CatmullClark, options, progress),
        Scheme::Sqrt3 => drive(mesh, &Sqrt3, options, progress),
        Scheme::Midpoint => {
            let midpoint = Midpoint::for_mesh(mesh, options.midpoint_faces);
            drive(mesh, &midpoint, options, progress)
        }
    }
}

/// One scheme on the driver: how it grows and how it builds a level.
/// Loop, Catmull-Clark and midpoint implement it through
/// [`FaceSplit`](super::split::FaceSplit), √3 directly.
pub(crate) trait Subdivider {
    /// The scheme.
    const SCHEME: Scheme;

    /// How many faces one level makes of a face.
    fn growth(&self) -> Growth;

    /// Level `level` (counted from 0 within the call) of `mesh`, built
    /// into a new mesh, and what it did (its counts are the driver's).
    fn level(
        &self,
        mesh: &Mesh,
        options: &SubdivisionOptions,
        level: u32,
        progress: &mut Progress<'_>,
    ) -> Result<(Mesh, LevelReport)>;
}

/// [`subdivide`] for one scheme type, in one journal step.
fn drive<S: Subdivider>(
    mesh: &mut Mesh,
    scheme: &S,
    options: &SubdivisionOptions,
    mut progress: Progress<'_>,
) -> Result<SubdivisionReport> {
    mesh.as_one_step(S::SCHEME.step(), |mesh| {
        check_options(mesh, S::SCHEME, options)?;
        let levels = Levels {
            count: options.levels,
            growth: scheme.growth(),
            max_faces: options.max_faces,
        };
        run_levels(
            mesh,
            S::SCHEME,
            levels,
            &mut progress,
            |parent, i, progress| scheme.level(parent, options, i, progress),
        )
    })
}

/// The checks of `options` every scheme shares: a crease column only where
/// the scheme takes one, the named columns exist with a fitting type.
fn check_options(mesh: &Mesh, scheme: Scheme, options: &SubdivisionOptions) -> Result<()> {
    let algorithm = scheme.algorithm();
    let crease = options.crease_column.as_deref();
    let checked_crease = if scheme.takes_creases() { crease } else { None };
    check_columns(
        mesh,
        algorithm,
        options.corner_column.as_deref(),
        checked_crease,
        &options.vertex_data,
    )?;
    if crease.is_some() && !scheme.takes_creases() {
        return Err(unsuitable(algorithm, None, scheme.no_creases()));
    }
    Ok(())
}

/// Run `levels` levels of `level`, each reading the previous result, and
/// hand the last over to `mesh`. Nothing of `mesh` changes before every
/// level is built; an error or a cancellation leaves it as it was.
fn run_levels(
    mesh: &mut Mesh,
    scheme: Scheme,
    levels: Levels,
    progress: &mut Progress<'_>,
    mut level: impl FnMut(&Mesh, u32, &mut Progress<'_>) -> Result<(Mesh, LevelReport)>,
) -> Result<SubdivisionReport> {
    let algorithm = scheme.algorithm();
    levels.check(mesh, algorithm)?;
    let mut report = SubdivisionReport {
        scheme,
        input: Counts::of(mesh),
        output: Counts::of(mesh),
        levels: Vec::with_capacity(levels.count as usize),
    };
    let mut current: Option<Mesh> = None;
    for i in 0..levels.count {
        let source = current.as_ref().unwrap_or(mesh);
        if source.is_empty() {
            break;
        }
        let (next, mut level_report) = level(source, i, progress)?;
        next.debug_validate();
        level_report.output = Counts::of(&next);
        report.output = level_report.output;
        report.levels.push(level_report);
        current = Some(next);
    }
    progress.report(algorithm, "done", 1, 1)?;
    if let Some(result) = current {
        crate::algo::check_finite(&result, algorithm)?;
        mesh.replace_with(result);
    }
    Ok(report)
}

/// How many faces one level makes of a face.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Growth {
    /// Every face into four (Loop; midpoint's triangles).
    Four,
    /// An n-sided face into n quads, then every quad into four
    /// (Catmull-Clark; midpoint's quads).
    Corners,
    /// Every triangle into three (√3; its boundary trisection adds a few).
    Three,
}

/// The levels a driver runs and the size it may reach.
#[derive(Copy, Clone, Debug)]
struct Levels {
    count: u32,
    growth: Growth,
    max_faces: usize,
}

impl Levels {
    /// The faces after every level, estimated from the face count and
    /// corner count of `mesh` (√3 is counted with its boundary
    /// trisection's extra faces as one more third).
    fn estimate(&self, mesh: &Mesh) -> f64 {
        if self.count == 0 {
            return mesh.face_count() as f64;
        }
        let faces = mesh.face_count() as f64;
        let later = f64::from(self.count - 1);
        match self.growth {
            Growth::Four => faces * 4f64.powf(later + 1.0),
            Growth::Three => faces * 3f64.powf(later + 1.0) * (4.0 / 3.0),
            Growth::Corners => {
                // Every half-edge is a corner of a face or of a hole.
                let in_holes: usize = mesh
                    .holes()
                    .filter_map(|f| mesh.face(f).ok())
                    .map(|f| f.degree())
                    .sum();
                let corners = mesh.halfedge_count() - in_holes;
                corners as f64 * 4f64.powf(later)
            }
        }
    }

    /// Refuse, before any work, a result estimated past `max_faces`.
    fn check(&self, mesh: &Mesh, algorithm: &'static str) -> Result<()> {
        let estimate = self.estimate(mesh);
        if estimate > self.max_faces as f64 {
            return Err(Error::TooLarge {
                algorithm,
                estimate: estimate.min(u64::MAX as f64) as u64,
                limit: self.max_faces as u64,
                option: "max_faces",
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::Scheme;

    #[test]
    fn words_round_trip() {
        for word in Scheme::WORDS {
            let scheme: Scheme = word.parse().unwrap();
            assert_eq!(scheme.to_string(), *word);
        }
        let err = "butterfly".parse::<Scheme>().unwrap_err();
        assert!(err
            .to_string()
            .contains("loop, catmull-clark, sqrt3, midpoint"));
    }

    #[cfg(feature = "serde")]
    #[test]
    fn serde_writes_the_words() {
        for word in Scheme::WORDS {
            let scheme: Scheme = word.parse().unwrap();
            assert_eq!(
                serde_json::to_string(&scheme).unwrap(),
                format!("\"{word}\"")
            );
            let back: Scheme = serde_json::from_str(&format!("\"{word}\"")).unwrap();
            assert_eq!(back, scheme);
        }
    }
}
