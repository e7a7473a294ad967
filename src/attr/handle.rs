//! Typed attribute handles, and the [`Element`] trait that ties a key type
//! to its arena.

use std::fmt;
use std::marker::PhantomData;

use crate::keys::{AnyKey, EdgeKey, ElementKind, FaceKey, HalfedgeKey, VertexKey};
use crate::store::Attribute;

mod sealed {
    pub trait Sealed {}
}

/// A key type of one arena: [`VertexKey`], [`HalfedgeKey`], [`EdgeKey`] or
/// [`FaceKey`] (faces include holes). Sealed.
pub trait Element: Copy + Eq + fmt::Debug + Send + Sync + sealed::Sealed + 'static {
    /// The arena.
    const KIND: ElementKind;
    /// Slot `i`'s generation is at `i >> SHIFT` (half-edges share their
    /// edge's).
    #[doc(hidden)]
    const SHIFT: u32;
    /// The key as an [`AnyKey`], for errors.
    fn any_key(self) -> AnyKey;
    /// The key's slot index.
    fn slot(self) -> u32;
    /// The key's generation.
    fn generation_of_key(self) -> u32;
    /// A key from raw parts (checked before any use).
    #[doc(hidden)]
    fn from_parts(index: u32, generation: u32) -> Self;
}

macro_rules! element {
    ($key:ident, $kind:ident, $shift:expr) => {
        impl sealed::Sealed for $key {}
        impl Element for $key {
            const KIND: ElementKind = ElementKind::$kind;
            const SHIFT: u32 = $shift;
            #[inline]
            fn any_key(self) -> AnyKey {
                AnyKey::$kind(self)
            }
            #[inline]
            fn slot(self) -> u32 {
                self.index
            }
            #[inline]
            fn generation_of_key(self) -> u32 {
                self.generation
            }
            #[inline]
            fn from_parts(index: u32, generation: u32) -> Self {
                $key::new(index, generation)
            }
        }
    };
}

element!(VertexKey, Vertex, 0);
element!(HalfedgeKey, Halfedge, crate::layout::Hid::EDGE_SHIFT);
element!(EdgeKey, Edge, 0);
element!(FaceKey, Face, 0);

/// A typed handle to one attribute column: the element kind `K`, the value
/// type `T` and the rule `R` are in the type, so reads and writes through it
/// need no type check beyond one id comparison. A handle whose column was
/// removed is reported as
/// [`Error::AttributeHandle`](crate::Error::AttributeHandle), never a panic.
/// Handles stay valid in clones of the mesh.
///
/// ```
/// use meshloom::attr::FaceAttr;
/// let mut mesh = meshloom::shapes::cube();
/// let colour: FaceAttr<[f32; 3]> = mesh.add_face_attr("colour")?;
/// assert_eq!(colour.name(), "colour");
/// let again: FaceAttr<[f32; 3]> = mesh.attr_handle("colour")?;
/// assert_eq!(again, colour);
/// # Ok::<(), meshloom::Error>(())
/// ```
pub struct Attr<K, T: Attribute, R = <T as Attribute>::Rule> {
    pub(crate) index: usize,
    pub(crate) id: u64,
    pub(crate) name: String,
    marker: Marker<K, T, R>,
}

/// Ties a handle to its key, value and rule types without owning any.
type Marker<K, T, R> = PhantomData<fn() -> (K, T, R)>;

/// A vertex attribute handle.
pub type VertexAttr<T, R = <T as Attribute>::Rule> = Attr<VertexKey, T, R>;
/// A half-edge (corner) attribute handle.
pub type HalfedgeAttr<T, R = <T as Attribute>::Rule> = Attr<HalfedgeKey, T, R>;
/// An edge attribute handle.
pub type EdgeAttr<T, R = <T as Attribute>::Rule> = Attr<EdgeKey, T, R>;
/// A face (and hole) attribute handle.
pub type FaceAttr<T, R = <T as Attribute>::Rule> = Attr<FaceKey, T, R>;

impl<K, T: Attribute, R> Attr<K, T, R> {
    pub(crate) fn new(index: usize, id: u64, name: &str) -> Self {
        Attr {
            index,
            id,
            name: name.to_owned(),
            marker: PhantomData,
        }
    }

    /// The attribute's name.
    pub fn name(&self) -> &str {
        &self.name
    }
}

impl<K, T: Attribute, R> Clone for Attr<K, T, R> {
    fn clone(&self) -> Self {
        Attr::new(self.index, self.id, &self.name)
    }
}

impl<K, T: Attribute, R> PartialEq for Attr<K, T, R> {
    fn eq(&self, other: &Self) -> bool {
        self.id == other.id
    }
}

impl<K, T: Attribute, R> Eq for Attr<K, T, R> {}

impl<K: Element, T: Attribute, R> fmt::Debug for Attr<K, T, R> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} attribute {:?} ({})",
            K::KIND,
            self.name,
            std::any::type_name::<T>()
        )
    }
}
