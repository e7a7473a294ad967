//! [`SecondaryMap`]: a value per element, beside a mesh, for algorithms and
//! users.
//!
//! Attribute columns ([`attr`](crate::attr)) live inside the mesh and
//! follow every edit by rule. A secondary map is the cheap alternative for
//! scratch data that lives only as long as an algorithm: a vector indexed
//! by slot (no hashing), each entry tagged with the generation of the key
//! that stored it, so a key of a removed element, or a newer element in a
//! reused slot, finds nothing rather than another element's value.

use std::fmt;
use std::marker::PhantomData;

use crate::keys::ElementKey;

/// Values keyed by element keys, stored densely by slot index, stale-key
/// safe: a key finds only the value stored under that very key (slot and
/// generation), never the value of another element in a reused slot. The
/// values of removed elements stay until overwritten or removed.
///
/// ```
/// use meshloom::map::SecondaryMap;
/// use meshloom::VertexKey;
///
/// let mut mesh = meshloom::shapes::icosphere(1);
/// // Breadth-first distance (in edges) from one vertex.
/// let start = mesh.vertices().next().unwrap();
/// let mut hops: SecondaryMap<VertexKey, u32> = SecondaryMap::with_capacity(mesh.vertex_count());
/// hops.insert(start, 0);
/// let mut queue = std::collections::VecDeque::from([start]);
/// while let Some(v) = queue.pop_front() {
///     let d = hops[v];
///     for w in mesh.vertex(v)?.neighbors() {
///         if !hops.contains_key(w) {
///             hops.insert(w, d + 1);
///             queue.push_back(w);
///         }
///     }
/// }
/// assert_eq!(hops.len(), mesh.vertex_count());
///
/// // Collapse an edge and compact: every slot is re-issued to a vertex
/// // under a new generation, and no new key finds an old value.
/// let h = mesh.halfedges().next().unwrap();
/// mesh.collapse_edge(h)?;
/// mesh.compact();
/// assert!(mesh.vertices().all(|v| hops.get(v).is_none()));
/// # Ok::<(), meshloom::Error>(())
/// ```
#[derive(Clone)]
pub struct SecondaryMap<K, V> {
    slots: Vec<Option<(u32, V)>>,
    len: usize,
    key: PhantomData<fn(K) -> K>,
}

impl<K: ElementKey, V> Default for SecondaryMap<K, V> {
    fn default() -> Self {
        SecondaryMap::new()
    }
}

