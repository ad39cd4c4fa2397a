//! `--triangulate`: the polygons a reader kept ([`super::ReadOptions::triangulate`]) fanned into
//! triangles, or refused with the reason.
//!
//! A polygon `v0 v1 … v(k−1)` becomes the triangles `(v0, vi, vi+1)` for `i = 1..k−2`, in that
//! order, in place of the polygon in the listing: each triangle keeps the polygon's winding
//! (orientation), its line, and its listed attributes (labels, fields, colours). Fanning from
//! one vertex is right only for a convex planar polygon, so each polygon is checked first and
//! refused, naming it and the reason, when
//! - there are no coordinates, or they have other than 2 or 3 components;
//! - a vertex id is repeated;
//! - it is degenerate: two consecutive vertices coincide, three consecutive vertices are
//!   collinear (a zero-area triangle would result), or its area is zero;
//! - it is not planar: a vertex lies farther than [`PLANAR_TOLERANCE`] × the polygon's size
//!   (its largest distance from its first vertex) from its plane (the plane through its
//!   centroid normal to its vector area, Newell's normal);
//! - it is not convex: it turns the other way at a vertex, or winds around more than once (a
//!   star polygon).
//!
//! Costs: O(k) time per polygon of k vertices; the new listing is built once (ids, offsets,
//! lines and the listed attributes at their new size), after which the input's arrays are freed.

use super::{RawInput, ReadErrorKind};
use crate::error::show;

/// How far (relative to the polygon's size, its largest distance from its first vertex) a vertex
/// may lie off the polygon's plane: `1e-6`, room for rounding of coordinates computed in double
/// precision or stored as 32-bit floats (relative precision 6e-8), not for a bent quad.
pub const PLANAR_TOLERANCE: f64 = 1e-6;

/// How small the sine of a turn (relative to its two edges' lengths) may be before three
/// consecutive vertices count as collinear.
const COLLINEAR_SINE: f64 = 1e-12;

/// At most this many ids are shown when a polygon is named in a message.
const SHOWN_IDS: usize = 8;

/// Replaces every polygon of `raw` (listed in `raw.polygons`) by its fan of triangles, or
/// returns the line of the first polygon that cannot be fanned and why.
pub(crate) fn fan_polygons(raw: RawInput) -> Result<RawInput, (u32, ReadErrorKind)> {
    if raw.polygons.at.is_empty() {
        return Ok(raw);
    }
    let n = raw.simplex_count();
    for &p in &raw.polygons.at {
        check(&raw, p).map_err(|why| {
            (
                raw.lines[p],
                ReadErrorKind::Triangulation(format!("{}: {why}", name(&raw, p))),
            )
        })?;
    }
    let extra: usize = raw
        .polygons
        .at
        .iter()
        .map(|&p| raw.simplex(p).len() - 3)
        .sum();
    let no_room = |what| move |b| super::no_room(what)(b);
    let mut out = RawInput::new();
    out.vertex_count = raw.vertex_count;
    out.try_reserve(n + extra, raw.ids.len() + 2 * extra)
        .map_err(|k| (0, k))?;
    let mut picks: Vec<usize> =
        super::try_with_capacity(n + extra, "the triangles' listings").map_err(|k| (0, k))?;
    let mut polygons = raw.polygons.at.iter().peekable();
    for i in 0..n {
        let ids = raw.simplex(i);
        let line = raw.lines[i];
        if polygons.next_if_eq(&&i).is_some() {
            for j in 1..ids.len() - 1 {
                out.try_push(&[ids[0], ids[j], ids[j + 1]], line)
                    .map_err(|k| (line, k))?;
                crate::alloc::try_push(&mut picks, i)
                    .map_err(|b| (line, no_room("the triangles' listings")(b)))?;
            }
        } else {
            out.try_push(ids, line).map_err(|k| (line, k))?;
            crate::alloc::try_push(&mut picks, i)
                .map_err(|b| (line, no_room("the triangles' listings")(b)))?;
        }
    }
    let RawInput {
        coords,
        mut attributes,
        ..
    } = raw;
    out.coords = coords;
    // A listed attribute of another length is the complex's to refuse (with its message).
    let consistent = attributes
        .iter()
        .all(|a| a.location != crate::complex::Location::Listed || a.element_count() == n);
    if consistent {
        attributes.pick_listed(picks.iter().copied());
    }
    out.attributes = attributes;
    Ok(out)
}

