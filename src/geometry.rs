//! Geometry over positions: the [`Point`] trait and measures (edge length,
//! face normal, area, centroid).
//!
//! Positions are an ordinary vertex attribute with the
//! [`Interpolate`](crate::attr::Interpolate) rule. The standard column
//! ([`attr::POSITION`](crate::attr::POSITION)) holds `[f64; 3]`; the `_in`
//! measures read any vertex column whose type implements [`Point`], so a
//! user can keep `[f32; 3]`, or with the optional features `glam` and
//! `nalgebra`, their 3D points and vectors (as columns with the
//! [`Interpolate`](crate::attr::Interpolate) rule); with `mint`, mint's
//! types read and write as points (they have no `Default`, so they cannot
//! be columns themselves).
//!
//! # Your own point types
//!
//! The builders take a slice of any [`Point`] type as it is, with no copy
//! loop in the caller: [`Mesh::from_polygons`](crate::Mesh::from_polygons)
//! borrows `&[[f64; 3]]` and converts other types to `f64` once, inside.
//!
//! | type | feature | versions |
//! |---|---|---|
//! | `[f64; 3]`, `[f32; 3]` | none | |
//! | `glam::Vec3`, `glam::DVec3` | `glam` | glam 0.29 to 0.34 |
//! | `nalgebra::Point3<f32/f64>`, `nalgebra::Vector3<f32/f64>` | `nalgebra` | nalgebra 0.33 to 0.35 |
//! | `mint::Point3<f32/f64>`, `mint::Vector3<f32/f64>` | `mint` | mint 0.5 |
//!
//! mint is the route that does not depend on versions: glam, nalgebra,
//! cgmath and most other math crates convert to and from mint's types
//! (their own `mint` feature), so a math crate outside the ranges above
//! still reaches meshloom through `mint::Point3`.
//!
//! ```
//! use meshloom::Mesh;
//! let faces = [[0u32, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]];
//! let f32s: Vec<[f32; 3]> = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
//! let tet = Mesh::from_polygons(&f32s, &faces)?;
//! assert!(tet.is_closed());
//! #[cfg(feature = "glam")]
//! {
//!     let v: Vec<glam::Vec3> = f32s.iter().map(|&p| glam::Vec3::from(p)).collect();
//!     assert_eq!(Mesh::from_polygons(&v, &faces)?.to_polygons(), tet.to_polygons());
//! }
//! #[cfg(feature = "nalgebra")]
//! {
//!     let n: Vec<nalgebra::Point3<f32>> = f32s.iter().map(|&p| p.into()).collect();
//!     assert_eq!(Mesh::from_polygons(&n, &faces)?.to_polygons(), tet.to_polygons());
//! }
//! #[cfg(feature = "mint")]
//! {
//!     let m: Vec<mint::Point3<f32>> = f32s.iter().map(|&p| p.into()).collect();
//!     assert_eq!(Mesh::from_polygons(&m, &faces)?.to_polygons(), tet.to_polygons());
//! }
//! # Ok::<(), meshloom::Error>(())
//! ```

use std::borrow::Cow;

use crate::attr::{Attr, Attribute, Rule};
use crate::error::{Error, Result};
use crate::keys::{EdgeKey, FaceKey, VertexKey};
use crate::layout::Vid;
use crate::mesh::Mesh;
use crate::vec3::{newell_edge, norm, normalize_or_zero, sub};

/// A 3D point type that geometry code can read and write as `[f64; 3]`.
///
/// ```
/// use meshloom::geometry::Point;
/// let p = [1.0f32, 2.0, 3.0];
/// assert_eq!(p.xyz(), [1.0, 2.0, 3.0]);
/// assert_eq!(<[f32; 3]>::from_xyz([0.5, 0.0, 1.0]), [0.5, 0.0, 1.0]);
/// ```
pub trait Point: Copy {
    /// The coordinates.
    fn xyz(&self) -> [f64; 3];
    /// A point from coordinates (rounded to the type's precision).
    fn from_xyz(p: [f64; 3]) -> Self;

    /// The coordinates of every point of a slice: borrowed where `Self` is
    /// `[f64; 3]` (the builders' own type), converted once otherwise. The
    /// builders ([`Mesh::from_polygons`](crate::Mesh::from_polygons)) take
    /// `&[P]` through this, so a caller passes its own points as they are.
    ///
    /// ```
    /// use meshloom::geometry::Point;
    /// let p = [[1.0f32, 2.0, 3.0]];
    /// assert_eq!(&*Point::slice_xyz(&p[..]), &[[1.0, 2.0, 3.0]]);
    /// let q = [[1.0f64, 2.0, 3.0]];
    /// assert!(matches!(Point::slice_xyz(&q[..]), std::borrow::Cow::Borrowed(_)));
    /// ```
    fn slice_xyz(points: &[Self]) -> Cow<'_, [[f64; 3]]>
    where
        Self: Sized,
    {
        Cow::Owned(points.iter().map(Point::xyz).collect())
    }
}

