//! Borrowed views of one attribute column, for hot loops and whole-column
//! passes: `get` is a generation compare, a presence test that costs nothing
//! on a dense column, and a slice read.

use std::any::Any;
use std::marker::PhantomData;

use super::handle::Element;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::slots::Slots;
use crate::store::{Attribute, Value, ValueType};
use crate::view::{EdgeView, FaceView, HalfedgeView, VertexView};

mod sealed {
    pub trait Sealed {}
}

/// A checked element view ([`VertexView`], [`HalfedgeView`], [`EdgeView`],
/// [`FaceView`]): its key was checked when it was made, so
/// [`AttrView::at`] reads without a generation check. Sealed.
pub trait ElementView<'m>: Copy + sealed::Sealed {
    /// The key type of its arena.
    type Key: Element;
    /// The mesh and the slot.
    #[doc(hidden)]
    fn parts(self) -> (&'m Mesh, usize);
}

macro_rules! element_view {
    ($view:ident, $key:ty, $field:ident) => {
        impl sealed::Sealed for $view<'_> {}
        impl<'m> ElementView<'m> for $view<'m> {
            type Key = $key;
            #[inline(always)]
            fn parts(self) -> (&'m Mesh, usize) {
                (self.mesh, self.$field.index())
            }
        }

        /// Two views are equal when they show the same element of the same
        /// mesh (no generation read: both were checked when made).
        impl PartialEq for $view<'_> {
            #[inline]
            fn eq(&self, other: &Self) -> bool {
                self.$field == other.$field && std::ptr::eq(self.mesh, other.mesh)
            }
        }

        impl Eq for $view<'_> {}
    };
}

element_view!(VertexView, crate::VertexKey, v);
element_view!(HalfedgeView, crate::HalfedgeKey, h);
element_view!(EdgeView, crate::EdgeKey, e);
element_view!(FaceView, crate::FaceKey, f);

#[inline]
fn bit(bits: Option<&[u64]>, i: usize) -> bool {
    match bits {
        None => true,
        Some(b) => b.get(i / 64).is_some_and(|w| w >> (i % 64) & 1 == 1),
    }
}

/// A read-only view of one attribute column, from
/// [`Mesh::attr_view`](crate::Mesh::attr_view).
///
/// ```
/// let mut mesh = meshloom::shapes::tetrahedron();
/// let w = mesh.add_vertex_attr::<f64>("weight")?;
/// let v = mesh.vertices().next().unwrap();
/// mesh.set_attr(&w, v, 0.5)?;
/// let view = mesh.attr_view(&w)?;
/// assert_eq!(view.get(v), Some(&0.5));
/// assert_eq!(view.iter().count(), 1); // the other vertices have no value
/// # Ok::<(), meshloom::Error>(())
/// ```
pub struct AttrView<'m, K, T> {
    /// The mesh the column belongs to, for [`AttrView::at`].
    pub(crate) mesh: &'m Mesh,
    /// One value per slot of the arena (two per edge slot on half-edges),
    /// never more: [`AttrView::get`] relies on it.
    pub(crate) values: &'m [T],
    pub(crate) present: Option<&'m [u64]>,
    /// The arena's stored generations (odd = live); empty while they are
    /// implied (`intact`: every slot live at the base).
    pub(crate) generations: &'m [u32],
    /// The arena's slot count.
    pub(crate) slot_count: usize,
    /// The arena's base generation.
    pub(crate) base: u32,
    /// No slot of the arena was freed since it was built or compacted
    /// (every slot is live at the base generation) and every slot has a
    /// value: the column is one slice in slot order
    /// ([`AttrView::dense_slice`]).
    pub(crate) dense_intact: bool,
    pub(crate) marker: PhantomData<K>,
}

/// The generation stored for arena slot `slot`, or `base` where none is
/// stored (an intact arena stores none: every slot is at the base). Only
/// for a slot below the slot count (a written-out arena stores one
/// generation per slot).
#[inline(always)]
fn stored_or_base(generations: &[u32], slot: usize, base: u32) -> u32 {
    generations.get(slot).copied().unwrap_or(base)
}