/// `element #i (a k-gon [v0 v1 ...])`: the polygon in messages, its ids capped.
fn name(raw: &RawInput, p: usize) -> String {
    let ids = raw.simplex(p);
    let shown = if ids.len() > SHOWN_IDS {
        format!("{} ...]", show(&ids[..SHOWN_IDS]).trim_end_matches(']'))
    } else {
        show(ids)
    };
    format!("polygon #{p} ({} vertices {shown})", ids.len())
}

/// Why polygon `p` of `raw` cannot be fanned, if it cannot.
fn check(raw: &RawInput, p: usize) -> Result<(), String> {
    let ids = raw.simplex(p);
    let Some(coords) = &raw.coords else {
        return Err("the file has no vertex coordinates to check it is convex and planar".into());
    };
    if !(2..=3).contains(&coords.dim) {
        return Err(format!(
            "its coordinates have {} components; only 2 or 3 are fanned",
            coords.dim
        ));
    }
    for (j, v) in ids.iter().enumerate() {
        if ids[..j].contains(v) {
            return Err(format!("vertex {v} is repeated"));
        }
    }
    let mut points = Vec::with_capacity(ids.len());
    for &v in ids {
        let at = v as usize * coords.dim;
        let Some(c) = coords.data.get(at..at + coords.dim) else {
            return Err(format!("vertex {v} has no coordinates"));
        };
        points.push([c[0], c[1], if coords.dim == 3 { c[2] } else { 0.0 }]);
    }
    shape(&points).map_err(|why| why.describe(ids))
}

/// Why a polygon's points cannot be fanned from the first.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Unfit {
    /// Points `i` and `i + 1` (cyclically) coincide.
    Coincide(usize),
    /// Points `i − 1`, `i`, `i + 1` (cyclically) are collinear.
    Collinear(usize),
    /// The vector area is zero.
    ZeroArea,
    /// Point `i` lies `distance` off the plane, beyond the tolerance `allowed`.
    NotPlanar {
        i: usize,
        distance: f64,
        allowed: f64,
    },
    /// The polygon turns the other way at point `i`.
    Reflex(usize),
    /// Every turn is the same way but the boundary winds `turns` times around.
    Winds(u32),
}