impl Point for [f64; 3] {
    #[inline]
    fn xyz(&self) -> [f64; 3] {
        *self
    }
    #[inline]
    fn from_xyz(p: [f64; 3]) -> Self {
        p
    }
    #[inline]
    fn slice_xyz(points: &[Self]) -> Cow<'_, [[f64; 3]]> {
        Cow::Borrowed(points)
    }
}

impl Point for [f32; 3] {
    #[inline]
    fn xyz(&self) -> [f64; 3] {
        self.map(f64::from)
    }
    #[inline]
    fn from_xyz(p: [f64; 3]) -> Self {
        p.map(|c| c as f32)
    }
}

#[cfg(feature = "mint")]
mod mint_points {
    use super::Point;

    macro_rules! mint_point {
        ($($t:ty),*) => {$(
            impl Point for $t {
                #[inline]
                fn xyz(&self) -> [f64; 3] {
                    [self.x.into(), self.y.into(), self.z.into()]
                }
                #[inline]
                #[allow(clippy::unnecessary_cast)]
                fn from_xyz(p: [f64; 3]) -> Self {
                    Self { x: p[0] as _, y: p[1] as _, z: p[2] as _ }
                }
            }
        )*};
    }
    mint_point!(
        mint::Point3<f64>,
        mint::Point3<f32>,
        mint::Vector3<f64>,
        mint::Vector3<f32>
    );
}

#[cfg(feature = "glam")]
mod glam_points {
    use super::Point;
    use crate::attr::{Attribute, Interpolate, Linear, Value};

    macro_rules! glam_point {
        ($t:ty, $s:ty, $variant:ident) => {
            impl Point for $t {
                #[inline]
                fn xyz(&self) -> [f64; 3] {
                    [self.x.into(), self.y.into(), self.z.into()]
                }
                #[inline]
                #[allow(clippy::unnecessary_cast)]
                fn from_xyz(p: [f64; 3]) -> Self {
                    <$t>::new(p[0] as $s, p[1] as $s, p[2] as $s)
                }
            }
            impl Linear for $t {
                #[inline]
                fn zero() -> Self {
                    <$t>::ZERO
                }
                #[inline]
                #[allow(clippy::unnecessary_cast)]
                fn add_scaled(&mut self, other: &Self, w: f64) {
                    *self += *other * (w as $s);
                }
            }
            impl Attribute for $t {
                type Rule = Interpolate;
                fn to_value(&self) -> Option<Value> {
                    Some(Value::List(
                        self.to_array()
                            .iter()
                            .map(|&c| Value::$variant(c))
                            .collect(),
                    ))
                }
                fn from_value(value: &Value) -> Option<Self> {
                    <[$s; 3]>::from_value(value).map(<$t>::from_array)
                }
                fn same_value(&self, other: &Self) -> bool {
                    self.to_array().same_value(&other.to_array())
                }
            }
        };
    }
    glam_point!(glam::Vec3, f32, F32);
    glam_point!(glam::DVec3, f64, F64);
}

#[cfg(feature = "nalgebra")]
mod nalgebra_points {
    use super::Point;
    use crate::attr::{Attribute, Interpolate, Linear, Value};

    macro_rules! nalgebra_point {
        ($t:ty, $s:ty, $variant:ident) => {
            impl Point for $t {
                #[inline]
                fn xyz(&self) -> [f64; 3] {
                    [self.x.into(), self.y.into(), self.z.into()]
                }
                #[inline]
                #[allow(clippy::unnecessary_cast)]
                fn from_xyz(p: [f64; 3]) -> Self {
                    <$t>::new(p[0] as $s, p[1] as $s, p[2] as $s)
                }
            }
            impl Linear for $t {
                #[inline]
                fn zero() -> Self {
                    <$t>::from_xyz([0.0; 3])
                }
                #[inline]
                #[allow(clippy::unnecessary_cast)]
                fn add_scaled(&mut self, other: &Self, w: f64) {
                    self.x += other.x * (w as $s);
                    self.y += other.y * (w as $s);
                    self.z += other.z * (w as $s);
                }
            }
            impl Attribute for $t {
                type Rule = Interpolate;
                fn to_value(&self) -> Option<Value> {
                    Some(Value::List(vec![
                        Value::$variant(self.x),
                        Value::$variant(self.y),
                        Value::$variant(self.z),
                    ]))
                }
                fn from_value(value: &Value) -> Option<Self> {
                    <[$s; 3]>::from_value(value).map(|[x, y, z]| <$t>::new(x, y, z))
                }
                fn same_value(&self, other: &Self) -> bool {
                    [self.x, self.y, self.z].same_value(&[other.x, other.y, other.z])
                }
            }
        };
    }
    nalgebra_point!(nalgebra::Point3<f32>, f32, F32);
    nalgebra_point!(nalgebra::Point3<f64>, f64, F64);
    nalgebra_point!(nalgebra::Vector3<f32>, f32, F32);
    nalgebra_point!(nalgebra::Vector3<f64>, f64, F64);
}