impl<'m, K: Element, T> AttrView<'m, K, T> {
    /// The value of `key`'s element; `None` if it has none or the key is
    /// stale.
    ///
    /// Inline only for the common case, a dense column on an intact arena
    /// (a mesh built or compacted and not edited since, e.g. its
    /// positions): a bounds test and a compare of the key's generation with
    /// the base. Every other state is one call to a shared out-of-line
    /// check. With all the states inline this function, and with it a
    /// user's per-element closure around it, grew too large for LLVM to
    /// inline the closure into the user's loop (the `normals_classic` row
    /// of examples/ml_bench.rs shows it).
    #[inline]
    pub fn get(&self, key: K) -> Option<&'m T> {
        let i = key.slot() as usize;
        let generation = key.generation_of_key();
        if self.dense_intact {
            // One value per slot, every slot live at the base generation,
            // every value present.
            let value = self.values.get(i)?;
            return (generation == self.base).then_some(value);
        }
        self.get_checked(i, generation)
    }

    /// [`get`](Self::get) on a column with gaps or an arena that was
    /// edited: the key's generation is odd and equals the stored one (the
    /// base while the arena stores none), and the column has a value
    /// there. `values` holds no more than the arena's slots (cut so in
    /// `Mesh::attr_view`): a key with a value has a slot below the slot
    /// count, no compare needed.
    #[cold]
    #[inline(never)]
    fn get_checked(&self, i: usize, generation: u32) -> Option<&'m T> {
        // Both loads are issued before either is tested, so a random access
        // waits for one cache miss, not two in a row.
        let value = self.values.get(i);
        let live = (stored_or_base(self.generations, i >> K::SHIFT, self.base) == generation)
            & (generation & 1 == 1);
        if live && bit(self.present, i) {
            value
        } else {
            None
        }
    }

    /// The value of a checked element (from [`Mesh::vertex`] and its
    /// siblings, or navigation from one): no generation check, only a test
    /// that the element belongs to the same mesh; `None` if it has no value
    /// or is of another mesh. The fastest read in a loop that navigates.
    ///
    /// ```
    /// let mesh = meshloom::shapes::tetrahedron();
    /// let pos = mesh.position_attr().unwrap();
    /// let view = mesh.attr_view(&pos)?;
    /// let v = mesh.vertex(mesh.vertices().next().unwrap())?;
    /// let far = v.halfedge().dest();
    /// assert_eq!(view.at(far).copied(), far.position());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn at<V: ElementView<'m, Key = K>>(&self, element: V) -> Option<&'m T> {
        let (mesh, i) = element.parts();
        if std::ptr::eq(mesh, self.mesh) && bit(self.present, i) {
            self.values.get(i)
        } else {
            None
        }
    }

    /// The whole column as one slice in slot order, when every slot of the
    /// arena holds a live element with a value (no element removed since the
    /// mesh was built or compacted, no absent value); `None` otherwise. For
    /// bulk copies (numpy, GPU buffers); on the face arena the slice
    /// includes the hole faces' slots.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let t = mesh.add_vertex_attr::<f64>("t")?;
    /// mesh.fill_attr(&t, 1.5)?;
    /// assert_eq!(mesh.attr_view(&t)?.dense_slice(), Some(&[1.5; 4][..]));
    /// let v = mesh.vertices().next().unwrap();
    /// mesh.clear_attr(&t, v)?;
    /// assert_eq!(mesh.attr_view(&t)?.dense_slice(), None);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    #[inline]
    pub fn dense_slice(&self) -> Option<&'m [T]> {
        self.dense_intact.then_some(self.values)
    }

    /// Every live element that has a value, with it, in slot order (faces:
    /// holes included).
    pub fn iter(&self) -> impl Iterator<Item = (K, &'m T)> + '_ {
        let (generations, present) = (self.generations, self.present);
        let (base, slot_count) = (self.base, self.slot_count);
        self.values.iter().enumerate().filter_map(move |(i, v)| {
            let slot = i >> K::SHIFT;
            let g = (slot < slot_count).then(|| stored_or_base(generations, slot, base))?;
            (g & 1 == 1 && bit(present, i)).then(|| (K::from_parts(i as u32, g), v))
        })
    }
}

