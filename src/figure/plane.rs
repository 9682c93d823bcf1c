//! The page plane (product.md "Diagrams": a 3D trace is drawn in the plane that shows it best): a
//! plane of the scene with two orthonormal axes, onto which points and directions of a trace are
//! projected, and the outlines of the scene's objects in it — exact in 2D; in 3D the cross-section
//! where the plane cuts an object (solid) and the outline of its projection (faint).

use glam::{DVec2, DVec3};

use crate::geom::Vector;
use crate::shape::{Dim, Parts, Shape};

/// A plane of the scene with an origin and two orthonormal axes: page `x` and page `y` (up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PagePlane<V> {
    /// The scene point drawn at the page origin.
    pub origin: V,
    /// The scene direction drawn to the right.
    pub x: V,
    /// The scene direction drawn upwards.
    pub y: V,
    /// Added to every page position: places several panels side by side on one page.
    pub offset: DVec2,
}

impl<V: Vector> PagePlane<V> {
    /// The plane through `origin` spanned by `a` and `b`: page x along `a`, page y along the part
    /// of `b` perpendicular to `a` (Gram–Schmidt). `None` when `a` is zero or `b` parallel to it.
    #[must_use]
    pub fn spanned(origin: V, a: V, b: V) -> Option<Self> {
        let x = a.try_unit()?;
        let y = (b - x * b.dot(x)).try_unit()?;
        // Nearly parallel inputs leave a y that is mostly rounding: refuse them.
        if b.try_unit().is_some_and(|bu| bu.dot(y).abs() < 1e-9) {
            return None;
        }
        Some(Self { origin, x, y, offset: DVec2::ZERO })
    }

    /// The plane through `origin` spanned by `a` and `b`, turned within itself so that the
    /// scene's `up` is drawn upwards: page y along the part of `up` in the plane, page x
    /// perpendicular to it in the plane, on the side of `right` (so that the page is not seen
    /// from behind). [`PagePlane::spanned`] when `up` is perpendicular to the plane; `None` when
    /// that is refused.
    #[must_use]
    pub fn upright(origin: V, a: V, b: V, up: V, right: V) -> Option<Self> {
        let plane = Self::spanned(origin, a, b)?;
        let (e1, e2) = (plane.x, plane.y);
        // `up` in the plane's orthonormal basis (e1, e2); x is (q, −p) or (−q, p) in it.
        let (p, q) = (up.dot(e1), up.dot(e2));
        let Some(y) = (e1 * p + e2 * q).try_unit() else { return Some(plane) };
        let (p, q) = (y.dot(e1), y.dot(e2));
        let x = e1 * q - e2 * p;
        let x = if x.dot(right) < 0.0 { -x } else { x };
        Some(Self { origin, x, y, offset: DVec2::ZERO })
    }

    /// The same plane with its page positions shifted by `offset`.
    #[must_use]
    pub fn shifted(self, offset: DVec2) -> Self {
        Self { offset, ..self }
    }

    /// The page position of scene point `p`: its coordinates along x and y (in 3D, the orthogonal
    /// projection onto the plane), plus the page offset.
    #[must_use]
    pub fn point(&self, p: V) -> DVec2 {
        let d = p - self.origin;
        DVec2::new(d.dot(self.x), d.dot(self.y)) + self.offset
    }

    /// The page components of scene direction `d` (its projection; shorter when `d` leaves the plane).
    #[must_use]
    pub fn dir(&self, d: V) -> DVec2 {
        DVec2::new(d.dot(self.x), d.dot(self.y))
    }

    /// How far `p` lies off the plane: the length of the part of `p − origin` that the projection
    /// drops (0 in 2D).
    #[must_use]
    pub fn off_plane(&self, p: V) -> f64 {
        let d = p - self.origin;
        let kept = self.x * d.dot(self.x) + self.y * d.dot(self.y);
        (d - kept).length()
    }
}

/// An outline on the page, in page coordinates.
#[derive(Clone, Debug, PartialEq)]
pub enum Outline {
    /// A circle.
    Circle {
        /// Centre.
        center: DVec2,
        /// Radius.
        radius: f64,
    },
    /// A closed polygon.
    Polygon(Vec<DVec2>),
    /// An open polyline (a 2D segment, a triangle cut by the plane).
    Path(Vec<DVec2>),
    /// An unbounded line (a plane cut by the page plane; a 2D line), drawn clipped to the view.
    Line {
        /// A point of the line.
        point: DVec2,
        /// Its unit direction.
        dir: DVec2,
    },
}

impl Outline {
    /// Points that bound the outline (none for an unbounded line), for fitting the view.
    #[must_use]
    pub fn extent(&self) -> Vec<DVec2> {
        match self {
            Self::Circle { center, radius } => {
                vec![*center - DVec2::splat(*radius), *center + DVec2::splat(*radius)]
            }
            Self::Polygon(points) | Self::Path(points) => points.clone(),
            Self::Line { .. } => Vec::new(),
        }
    }