impl Mesh {
    /// The coordinates of vertex slot `v` in a point column.
    fn point_in<P: Point + Attribute, R: Rule<P>>(
        &self,
        h: &Attr<VertexKey, P, R>,
        v: Vid,
    ) -> Result<[f64; 3]> {
        self.attr(h, self.vkey(v))?
            .map(Point::xyz)
            .ok_or_else(|| Error::NoPositions)
    }

    /// The Newell vector of a face: its direction is the normal, its length
    /// twice the (projected) area.
    fn newell_in<P: Point + Attribute, R: Rule<P>>(
        &self,
        h: &Attr<VertexKey, P, R>,
        f: FaceKey,
    ) -> Result<[f64; 3]> {
        let fs = self.check_face(f)?;
        let mut n = [0.0; 3];
        for he in self.face_halfedges(fs) {
            let a = self.point_in(h, self.origin(he))?;
            let b = self.point_in(h, self.dest(he))?;
            newell_edge(&mut n, a, b);
        }
        Ok(n)
    }

    /// The length of edge `e` measured in the point column `h`.
    ///
    /// # Errors
    /// [`Error::StaleKey`], [`Error::AttributeHandle`],
    /// [`Error::NoPositions`] if an end has no value.
    pub fn edge_length_in<P: Point + Attribute, R: Rule<P>>(
        &self,
        h: &Attr<VertexKey, P, R>,
        e: EdgeKey,
    ) -> Result<f64> {
        let [x, y] = self.check_edge(e)?.halfedges();
        let a = self.point_in(h, self.origin(x))?;
        let b = self.point_in(h, self.origin(y))?;
        Ok(norm(sub(a, b)))
    }

    /// The unit normal of face `f` (Newell's method, so non-planar polygons
    /// get a best-fit normal) measured in the point column `h`; zero for a
    /// degenerate face.
    ///
    /// # Errors
    /// As [`Mesh::edge_length_in`].
    pub fn face_normal_in<P: Point + Attribute, R: Rule<P>>(
        &self,
        h: &Attr<VertexKey, P, R>,
        f: FaceKey,
    ) -> Result<[f64; 3]> {
        Ok(normalize_or_zero(self.newell_in(h, f)?))
    }

    /// The area of face `f` (exact for planar polygons) in the point column
    /// `h`.
    ///
    /// # Errors
    /// As [`Mesh::edge_length_in`].
    pub fn face_area_in<P: Point + Attribute, R: Rule<P>>(
        &self,
        h: &Attr<VertexKey, P, R>,
        f: FaceKey,
    ) -> Result<f64> {
        Ok(0.5 * norm(self.newell_in(h, f)?))
    }

    /// The centroid of face `f`'s corners in the point column `h`.
    ///
    /// # Errors
    /// As [`Mesh::edge_length_in`].
    pub fn face_centroid_in<P: Point + Attribute, R: Rule<P>>(
        &self,
        h: &Attr<VertexKey, P, R>,
        f: FaceKey,
    ) -> Result<[f64; 3]> {
        let fs = self.check_face(f)?;
        let mut c = [0.0; 3];
        let mut n = 0usize;
        for he in self.face_halfedges(fs) {
            let p = self.point_in(h, self.origin(he))?;
            for k in 0..3 {
                c[k] += p[k];
            }
            n += 1;
        }
        Ok(c.map(|x| x / n.max(1) as f64))
    }