impl<K: ElementKey, V> SecondaryMap<K, V> {
    /// An empty map.
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, FaceKey};
    /// let mut area: SecondaryMap<FaceKey, f64> = SecondaryMap::new();
    /// assert!(area.is_empty());
    /// let cube = meshloom::shapes::cube();
    /// for f in cube.faces() {
    ///     area.insert(f, cube.face_area(f)?);
    /// }
    /// assert_eq!(area.values().sum::<f64>(), 6.0);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn new() -> Self {
        SecondaryMap {
            slots: Vec::new(),
            len: 0,
            key: PhantomData,
        }
    }

    /// An empty map with room for slots `0..slots` (pass the mesh's
    /// element count, or its [`slot_counts`](crate::Mesh::slot_counts)).
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, VertexKey};
    /// let mesh = meshloom::shapes::icosphere(2);
    /// let mut height = SecondaryMap::<VertexKey, f64>::with_capacity(mesh.slot_counts()[0]);
    /// for v in mesh.vertices() {
    ///     height.insert(v, mesh.position(v)?[2]);
    /// }
    /// assert_eq!(height.len(), mesh.vertex_count());
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn with_capacity(slots: usize) -> Self {
        SecondaryMap {
            slots: Vec::with_capacity(slots),
            len: 0,
            key: PhantomData,
        }
    }

    /// Number of values held.
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, EdgeKey};
    /// let mesh = meshloom::shapes::disk(5);
    /// let rim: SecondaryMap<EdgeKey, ()> = mesh
    ///     .edges()
    ///     .filter(|&e| mesh.edge(e).is_ok_and(|e| e.is_boundary()))
    ///     .map(|e| (e, ()))
    ///     .collect();
    /// assert_eq!(rim.len(), 5);
    /// ```
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no value is held.
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, VertexKey};
    /// let mut m = SecondaryMap::<VertexKey, u8>::default();
    /// assert!(m.is_empty());
    /// let v = meshloom::shapes::tetrahedron().vertices().next().unwrap();
    /// m.insert(v, 1);
    /// assert!(!m.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Store `value` for `key`; returns the value `key` held before, if
    /// any. A value stored by an older key of the same slot (an element
    /// since removed) is dropped.
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, VertexKey};
    /// let mesh = meshloom::shapes::tetrahedron();
    /// let v = mesh.vertices().next().unwrap();
    /// let mut label = SecondaryMap::<VertexKey, &str>::new();
    /// assert_eq!(label.insert(v, "apex"), None);
    /// assert_eq!(label.insert(v, "tip"), Some("apex")); // the value it replaced
    /// assert_eq!(label[v], "tip");
    /// ```
    pub fn insert(&mut self, key: K, value: V) -> Option<V> {
        let i = key.index();
        if i >= self.slots.len() {
            self.slots.resize_with(i + 1, || None);
        }
        let old = self.slots[i].replace((key.generation(), value));
        match old {
            Some((g, v)) if g == key.generation() => Some(v),
            Some(_) => None,
            None => {
                self.len += 1;
                None
            }
        }
    }

    /// The value `key` holds; `None` for a key that stored nothing, or
    /// whose slot a newer key has stored into since. (A removed element's
    /// key still finds the value it stored: the map does not watch the
    /// mesh.)
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, FaceKey};
    /// let mut mesh = meshloom::shapes::icosphere(1);
    /// let index: SecondaryMap<FaceKey, usize> = mesh.faces().enumerate().map(|(i, f)| (f, i)).collect();
    /// let f = mesh.faces().next().unwrap();
    /// assert_eq!(index.get(f), Some(&0));
    /// // After a collapse and a compaction every face has a new key, and no new
    /// // key finds a value stored under an old one, whatever slot it reuses.
    /// let h = mesh.halfedges().next().unwrap();
    /// mesh.collapse_edge(h)?;
    /// mesh.compact();
    /// assert!(mesh.faces().all(|f| index.get(f).is_none()));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn get(&self, key: K) -> Option<&V> {
        match self.slots.get(key.index())? {
            Some((g, v)) if *g == key.generation() => Some(v),
            _ => None,
        }
    }

    /// The value `key` holds, to change.
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, VertexKey};
    /// let mesh = meshloom::shapes::cube();
    /// let mut valence: SecondaryMap<VertexKey, usize> = mesh.vertices().map(|v| (v, 0)).collect();
    /// for h in mesh.halfedges() {
    ///     let from = mesh.halfedge(h)?.origin().key();
    ///     *valence.get_mut(from).unwrap() += 1;
    /// }
    /// assert!(valence.values().all(|&n| n == 3));
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn get_mut(&mut self, key: K) -> Option<&mut V> {
        match self.slots.get_mut(key.index())? {
            Some((g, v)) if *g == key.generation() => Some(v),
            _ => None,
        }
    }

    /// The value `key` holds, stored from `make()` first if it has none.
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, VertexKey};
    /// let mesh = meshloom::shapes::disk(6);
    /// // Corners per vertex, counted without filling the map first.
    /// let mut corners = SecondaryMap::<VertexKey, u32>::new();
    /// for f in mesh.faces() {
    ///     for v in mesh.face(f)?.vertices() {
    ///         *corners.get_or_insert_with(v, || 0) += 1;
    ///     }
    /// }
    /// assert_eq!(corners.values().max(), Some(&6)); // the centre
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn get_or_insert_with(&mut self, key: K, make: impl FnOnce() -> V) -> &mut V {
        if self.get(key).is_none() {
            self.insert(key, make());
        }
        let i = key.index();
        match &mut self.slots[i] {
            Some((_, v)) => v,
            None => unreachable!("inserted above"),
        }
    }

    /// Whether `key` holds a value.
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, VertexKey};
    /// let mesh = meshloom::shapes::octahedron();
    /// let v = mesh.vertices().next().unwrap();
    /// let seen: SecondaryMap<VertexKey, ()> = mesh.vertex(v)?.neighbors().map(|w| (w, ())).collect();
    /// assert!(!seen.contains_key(v));
    /// assert_eq!(mesh.vertices().filter(|&w| seen.contains_key(w)).count(), 4);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn contains_key(&self, key: K) -> bool {
        self.get(key).is_some()
    }

    /// Take the value `key` holds out of the map.
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, EdgeKey};
    /// let mesh = meshloom::shapes::tetrahedron();
    /// let mut todo: SecondaryMap<EdgeKey, f64> = mesh.edges().map(|e| (e, 1.0)).collect();
    /// let e = mesh.edges().next().unwrap();
    /// assert_eq!(todo.remove(e), Some(1.0));
    /// assert_eq!(todo.remove(e), None);
    /// assert_eq!(todo.len(), 5);
    /// ```
    pub fn remove(&mut self, key: K) -> Option<V> {
        let slot = self.slots.get_mut(key.index())?;
        if slot.as_ref().is_some_and(|(g, _)| *g == key.generation()) {
            self.len -= 1;
            slot.take().map(|(_, v)| v)
        } else {
            None
        }
    }

    /// Remove every value, keeping the memory.
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, FaceKey};
    /// let mesh = meshloom::shapes::cube();
    /// let mut mark: SecondaryMap<FaceKey, bool> = mesh.faces().map(|f| (f, true)).collect();
    /// mark.clear(); // ready for the next pass, memory kept
    /// assert!(mark.is_empty() && mesh.faces().all(|f| !mark.contains_key(f)));
    /// ```
    pub fn clear(&mut self) {
        self.slots.iter_mut().for_each(|s| *s = None);
        self.len = 0;
    }

    /// Every key and value, in slot order. Keys whose element has since
    /// been removed are included: check them against the mesh if it has
    /// changed.
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, EdgeKey};
    /// let mesh = meshloom::shapes::icosphere(1);
    /// let length: SecondaryMap<EdgeKey, f64> =
    ///     mesh.edges().map(|e| (e, mesh.edge_length(e).unwrap())).collect();
    /// let (longest, _) = length.iter().max_by(|a, b| a.1.total_cmp(b.1)).unwrap();
    /// assert!(mesh.edge(longest).is_ok());
    /// ```
    pub fn iter(&self) -> impl Iterator<Item = (K, &V)> + '_ {
        self.slots
            .iter()
            .enumerate()
            .filter_map(|(i, s)| s.as_ref().map(|(g, v)| (K::from_parts(i as u32, *g), v)))
    }

    /// Every key and value, values changeable, in slot order.
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, FaceKey};
    /// let mesh = meshloom::shapes::cube();
    /// let mut weight: SecondaryMap<FaceKey, f64> = mesh.faces().map(|f| (f, 2.0)).collect();
    /// for (_, w) in weight.iter_mut() {
    ///     *w /= 12.0; // normalise
    /// }
    /// assert!((weight.values().sum::<f64>() - 1.0).abs() < 1e-12);
    /// ```
    pub fn iter_mut(&mut self) -> impl Iterator<Item = (K, &mut V)> + '_ {
        self.slots
            .iter_mut()
            .enumerate()
            .filter_map(|(i, s)| s.as_mut().map(|(g, v)| (K::from_parts(i as u32, *g), v)))
    }

    /// Every key, in slot order.
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, VertexKey};
    /// let mesh = meshloom::shapes::cube();
    /// let top: SecondaryMap<VertexKey, ()> = mesh
    ///     .vertices()
    ///     .filter(|&v| mesh.position(v).is_ok_and(|p| p[2] > 0.5))
    ///     .map(|v| (v, ()))
    ///     .collect();
    /// assert_eq!(top.keys().count(), 4); // in slot order
    /// ```
    pub fn keys(&self) -> impl Iterator<Item = K> + '_ {
        self.iter().map(|(k, _)| k)
    }

    /// Every value, in slot order.
    ///
    /// ```
    /// use meshloom::{map::SecondaryMap, FaceKey};
    /// let mesh = meshloom::shapes::cube();
    /// let area: SecondaryMap<FaceKey, f64> = mesh.faces().map(|f| (f, mesh.face_area(f).unwrap())).collect();
    /// assert_eq!(area.values().sum::<f64>(), 6.0);
    /// ```
    pub fn values(&self) -> impl Iterator<Item = &V> + '_ {
        self.iter().map(|(_, v)| v)
    }
}