    /// The distance on the page between segment `a`–`b` and the outline: 0 when they meet (the
    /// segment crosses or touches it), else the least distance between their points (for a
    /// circle `|c − ab| − r` outside it, `r − max |c − a|, |c − b|` inside).
    #[must_use]
    pub fn gap(&self, a: DVec2, b: DVec2) -> f64 {
        let edges = |points: &[DVec2], closed: bool| {
            let mut edges: Vec<(DVec2, DVec2)> = points.windows(2).map(|w| (w[0], w[1])).collect();
            if closed && points.len() > 2 {
                edges.push((points[points.len() - 1], points[0]));
            }
            edges.iter().map(|(c, d)| segment_gap(a, b, *c, *d)).fold(f64::INFINITY, f64::min)
        };
        match self {
            Self::Circle { center, radius } => {
                let (near, far) =
                    (point_to_segment(*center, a, b), a.distance(*center).max(b.distance(*center)));
                if near >= *radius {
                    near - radius
                } else if far <= *radius {
                    radius - far
                } else {
                    0.0
                }
            }
            Self::Polygon(points) => edges(points, true),
            Self::Path(points) => edges(points, false),
            Self::Line { point, dir } => {
                let normal = dir.perp();
                let (da, db) = ((a - *point).dot(normal), (b - *point).dot(normal));
                if da * db <= 0.0 {
                    0.0
                } else {
                    da.abs().min(db.abs())
                }
            }
        }
    }
}

/// The distance from `p` to the segment `a`–`b`.
fn point_to_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t =
        if ab.length_squared() > 0.0 { ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
    p.distance(a + ab * t)
}

/// The distance between segments `a`–`b` and `c`–`d`: 0 when they cross, else the least distance
/// from an end of one to the other (0 too when they touch or overlap).
#[must_use]
pub fn segment_gap(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> f64 {
    let side = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    if side(a, b, c) * side(a, b, d) < 0.0 && side(c, d, a) * side(c, d, b) < 0.0 {
        return 0.0;
    }
    [
        point_to_segment(a, c, d),
        point_to_segment(b, c, d),
        point_to_segment(c, a, b),
        point_to_segment(d, a, b),
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min)
}

/// An object's outline and what it is.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectOutline {
    /// The outline.
    pub outline: Outline,
    /// True for the cut of the object by the page plane (2D objects are always their own cut);
    /// false for the outline of the object's projection, drawn faint.
    pub section: bool,
}

/// A dimension whose objects can be outlined on a page plane.
pub trait Planar: Dim {
    /// The outlines of `shape` on `plane`: in 2D the shape itself; in 3D its cross-section (when
    /// the plane cuts it) and, for bounded shapes, the outline of its projection when that differs.
    fn outlines(shape: &Shape<Self>, plane: &PagePlane<Self>) -> Vec<ObjectOutline>;
}

impl Planar for DVec2 {
    fn outlines(shape: &Shape<Self>, plane: &PagePlane<Self>) -> Vec<ObjectOutline> {
        let outline = match shape {
            Shape::Sphere(s) => Outline::Circle { center: plane.point(s.center), radius: s.radius },
            Shape::Plane(p) => Outline::Line {
                point: plane.point(p.point),
                dir: plane.dir(DVec2::new(p.normal.y, -p.normal.x)),
            },
            Shape::Box(b) => Outline::Polygon(
                [b.min, DVec2::new(b.max.x, b.min.y), b.max, DVec2::new(b.min.x, b.max.y)]
                    .iter()
                    .map(|p| plane.point(*p))
                    .collect(),
            ),
            Shape::Facet(f) => {
                let points = f.vertices.iter().map(|p| plane.point(*p)).collect();
                if f.closed {
                    Outline::Polygon(points)
                } else {
                    Outline::Path(points)
                }
            }
            // There are no meshes in 2D.
            Shape::Mesh(m) => match *m {},
        };
        vec![ObjectOutline { outline, section: true }]
    }
}