/// A mutable view of one attribute column, from
/// [`Mesh::attr_view_mut`](crate::Mesh::attr_view_mut).
///
/// `get_mut` and `iter_mut` hand out the stored values: on a dynamic column
/// they can change a value's type; writers then convert or skip it.
///
/// ```
/// let mut mesh = meshloom::shapes::tetrahedron();
/// let w = mesh.add_vertex_attr::<f64>("weight")?;
/// let keys: Vec<_> = mesh.vertices().collect();
/// let mut view = mesh.attr_view_mut(&w)?;
/// for &v in &keys {
///     view.set(v, Some(1.0))?;
/// }
/// for (_, x) in view.iter_mut() {
///     *x *= 3.0;
/// }
/// assert_eq!(mesh.attr(&w, keys[2])?, Some(&3.0));
/// # Ok::<(), meshloom::Error>(())
/// ```
pub struct AttrViewMut<'m, K, T> {
    pub(crate) values: &'m mut Vec<T>,
    pub(crate) present: &'m mut Option<Vec<u64>>,
    /// The column's count of clear presence bits (see `Column::absent`).
    pub(crate) absent: &'m mut usize,
    pub(crate) slots: &'m Slots,
    pub(crate) shift: u32,
    pub(crate) value_type: Option<ValueType>,
    pub(crate) name: &'m str,
    /// The position column: values must be finite.
    pub(crate) finite: bool,
    pub(crate) marker: PhantomData<K>,
}

