//! Typed, generational keys for the four element kinds.
//!
//! A key is a slot index plus the generation the slot had when the element
//! was made. Removing an element bumps its slot's generation, so a key kept
//! across the removal no longer matches and every public entry point reports
//! it as [`Error::StaleKey`](crate::Error::StaleKey) instead of handing back
//! whatever element reuses the slot.
//!
//! Half-edges come in twin pairs stored side by side (the layout lives in
//! `layout.rs`), so a [`HalfedgeKey`] shares its generation with its
//! [`EdgeKey`] and `twin` needs no storage.

use std::fmt;

mod sealed {
    /// Only this crate's keys are element keys.
    pub trait Sealed {}
}

/// What the four key types have in common: a slot index and the
/// generation it was issued for. Implemented by [`VertexKey`],
/// [`HalfedgeKey`], [`EdgeKey`] and [`FaceKey`] only (sealed); generic code
/// such as [`SecondaryMap`](crate::map::SecondaryMap) is written over it.
pub trait ElementKey: Copy + Eq + fmt::Debug + sealed::Sealed {
    /// The slot index.
    fn index(self) -> usize;
    /// The slot generation.
    fn generation(self) -> u32;
    #[doc(hidden)]
    fn from_parts(index: u32, generation: u32) -> Self;
}

macro_rules! key_type {
    ($(#[$doc:meta])* $name:ident, $prefix:literal) => {
        $(#[$doc])*
        #[derive(Copy, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
        #[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
        pub struct $name {
            pub(crate) index: u32,
            pub(crate) generation: u32,
        }

        impl $name {
            pub(crate) const fn new(index: u32, generation: u32) -> Self {
                Self { index, generation }
            }

            /// The slot index: dense after [`Mesh::compact`](crate::Mesh),
            /// stable while the element lives, reused after it is removed.
            pub const fn index(self) -> usize {
                self.index as usize
            }

            /// The slot generation this key was issued for.
            pub const fn generation(self) -> u32 {
                self.generation
            }
        }

        impl sealed::Sealed for $name {}

        impl ElementKey for $name {
            #[inline]
            fn index(self) -> usize {
                self.index as usize
            }
            #[inline]
            fn generation(self) -> u32 {
                self.generation
            }
            #[inline]
            fn from_parts(index: u32, generation: u32) -> Self {
                Self::new(index, generation)
            }
        }

        impl fmt::Debug for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, concat!($prefix, "{}v{}"), self.index, self.generation)
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                fmt::Debug::fmt(self, f)
            }
        }
    };
}

key_type!(
    /// A key to a vertex.
    VertexKey,
    "v"
);
key_type!(
    /// A key to a half-edge: one direction of an edge.
    HalfedgeKey,
    "h"
);
key_type!(
    /// A key to an edge: the unordered pair of twin half-edges.
    EdgeKey,
    "e"
);
key_type!(
    /// A key to a face; hole faces (outside a boundary) are faces too.
    FaceKey,
    "f"
);

impl HalfedgeKey {
    /// The twin half-edge key (same edge, other direction). Pure arithmetic:
    /// valid exactly when `self` is.
    pub const fn twin_key(self) -> HalfedgeKey {
        self.id().twin().key(self.generation)
    }

    /// The edge this half-edge belongs to. Pure arithmetic.
    pub const fn edge_key(self) -> EdgeKey {
        self.id().edge().key(self.generation)
    }
}

impl EdgeKey {
    /// One of the edge's half-edges: `side` 0 or 1 (any other value is
    /// taken modulo 2). Pure arithmetic.
    pub const fn halfedge_key(self, side: u32) -> HalfedgeKey {
        self.id().halfedge(side).key(self.generation)
    }
}

/// The element kinds, for errors and attribute columns.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ElementKind {
    /// A vertex.
    Vertex,
    /// A half-edge.
    Halfedge,
    /// An edge (twin pair).
    Edge,
    /// A face or hole.
    Face,
}

impl fmt::Display for ElementKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ElementKind::Vertex => "vertex",
            ElementKind::Halfedge => "half-edge",
            ElementKind::Edge => "edge",
            ElementKind::Face => "face",
        })
    }
}

/// A key of any kind, for errors that must name the element involved.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum AnyKey {
    /// A vertex key.
    Vertex(VertexKey),
    /// A half-edge key.
    Halfedge(HalfedgeKey),
    /// An edge key.
    Edge(EdgeKey),
    /// A face key.
    Face(FaceKey),
}

impl fmt::Display for AnyKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AnyKey::Vertex(k) => write!(f, "vertex {k}"),
            AnyKey::Halfedge(k) => write!(f, "half-edge {k}"),
            AnyKey::Edge(k) => write!(f, "edge {k}"),
            AnyKey::Face(k) => write!(f, "face {k}"),
        }
    }
}

impl From<VertexKey> for AnyKey {
    fn from(k: VertexKey) -> AnyKey {
        AnyKey::Vertex(k)
    }
}
impl From<HalfedgeKey> for AnyKey {
    fn from(k: HalfedgeKey) -> AnyKey {
        AnyKey::Halfedge(k)
    }
}
impl From<EdgeKey> for AnyKey {
    fn from(k: EdgeKey) -> AnyKey {
        AnyKey::Edge(k)
    }
}
impl From<FaceKey> for AnyKey {
    fn from(k: FaceKey) -> AnyKey {
        AnyKey::Face(k)
    }
}