impl Planar for DVec3 {
    fn outlines(shape: &Shape<Self>, plane: &PagePlane<Self>) -> Vec<ObjectOutline> {
        let normal = plane.x.cross(plane.y);
        let mut out = Vec::new();
        match shape {
            Shape::Sphere(s) => {
                let center = plane.point(s.center);
                let off = (s.center - plane.origin).dot(normal);
                let cut = (s.radius * s.radius - off * off).max(0.0).sqrt();
                if off.abs() < s.radius {
                    out.push(ObjectOutline {
                        outline: Outline::Circle { center, radius: cut },
                        section: true,
                    });
                }
                if cut < 0.97 * s.radius {
                    out.push(ObjectOutline {
                        outline: Outline::Circle { center, radius: s.radius },
                        section: false,
                    });
                }
            }
            Shape::Plane(p) => {
                // The line {(a, b): a·(x·m) + b·(y·m) = (P − O)·m} of the page.
                let m = DVec2::new(plane.x.dot(p.normal), plane.y.dot(p.normal));
                let len2 = m.length_squared();
                if len2 > 1e-12 {
                    let c = (p.point - plane.origin).dot(p.normal);
                    let point = m * (c / len2) + plane.offset;
                    let dir = m.perp() / len2.sqrt();
                    out.push(ObjectOutline { outline: Outline::Line { point, dir }, section: true });
                }
            }
            Shape::Box(b) => {
                let corners: Vec<DVec3> = (0..8)
                    .map(|k| {
                        DVec3::new(
                            if k & 1 == 0 { b.min.x } else { b.max.x },
                            if k & 2 == 0 { b.min.y } else { b.max.y },
                            if k & 4 == 0 { b.min.z } else { b.max.z },
                        )
                    })
                    .collect();
                // The 12 edges join corners that differ in one bit.
                let edges: Vec<(usize, usize)> = (0..8)
                    .flat_map(|a| [1, 2, 4].map(move |bit| (a, a | bit)))
                    .filter(|(a, b)| a != b)
                    .collect();
                let cut = section(plane, normal, &corners, &edges);
                if cut.len() >= 3 {
                    out.push(ObjectOutline { outline: Outline::Polygon(convex_hull(cut)), section: true });
                }
                let hull = convex_hull(corners.iter().map(|c| plane.point(*c)).collect());
                out.push(ObjectOutline { outline: Outline::Polygon(hull), section: false });
            }
            Shape::Facet(t) => {
                let cut = section(plane, normal, &t.vertices, &[(0, 1), (1, 2), (2, 0)]);
                if cut.len() >= 2 {
                    out.push(ObjectOutline { outline: Outline::Path(cut[..2].to_vec()), section: true });
                }
                let projected = t.vertices.iter().map(|p| plane.point(*p)).collect();
                out.push(ObjectOutline { outline: Outline::Polygon(projected), section: false });
            }
            Shape::Mesh(m) => {
                // Each triangle the plane cuts adds a segment of the section; the projection's
                // outline is drawn as the convex hull of every vertex.
                let mut all = Vec::new();
                for k in 0..m.count() {
                    let vertices = m.points(k);
                    let cut = section(plane, normal, &vertices, &[(0, 1), (1, 2), (2, 0)]);
                    if cut.len() >= 2 {
                        out.push(ObjectOutline { outline: Outline::Path(cut[..2].to_vec()), section: true });
                    }
                    all.extend(vertices.iter().map(|p| plane.point(*p)));
                }
                out.push(ObjectOutline { outline: Outline::Polygon(convex_hull(all)), section: false });
            }
        }
        out
    }
}

/// Where the edges of a convex solid or face cross the plane, on the page (duplicates removed).
fn section(
    plane: &PagePlane<DVec3>,
    normal: DVec3,
    vertices: &[DVec3],
    edges: &[(usize, usize)],
) -> Vec<DVec2> {
    let side: Vec<f64> = vertices.iter().map(|v| (*v - plane.origin).dot(normal)).collect();
    let mut points: Vec<DVec2> = Vec::new();
    for &(a, b) in edges {
        let (sa, sb) = (side[a], side[b]);
        if (sa <= 0.0 && sb >= 0.0) || (sa >= 0.0 && sb <= 0.0) {
            let p = if sa - sb == 0.0 {
                vertices[a]
            } else {
                vertices[a] + (vertices[b] - vertices[a]) * (sa / (sa - sb))
            };
            let q = plane.point(p);
            if points.iter().all(|o| (*o - q).length() > 1e-9) {
                points.push(q);
            }
        }
    }
    points
}