impl Unfit {
    fn describe(self, ids: &[u32]) -> String {
        let k = ids.len();
        let id = |i: usize| ids[i % k];
        match self {
            Unfit::Coincide(i) => format!(
                "degenerate: vertices {} and {} are at the same point",
                id(i),
                id(i + 1)
            ),
            Unfit::Collinear(i) => format!(
                "degenerate: vertices {}, {} and {} are collinear",
                id(i + k - 1),
                id(i),
                id(i + 1)
            ),
            Unfit::ZeroArea => "degenerate: its area is zero".into(),
            Unfit::NotPlanar {
                i,
                distance,
                allowed,
            } => format!(
                "not planar: vertex {} is {distance:.3e} off its plane (tolerance {allowed:.3e}, \
                 1e-6 × its size)",
                id(i)
            ),
            Unfit::Reflex(i) => format!("not convex: it turns the other way at vertex {}", id(i)),
            Unfit::Winds(w) => format!("not convex: its boundary winds {w} times around"),
        }
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Whether the polygon through `points` (at least 3, in order) is convex and planar, so that
/// the fan from its first point covers it; else the first reason found.
pub(crate) fn shape(points: &[[f64; 3]]) -> Result<(), Unfit> {
    let k = points.len();
    let at = |i: usize| points[i % k];
    for i in 0..k {
        if at(i) == at(i + 1) {
            return Err(Unfit::Coincide(i));
        }
    }
    // Newell's vector area, about the first point (for precision).
    let mut area = [0.0; 3];
    for i in 1..k - 1 {
        let t = cross(sub(at(i), at(0)), sub(at(i + 1), at(0)));
        area = [area[0] + t[0], area[1] + t[1], area[2] + t[2]];
    }
    let size = points
        .iter()
        .map(|&q| norm(sub(q, at(0))))
        .fold(0.0, f64::max);
    let a = norm(area);
    if a.is_nan() || a <= COLLINEAR_SINE * size * size {
        return Err(Unfit::ZeroArea);
    }
    let normal = [area[0] / a, area[1] / a, area[2] / a];
    let mut centre = [0.0; 3];
    for q in points {
        centre = [centre[0] + q[0], centre[1] + q[1], centre[2] + q[2]];
    }
    let centre = centre.map(|c| c / k as f64);
    let allowed = PLANAR_TOLERANCE * size;
    for (i, &q) in points.iter().enumerate() {
        let distance = dot(sub(q, centre), normal).abs();
        if distance > allowed {
            return Err(Unfit::NotPlanar {
                i,
                distance,
                allowed,
            });
        }
    }
    let mut turned = 0.0;
    for i in 0..k {
        let before = sub(at(i + k), at(i + k - 1));
        let after = sub(at(i + 1), at(i));
        let sine = dot(cross(before, after), normal);
        let cosine = dot(before, after);
        if sine.abs() <= COLLINEAR_SINE * norm(before) * norm(after) {
            return Err(Unfit::Collinear(i));
        }
        if sine < 0.0 {
            return Err(Unfit::Reflex(i));
        }
        turned += sine.atan2(cosine);
    }
    let winds = (turned / std::f64::consts::TAU).round();
    if winds != 1.0 {
        return Err(Unfit::Winds(winds as u32));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::complex::{Attribute, Coords, Location, Values};
    use proptest::prelude::*;
    use std::f64::consts::TAU;

    /// The area of the planar polygon `q` (2D), by the shoelace formula: the oracle.
    fn shoelace(q: &[[f64; 2]]) -> f64 {
        let k = q.len();
        (0..k)
            .map(|i| q[i][0] * q[(i + 1) % k][1] - q[(i + 1) % k][0] * q[i][1])
            .sum::<f64>()
            / 2.0
    }

    /// Whether the 2D polygon `q` (counter-clockwise) is strictly convex, by brute force: every
    /// other point strictly left of every edge.
    fn convex_brute(q: &[[f64; 2]]) -> bool {
        let k = q.len();
        (0..k).all(|i| {
            let (a, b) = (q[i], q[(i + 1) % k]);
            (0..k).filter(|&j| j != i && j != (i + 1) % k).all(|j| {
                let c = q[j];
                (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 1e-9
            })
        })
    }

    /// A plane in space: an origin and an orthonormal pair, from three angles and an offset.
    fn frame(angles: [f64; 3], origin: [f64; 3]) -> ([f64; 3], [f64; 3], [f64; 3]) {
        let [a, b, c] = angles;
        // A rotation matrix's first two columns (Z-Y-Z Euler angles).
        let (ca, sa, cb, sb, cc, sc) = (a.cos(), a.sin(), b.cos(), b.sin(), c.cos(), c.sin());
        let u = [ca * cb * cc - sa * sc, sa * cb * cc + ca * sc, -sb * cc];
        let v = [-ca * cb * sc - sa * cc, -sa * cb * sc + ca * cc, sb * sc];
        (origin, u, v)
    }

    fn place(f: &([f64; 3], [f64; 3], [f64; 3]), p: [f64; 2]) -> [f64; 3] {
        let (o, u, v) = f;
        [0, 1, 2].map(|c| o[c] + p[0] * u[c] + p[1] * v[c])
    }

    /// Points on an ellipse at increasing angles: a strictly convex polygon (counter-clockwise).
    fn ellipse(gaps: &[f64], radii: (f64, f64), start: f64) -> Vec<[f64; 2]> {
        let total: f64 = gaps.iter().sum();
        let mut angle = start;
        gaps.iter()
            .map(|g| {
                let p = [radii.0 * angle.cos(), radii.1 * angle.sin()];
                angle += g / total * TAU;
                p
            })
            .collect()
    }

    /// A listing of the one polygon `q` (placed in space by `f`) with a listed label 7.
    fn listing(points: &[[f64; 3]]) -> RawInput {
        let mut raw = RawInput::new();
        raw.vertex_count = Some(points.len() as u32);
        raw.coords = Some(Coords {
            dim: 3,
            data: points.iter().flatten().copied().collect(),
        });
        raw.push(&[0, 1], 1);
        let ids: Vec<u32> = (0..points.len() as u32).collect();
        raw.polygons.at.push(1);
        raw.push(&ids, 2);
        raw.attributes
            .insert(Attribute::labels("ref", Location::Listed, vec![3, 7]));
        raw
    }

    fn gaps(k: std::ops::Range<usize>) -> impl Strategy<Value = Vec<f64>> {
        // No gap above half the turn (at most 1/(1 + 0.5 × 2)), so that the centre is inside.
        prop::collection::vec(0.5f64..1.0, k)
    }

    proptest! {
        /// Random strictly convex polygons (points on an ellipse) in random planes: the fan
        /// covers the polygon (its triangles' areas sum to the shoelace area of the 2D polygon),
        /// every triangle's normal is the plane's (winding kept), the fan starts at the first
        /// vertex and each triangle carries the polygon's label.
        #[test]
        fn fans_of_random_convex_polygons_in_random_planes_cover_them(
            g in gaps(3..12),
            rx in 0.5f64..20.0, ry in 0.5f64..20.0, start in 0.0f64..TAU,
            angles in prop::array::uniform3(0.0f64..TAU),
            origin in prop::array::uniform3(-100.0f64..100.0),
        ) {
            let flat = ellipse(&g, (rx, ry), start);
            prop_assume!(convex_brute(&flat));
            let f = frame(angles, origin);
            let points: Vec<[f64; 3]> = flat.iter().map(|&p| place(&f, p)).collect();
            let out = fan_polygons(listing(&points)).unwrap();
            let k = points.len();
            prop_assert_eq!(out.simplex_count(), 1 + k - 2);
            prop_assert_eq!(out.simplex(0), &[0, 1][..]);
            let normal = cross(f.1, f.2);
            let mut sum = 0.0;
            for t in 1..out.simplex_count() {
                let ids = out.simplex(t);
                prop_assert_eq!(ids[0], 0);
                prop_assert_eq!(out.lines[t], 2);
                let [a, b, c] = [0, 1, 2].map(|j| points[ids[j] as usize]);
                let n = cross(sub(b, a), sub(c, a));
                // Same direction as the plane's normal: the winding is kept.
                prop_assert!(dot(n, normal) > 0.0);
                prop_assert!(norm(cross(n, normal)) <= 1e-9 * norm(n));
                sum += norm(n) / 2.0;
            }
            let want = shoelace(&flat);
            prop_assert!((sum - want).abs() <= 1e-9 * want, "{} against {}", sum, want);
            let labels = out.attributes.get("ref", Location::Listed).unwrap();
            let mut expected = vec![3];
            expected.resize(k - 1, 7);
            prop_assert_eq!(&labels.values, &Values::I32(expected));
        }

        /// Random non-convex polygons (a convex one with one vertex pulled inside, past the
        /// chord of its neighbours) in random planes are refused as not convex.
        #[test]
        fn random_non_convex_polygons_are_refused(
            g in gaps(4..12),
            rx in 0.5f64..20.0, ry in 0.5f64..20.0, start in 0.0f64..TAU,
            which in 0usize..100, pull in 0.05f64..0.9,
            angles in prop::array::uniform3(0.0f64..TAU),
            origin in prop::array::uniform3(-100.0f64..100.0),
        ) {
            let mut flat = ellipse(&g, (rx, ry), start);
            let k = flat.len();
            let i = which % k;
            let (a, b) = (flat[(i + k - 1) % k], flat[(i + 1) % k]);
            let mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
            // Past the chord towards the centre (the origin, inside): a reflex vertex.
            flat[i] = [mid[0] * (1.0 - pull), mid[1] * (1.0 - pull)];
            prop_assume!(!convex_brute(&flat));
            let f = frame(angles, origin);
            let points: Vec<[f64; 3]> = flat.iter().map(|&p| place(&f, p)).collect();
            let e = fan_polygons(listing(&points)).unwrap_err();
            prop_assert_eq!(e.0, 2);
            prop_assert!(e.1.to_string().contains("not convex"), "{}", e.1);
        }

        /// Random convex polygons with one vertex lifted off their plane by more than the
        /// tolerance are refused as not planar; lifted by much less, they are fanned.
        #[test]
        fn random_non_planar_polygons_are_refused(
            g in gaps(4..12),
            rx in 0.5f64..20.0, ry in 0.5f64..20.0, start in 0.0f64..TAU,
            which in 0usize..100, lift in 1e-4f64..1.0,
            angles in prop::array::uniform3(0.0f64..TAU),
            origin in prop::array::uniform3(-100.0f64..100.0),
        ) {
            let flat = ellipse(&g, (rx, ry), start);
            prop_assume!(convex_brute(&flat));
            let f = frame(angles, origin);
            let normal = cross(f.1, f.2);
            let size = rx.max(ry);
            let mut points: Vec<[f64; 3]> = flat.iter().map(|&p| place(&f, p)).collect();
            let i = which % points.len();
            let bent = |h: f64| {
                let mut p = points.clone();
                p[i] = [0, 1, 2].map(|c| p[i][c] + h * size * normal[c]);
                p
            };
            let e = fan_polygons(listing(&bent(lift))).unwrap_err();
            prop_assert!(e.1.to_string().contains("not planar"), "{}", e.1);
            points = bent(1e-9);
            prop_assert!(fan_polygons(listing(&points)).is_ok());
        }
    }

    fn refusal(points: &[[f64; 3]]) -> String {
        fan_polygons(listing(points)).unwrap_err().1.to_string()
    }

    /// A polygon in the plane z = 0 from its (x, y) corners.
    fn planar(xy: &[(f64, f64)]) -> Vec<[f64; 3]> {
        xy.iter().map(|&(x, y)| [x, y, 0.0]).collect()
    }

    const UNIT_SQUARE: [(f64, f64); 4] = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];

    #[test]
    fn degenerate_polygons_are_refused_with_the_reason() {
        let sq = planar(&UNIT_SQUARE);
        assert!(fan_polygons(listing(&sq)).is_ok());
        let mut coincide = sq;
        coincide[2] = coincide[1];
        assert!(refusal(&coincide).contains("vertices 1 and 2 are at the same point"));
        let collinear = planar(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (1.0, 1.0)]);
        assert!(refusal(&collinear).contains("vertices 0, 1 and 2 are collinear"));
        let flat = planar(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0)]);
        assert!(refusal(&flat).contains("area is zero"));
        // A pentagram: every turn the same way, but it winds twice.
        let star: Vec<[f64; 3]> = (0..5)
            .map(|i| {
                let a = TAU * (2 * i) as f64 / 5.0;
                [a.cos(), a.sin(), 0.0]
            })
            .collect();
        assert!(refusal(&star).contains("winds 2 times"));
    }