impl<K: ElementKey, V> std::ops::Index<K> for SecondaryMap<K, V> {
    type Output = V;

    /// The value `key` holds.
    ///
    /// # Panics
    /// If `key` holds none: use [`SecondaryMap::get`] for keys that may
    /// not.
    fn index(&self, key: K) -> &V {
        match self.get(key) {
            Some(v) => v,
            None => panic!("{key:?} holds no value in this SecondaryMap"),
        }
    }
}

impl<K: ElementKey, V> FromIterator<(K, V)> for SecondaryMap<K, V> {
    fn from_iter<T: IntoIterator<Item = (K, V)>>(iter: T) -> Self {
        let mut map = SecondaryMap::new();
        map.extend(iter);
        map
    }
}

impl<K: ElementKey, V> Extend<(K, V)> for SecondaryMap<K, V> {
    fn extend<T: IntoIterator<Item = (K, V)>>(&mut self, iter: T) {
        for (k, v) in iter {
            self.insert(k, v);
        }
    }
}

impl<K: ElementKey, V: fmt::Debug> fmt::Debug for SecondaryMap<K, V> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_map().entries(self.iter()).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{EdgeKey, FaceKey, VertexKey};

    #[test]
    fn reused_slots_do_not_leak_values() {
        let mut mesh = crate::shapes::icosphere(1);
        let mut m: SecondaryMap<FaceKey, usize> =
            mesh.faces().enumerate().map(|(i, f)| (f, i)).collect();
        assert_eq!(m.len(), mesh.face_count());
        let old = mesh.faces().nth(4).unwrap();
        assert_eq!(m.get(old), Some(&4));
        let h = mesh.halfedges().next().unwrap();
        mesh.collapse_edge(h).unwrap();
        mesh.compact();
        // The slot of `old` holds a face again, under another key.
        let new = mesh.faces().find(|f| f.index() == old.index()).unwrap();
        assert_ne!(new, old);
        assert_eq!(m.get(new), None);
        assert_eq!(m.remove(new), None);
        assert!(mesh.faces().all(|f| !m.contains_key(f)));
        // The old key still finds its own value, until the new key stores.
        assert_eq!(m.get(old), Some(&4));
        let before = m.len();
        assert_eq!(m.insert(new, 99), None);
        assert_eq!(m.len(), before);
        assert_eq!(m.get(old), None);
        assert_eq!(m[new], 99);
        *m.get_mut(new).unwrap() += 1;
        assert_eq!(m.remove(new), Some(100));
        assert!(!m.contains_key(new));
        assert_eq!(m.len(), before - 1);
    }

    #[test]
    fn insert_get_remove_clear() {
        let mesh = crate::shapes::cube();
        let mut m = SecondaryMap::<EdgeKey, f64>::default();
        assert!(m.is_empty());
        for e in mesh.edges() {
            assert_eq!(m.insert(e, mesh.edge_length(e).unwrap()), None);
        }
        assert_eq!(m.len(), 12);
        let e = mesh.edges().next().unwrap();
        assert_eq!(m.insert(e, 2.0), Some(1.0));
        assert_eq!(m.len(), 12);
        assert_eq!(
            m.keys().collect::<Vec<_>>(),
            mesh.edges().collect::<Vec<_>>()
        );
        assert_eq!(m.values().sum::<f64>(), 13.0);
        for (_, v) in m.iter_mut() {
            *v = 0.0;
        }
        assert_eq!(m.values().sum::<f64>(), 0.0);
        let mut counts = SecondaryMap::<VertexKey, u32>::new();
        let v = mesh.vertices().next().unwrap();
        *counts.get_or_insert_with(v, || 0) += 1;
        *counts.get_or_insert_with(v, || 0) += 1;
        assert_eq!(counts[v], 2);
        m.clear();
        assert!(m.is_empty());
        assert_eq!(m.get(e), None);
        assert_eq!(format!("{counts:?}"), format!("{{{v:?}: 2}}"));
    }
}