/// The convex hull of page points, counter-clockwise (Andrew's monotone chain).
#[must_use]
pub fn convex_hull(mut points: Vec<DVec2>) -> Vec<DVec2> {
    points.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    points.dedup_by(|a, b| (*a - *b).length() < 1e-12);
    if points.len() < 3 {
        return points;
    }
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<DVec2> = Vec::with_capacity(points.len() * 2);
    for pass in 0..2 {
        let start = hull.len();
        let ordered: Box<dyn Iterator<Item = &DVec2>> =
            if pass == 0 { Box::new(points.iter()) } else { Box::new(points.iter().rev()) };
        for &p in ordered {
            while hull.len() >= start + 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::sphere::Sphere;

    #[test]
    fn spanned_planes_are_orthonormal() {
        let p =
            PagePlane::spanned(DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(1.0, 1.0, 0.0)).unwrap();
        assert!((p.x.length() - 1.0).abs() < 1e-12 && (p.y.length() - 1.0).abs() < 1e-12);
        assert!(p.x.dot(p.y).abs() < 1e-12);
        assert!(PagePlane::spanned(DVec3::ZERO, DVec3::X, DVec3::X * 3.0).is_none());
        assert_eq!(p.point(DVec3::new(1.0, 2.0, 5.0)), DVec2::new(1.0, 2.0));
        assert!((p.off_plane(DVec3::new(1.0, 2.0, 5.0)) - 5.0).abs() < 1e-12);
    }

    #[test]
    fn an_upright_plane_draws_the_scenes_up_upwards_and_keeps_its_right_side() {
        // The plane of a shadow ray L along (1, 0, 1) and a floor's normal (0, 1, 0): spanned
        // from L, the floor's normal is drawn at 45°; upright, it is drawn straight up.
        let (l, n) = (DVec3::new(1.0, 0.0, 1.0), DVec3::Y);
        let tilted = PagePlane::spanned(DVec3::ZERO, l + n, n).unwrap();
        assert!(tilted.dir(n).x.abs() > 0.5);
        let p = PagePlane::upright(DVec3::ZERO, l + n, n, DVec3::Y, DVec3::X).unwrap();
        assert!((p.dir(DVec3::Y) - DVec2::new(0.0, 1.0)).length() < 1e-12);
        assert!(p.x.dot(p.y).abs() < 1e-12 && (p.x.length() - 1.0).abs() < 1e-12);
        // Page x lies in the plane and on the side of `right`.
        assert!((p.x - l.normalize()).length() < 1e-12);
        let mirrored = PagePlane::upright(DVec3::ZERO, l + n, n, DVec3::Y, -DVec3::X).unwrap();
        assert!((mirrored.x + l.normalize()).length() < 1e-12);
        // `up` perpendicular to the plane: the spanned plane as it is.
        let flat = PagePlane::upright(DVec3::ZERO, DVec3::X, DVec3::Z, DVec3::Y, DVec3::X).unwrap();
        assert_eq!((flat.x, flat.y), (DVec3::X, DVec3::Z));
    }

    #[test]
    fn a_sphere_cut_off_centre_gives_a_smaller_circle_and_its_silhouette() {
        let plane = PagePlane::spanned(DVec3::ZERO, DVec3::X, DVec3::Y).unwrap();
        let shape = Shape::Sphere(Sphere { center: DVec3::new(0.0, 0.0, 0.6), radius: 1.0 });
        let outlines = DVec3::outlines(&shape, &plane);
        assert_eq!(outlines.len(), 2);
        let Outline::Circle { radius, .. } = outlines[0].outline else { panic!() };
        assert!((radius - 0.8).abs() < 1e-12);
        assert!(outlines[0].section && !outlines[1].section);
    }

    #[test]
    // A segment that meets an outline has a gap of exactly 0.
    #[allow(clippy::float_cmp)]
    fn gaps_between_a_segment_and_outlines() {
        let v = DVec2::new;
        let circle = Outline::Circle { center: v(0.0, 0.0), radius: 1.0 };
        assert!((circle.gap(v(-2.0, 1.5), v(2.0, 1.5)) - 0.5).abs() < 1e-12);
        assert_eq!(circle.gap(v(-2.0, 0.5), v(2.0, 0.5)), 0.0);
        assert!((circle.gap(v(-0.2, 0.0), v(0.2, 0.0)) - 0.8).abs() < 1e-12);
        let square = Outline::Polygon(vec![v(0.0, 0.0), v(1.0, 0.0), v(1.0, 1.0), v(0.0, 1.0)]);
        assert!((square.gap(v(-1.0, 1.25), v(2.0, 1.25)) - 0.25).abs() < 1e-12);
        assert_eq!(square.gap(v(-1.0, 0.5), v(2.0, 0.5)), 0.0);
        let line = Outline::Line { point: v(0.0, -1.0), dir: v(1.0, 0.0) };
        assert!((line.gap(v(0.0, 0.0), v(3.0, 2.0)) - 1.0).abs() < 1e-12);
        assert_eq!(line.gap(v(0.0, 0.0), v(0.0, -2.0)), 0.0);
        // Collinear segments apart are apart; touching ones meet.
        assert!((segment_gap(v(0.0, 0.0), v(1.0, 0.0), v(2.0, 0.0), v(3.0, 0.0)) - 1.0).abs() < 1e-12);
        assert_eq!(segment_gap(v(0.0, 0.0), v(1.0, 0.0), v(1.0, 0.0), v(1.0, 1.0)), 0.0);
    }

    #[test]
    fn hull_of_a_square_with_an_inner_point() {
        let pts = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(0.5, 0.5),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
        ];
        assert_eq!(convex_hull(pts).len(), 4);
    }
}