impl<K: Element, T: Attribute> AttrViewMut<'_, K, T> {
    /// Drop the presence bits when every slot of the arena has a value (a
    /// filled column on an arena with no vacant slot): the column is dense
    /// again, so bulk reads ([`AttrView::dense_slice`]) take it whole.
    /// Writes keep the count of absent slots, so this is a test.
    pub(crate) fn drop_full_presence(&mut self) {
        if *self.absent == 0 {
            *self.present = None;
        }
    }

    #[inline]
    fn live(&self, key: K) -> Option<usize> {
        let i = key.slot();
        self.slots
            .is_current(i >> self.shift, key.generation_of_key())
            .then_some(i as usize)
    }

    /// The value of `key`'s element; `None` if it has none or the key is
    /// stale.
    #[inline]
    pub fn get(&self, key: K) -> Option<&T> {
        let i = self.live(key)?;
        if bit(self.present.as_deref(), i) {
            self.values.get(i)
        } else {
            None
        }
    }

    /// The value of `key`'s element, mutably.
    #[inline]
    pub fn get_mut(&mut self, key: K) -> Option<&mut T> {
        let i = self.live(key)?;
        if bit(self.present.as_deref(), i) {
            self.values.get_mut(i)
        } else {
            None
        }
    }

    /// Set (`Some`) or clear (`None`) the value of `key`'s element.
    ///
    /// # Errors
    /// [`Error::StaleKey`]; [`Error::AttributeType`] for a value of another
    /// type than a dynamic column declares.
    pub fn set(&mut self, key: K, value: Option<T>) -> Result<()> {
        let i = self
            .live(key)
            .ok_or_else(|| Error::StaleKey(key.any_key()))?;
        if let (Some(ty), Some(v)) = (self.value_type, value.as_ref()) {
            check_dynamic(K::KIND, self.name, ty, v)?;
        }
        if self.finite {
            if let Some(p) = value
                .as_ref()
                .and_then(|v| (v as &dyn Any).downcast_ref::<[f64; 3]>())
            {
                if !p.iter().all(|c| c.is_finite()) {
                    return Err(Error::NonFinitePosition {
                        key: key.any_key(),
                        position: *p,
                    });
                }
            }
        }
        let len = self.values.len();
        let has = value.is_some();
        self.values[i] = value.unwrap_or_default();
        // The last absent value set makes the column dense again.
        crate::store::mark(self.present, self.absent, len, i, has);
        Ok(())
    }

    /// Write the whole column at once from `values`, one per slot in slot
    /// order, when every slot of the arena holds a live element (no element
    /// removed since the mesh was built or compacted) and `values` has one
    /// value per slot: the column is then dense ([`AttrView::dense_slice`]).
    /// Returns `false`, writing nothing, when the arena has a vacant slot or
    /// the length differs (write by key then). On the face arena the slots
    /// include the hole faces'.
    ///
    /// ```
    /// let mut mesh = meshloom::shapes::tetrahedron();
    /// let t = mesh.add_vertex_attr::<f64>("t")?;
    /// assert!(mesh.attr_view_mut(&t)?.set_slots(&[1.0, 2.0, 3.0, 4.0])?);
    /// assert_eq!(mesh.attr_view(&t)?.dense_slice(), Some(&[1.0, 2.0, 3.0, 4.0][..]));
    /// assert!(!mesh.attr_view_mut(&t)?.set_slots(&[1.0])?);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::AttributeType`] for a value of another type than a dynamic
    /// column declares; [`Error::NonFinitePosition`] on the position
    /// column. Nothing is written then.
    pub fn set_slots(&mut self, values: &[T]) -> Result<bool> {
        if values.len() != self.values.len() || !self.slots.intact() {
            return Ok(false);
        }
        for (i, v) in values.iter().enumerate() {
            if let Some(ty) = self.value_type {
                check_dynamic(K::KIND, self.name, ty, v)?;
            }
            if self.finite {
                if let Some(p) = (v as &dyn Any).downcast_ref::<[f64; 3]>() {
                    if !p.iter().all(|c| c.is_finite()) {
                        let g = self.slots.generation(i >> self.shift).unwrap_or(1);
                        return Err(Error::NonFinitePosition {
                            key: K::from_parts(i as u32, g).any_key(),
                            position: *p,
                        });
                    }
                }
            }
        }
        self.values.clone_from_slice(values);
        *self.present = None;
        *self.absent = 0;
        Ok(true)
    }

    /// Every live element that has a value, with it, in slot order.
    pub fn iter(&self) -> impl Iterator<Item = (K, &T)> + '_ {
        let (slots, shift, present) = (self.slots, self.shift, self.present.as_deref());
        self.values.iter().enumerate().filter_map(move |(i, v)| {
            let g = slots.generation(i >> shift)?;
            (g & 1 == 1 && bit(present, i)).then(|| (K::from_parts(i as u32, g), v))
        })
    }

    /// Every live element that has a value, with it mutably, in slot order.
    pub fn iter_mut(&mut self) -> impl Iterator<Item = (K, &mut T)> + use<'_, K, T> {
        let (slots, shift, present) = (self.slots, self.shift, self.present.as_deref());
        self.values
            .iter_mut()
            .enumerate()
            .filter_map(move |(i, v)| {
                let g = slots.generation(i >> shift)?;
                (g & 1 == 1 && bit(present, i)).then(|| (K::from_parts(i as u32, g), v))
            })
    }
}

/// A value stored in a dynamic column must have the declared type.
pub(crate) fn check_dynamic<T: Any>(
    kind: crate::keys::ElementKind,
    name: &str,
    declared: ValueType,
    value: &T,
) -> Result<()> {
    match (value as &dyn Any).downcast_ref::<Value>() {
        Some(v) if v.value_type() != declared => Err(Error::AttributeType {
            kind,
            name: name.to_owned(),
            expected: declared.name(),
            found: v.value_type().name(),
        }),
        _ => Ok(()),
    }
}