    #[test]
    fn repeated_vertices_and_missing_coordinates_are_refused() {
        let sq = planar(&UNIT_SQUARE);
        let mut raw = listing(&sq);
        raw.ids[2 + 3] = 1;
        let e = fan_polygons(raw).unwrap_err().1.to_string();
        assert_eq!(
            e,
            "cannot triangulate polygon #1 (4 vertices [0 1 2 1]): vertex 1 is repeated"
        );
        let mut raw = listing(&sq);
        raw.coords = None;
        let e = fan_polygons(raw).unwrap_err().1.to_string();
        assert!(e.contains("no vertex coordinates"), "{e}");
        let mut raw = listing(&sq);
        raw.ids[2 + 3] = 9;
        let e = fan_polygons(raw).unwrap_err().1.to_string();
        assert!(e.contains("vertex 9 has no coordinates"), "{e}");
    }

    #[test]
    fn two_dimensional_coordinates_are_fanned() {
        let mut raw = RawInput::new();
        raw.coords = Some(Coords {
            dim: 2,
            data: vec![0.0, 0.0, 2.0, 0.0, 2.0, 1.0, 1.0, 2.0, 0.0, 1.0],
        });
        raw.polygons.at.push(0);
        raw.push(&[0, 1, 2, 3, 4], 5);
        let out = fan_polygons(raw).unwrap();
        let got: Vec<&[u32]> = (0..out.simplex_count()).map(|i| out.simplex(i)).collect();
        assert_eq!(got, [&[0, 1, 2][..], &[0, 2, 3], &[0, 3, 4]]);
        assert_eq!(out.lines, [5, 5, 5]);
    }
}