    /// The length of edge `e`.
    ///
    /// # Errors
    /// [`Error::StaleKey`], [`Error::NoPositions`].
    ///
    /// ```
    /// let cube = meshloom::shapes::cube();
    /// let e = cube.edges().next().unwrap();
    /// assert_eq!(cube.edge_length(e)?, 1.0);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn edge_length(&self, e: EdgeKey) -> Result<f64> {
        self.edge_length_in(&self.position_attr().ok_or_else(|| Error::NoPositions)?, e)
    }

    /// The unit normal of face `f` (zero for a degenerate face).
    ///
    /// # Errors
    /// [`Error::StaleKey`], [`Error::NoPositions`].
    ///
    /// ```
    /// let cube = meshloom::shapes::cube();
    /// let f = cube.faces().next().unwrap(); // the face at z = 0
    /// assert_eq!(cube.face_normal(f)?, [0.0, 0.0, -1.0]);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn face_normal(&self, f: FaceKey) -> Result<[f64; 3]> {
        self.face_normal_in(&self.position_attr().ok_or_else(|| Error::NoPositions)?, f)
    }

    /// The area of face `f` (exact for planar polygons).
    ///
    /// # Errors
    /// [`Error::StaleKey`], [`Error::NoPositions`].
    ///
    /// ```
    /// let cube = meshloom::shapes::cube();
    /// let total: f64 = cube.faces().map(|f| cube.face_area(f).unwrap()).sum();
    /// assert!((total - 6.0).abs() < 1e-12);
    /// ```
    pub fn face_area(&self, f: FaceKey) -> Result<f64> {
        self.face_area_in(&self.position_attr().ok_or_else(|| Error::NoPositions)?, f)
    }

    /// The centroid of face `f`'s corners.
    ///
    /// # Errors
    /// [`Error::StaleKey`], [`Error::NoPositions`].
    ///
    /// ```
    /// let cube = meshloom::shapes::cube();
    /// let f = cube.faces().next().unwrap();
    /// assert_eq!(cube.face_centroid(f)?, [0.5, 0.5, 0.0]);
    /// # Ok::<(), meshloom::Error>(())
    /// ```
    pub fn face_centroid(&self, f: FaceKey) -> Result<[f64; 3]> {
        self.face_centroid_in(&self.position_attr().ok_or_else(|| Error::NoPositions)?, f)
    }
}

#[cfg(test)]
mod tests {
    use crate::VertexKey;

    #[test]
    fn f32_points_measure_like_f64() {
        let mut cube = crate::shapes::cube();
        let p32 = cube.add_vertex_attr::<[f32; 3]>("p32").unwrap();
        let keys: Vec<VertexKey> = cube.vertices().collect();
        for &v in &keys {
            let p = cube.position(v).unwrap();
            cube.set_attr(&p32, v, p.map(|c| c as f32)).unwrap();
        }
        for f in cube.faces().collect::<Vec<_>>() {
            assert_eq!(
                cube.face_area_in(&p32, f).unwrap(),
                cube.face_area(f).unwrap()
            );
            assert_eq!(
                cube.face_normal_in(&p32, f).unwrap(),
                cube.face_normal(f).unwrap()
            );
        }
        cube.clear_attr(&p32, keys[0]).unwrap();
        let e = cube.vertex(keys[0]).unwrap().edges().next().unwrap();
        assert!(cube.edge_length_in(&p32, e).is_err());
    }

    #[cfg(feature = "glam")]
    #[test]
    fn glam_positions() {
        use crate::attr::Attribute;
        use crate::geometry::Point;
        let mut cube = crate::shapes::cube();
        let g = cube.add_vertex_attr::<glam::DVec3>("g").unwrap();
        for v in cube.vertices().collect::<Vec<_>>() {
            let p = cube.position(v).unwrap();
            cube.set_attr(&g, v, glam::DVec3::from_xyz(p)).unwrap();
        }
        let f = cube.faces().next().unwrap();
        assert_eq!(cube.face_centroid_in(&g, f).unwrap(), [0.5, 0.5, 0.0]);
        let v = glam::Vec3::new(1.0, 2.0, 3.0);
        assert_eq!(glam::Vec3::from_value(&v.to_value().unwrap()), Some(v));
    }

    #[cfg(feature = "nalgebra")]
    #[test]
    fn nalgebra_positions() {
        use crate::attr::Attribute;
        use crate::geometry::Point;
        let mut cube = crate::shapes::cube();
        let n = cube.add_vertex_attr::<nalgebra::Point3<f64>>("n").unwrap();
        for v in cube.vertices().collect::<Vec<_>>() {
            let p = cube.position(v).unwrap();
            cube.set_attr(&n, v, nalgebra::Point3::from_xyz(p)).unwrap();
        }
        let f = cube.faces().next().unwrap();
        assert_eq!(cube.face_normal_in(&n, f).unwrap(), [0.0, 0.0, -1.0]);
        let e = cube.edges().next().unwrap();
        let m = cube.split_edge(e, 0.5).unwrap();
        assert_eq!(
            cube.attr(&n, m).unwrap().map(Point::xyz),
            Some(cube.position(m).unwrap())
        );
        let v = nalgebra::Vector3::<f32>::new(1.0, 2.0, 3.0);
        assert_eq!(
            nalgebra::Vector3::<f32>::from_value(&v.to_value().unwrap()),
            Some(v)
        );
    }

    #[cfg(feature = "mint")]
    #[test]
    fn mint_points() {
        use crate::geometry::Point;
        let p = mint::Point3::<f32>::from_xyz([1.0, 2.0, 3.0]);
        assert_eq!(p.xyz(), [1.0, 2.0, 3.0]);
    }
}
