//! Cyclic order written once over [`Navigate`]: the manifold fans of triangles around a vertex
//! (counter-clockwise by the input winding) and the clusters of triangles or tetrahedra around an
//! edge. Structures with a stored radial order (TS, PE, LE, DE) override the 2-complex case.
//!
//! Both walks look only at the star of the vertex or edge: every triangle containing an edge vx
//! contains v, so the star of v alone says which edges at v bound exactly two triangles.

use crate::relation::QueryError;
use crate::relation::handle::{Fans, Navigate, SimplexHandle};
use crate::scratch::{Scratch, pooled_vec};

// Walks keep their lists in this thread's pooled buffers: no allocation once they are warm.
pooled_vec!(Piece, [u32; 2]);

/// One simplex of a star with the two "sides" it can be joined through (the link vertices of a
/// triangle around a vertex, or of a tetrahedron around an edge), `prev` before `next` in the
/// input winding when there is one.
#[derive(Clone, Copy)]
struct Piece {
    handle: SimplexHandle,
    prev: u32,
    next: u32,
}

/// The q-simplices around `h` as pieces whose sides are still to fill, in this thread's pooled
/// buffer.
fn pieces_around<N: Navigate + ?Sized>(
    nav: &N,
    h: SimplexHandle,
    q: usize,
) -> Result<Scratch<Vec<Piece>>, QueryError> {
    let mut pieces = Scratch::<Vec<Piece>>::take();
    nav.visit(h, q, &mut |t| {
        pieces.push(Piece {
            handle: t,
            prev: 0,
            next: 0,
        })
    })?;
    Ok(pieces)
}

/// See [`Navigate::fans_around`].
pub(crate) fn fans_around<N: Navigate + ?Sized>(
    nav: &N,
    v: SimplexHandle,
    out: &mut Fans,
) -> Result<(), QueryError> {
    out.clear();
    let Some(vid) = v.as_vertex() else {
        return Err(QueryError::WrongHandleKind {
            handle: v,
            expected: "a vertex",
        });
    };
    nav.check(v)?;
    if nav.dimension() > 2 {
        return Err(QueryError::DimensionOutOfRange {
            p: 0,
            q: 2,
            dim: nav.dimension(),
        });
    }
    if nav.dimension() < 2 {
        return Ok(());
    }
    let mut pieces = pieces_around(nav, v, 2)?;
    for p in pieces.iter_mut() {
        let t = nav
            .top_id(p.handle)?
            .expect("a triangle of a 2-complex is top");
        let w = nav.top_as_given(t)?;
        let at = w
            .iter()
            .position(|&x| x == vid.0)
            .expect("v is in its star");
        (p.prev, p.next) = (w[(at + 1) % 3], w[(at + 2) % 3]);
    }
    chains(&mut pieces, true, out);
    Ok(())
}

/// See [`Navigate::around_edge`].
pub(crate) fn around_edge<N: Navigate + ?Sized>(
    nav: &N,
    e: SimplexHandle,
    q: usize,
    out: &mut Fans,
) -> Result<(), QueryError> {
    out.clear();
    if e.dim() != 1 {
        return Err(QueryError::WrongHandleKind {
            handle: e,
            expected: "an edge",
        });
    }
    nav.check(e)?;
    let d = nav.dimension();
    if !(2..=3).contains(&q) || q > d {
        return Err(QueryError::DimensionOutOfRange { p: 1, q, dim: d });
    }
    let ends = nav.vertices_of(e)?;
    let mut tris = Scratch::<Vec<SimplexHandle>>::take();
    nav.visit(e, 2, &mut |t| tris.push(t))?;
    if d == 2 {
        // No tetrahedra: the triangles in the structure's natural order, one cyclic group.
        push_group(out, &tris, tris.len() >= 2, false);
        return Ok(());
    }
    let mut pieces = pieces_around(nav, e, 3)?;
    for p in pieces.iter_mut() {
        let w = nav.vertices_of(p.handle)?;
        let mut rest = w.iter().copied().filter(|x| !ends.contains(x));
        (p.prev, p.next) = (rest.next().unwrap(), rest.next().unwrap());
    }
    chains(&mut pieces, false, out);
    if q == 3 {
        return Ok(());
    }
    triangles_of_tet_fans(nav, &ends, &tris, out)
}

/// Replaces the tetrahedron groups in `out` by the triangles met walking each one, then adds
/// every other triangle at the edge as a group of its own.
fn triangles_of_tet_fans<N: Navigate + ?Sized>(
    nav: &N,
    ends: &[u32],
    tris: &[SimplexHandle],
    out: &mut Fans,
) -> Result<(), QueryError> {
    let mut tets = Scratch::<Fans>::take();
    tets.copy_from(out);
    out.clear();
    let tri_of = |x: u32| nav.locate(&[ends[0], ends[1], x]);
    let mut used = Scratch::<Vec<SimplexHandle>>::take();
    let mut seq = Scratch::<Vec<SimplexHandle>>::take();
    let mut links = Scratch::<Vec<[u32; 2]>>::take();
    let mut xs = Scratch::<Vec<u32>>::take();
    // Consecutive tetrahedra share the triangle e ∪ {x}, x their common link vertex.
    let link = |t: SimplexHandle| -> Result<[u32; 2], QueryError> {
        let w = nav.vertices_of(t)?;
        let mut r = w.iter().copied().filter(|x| !ends.contains(x));
        Ok([r.next().unwrap(), r.next().unwrap()])
    };
    let shared = |a: [u32; 2], b: [u32; 2]| if b.contains(&a[0]) { a[0] } else { a[1] };
    let other = |a: [u32; 2], x: u32| if a[0] == x { a[1] } else { a[0] };
    for k in 0..tets.len() {
        links.clear();
        for &t in tets.group(k) {
            links.push(link(t)?);
        }
        let m = links.len();
        xs.clear();
        if m == 1 {
            xs.extend(links[0]);
        } else if tets.closed[k] {
            xs.extend((0..m).map(|i| shared(links[i], links[(i + 1) % m])));
        } else {
            xs.push(other(links[0], shared(links[0], links[1])));
            xs.extend((0..m - 1).map(|i| shared(links[i], links[i + 1])));
            xs.push(other(links[m - 1], shared(links[m - 2], links[m - 1])));
        }
        seq.clear();
        for &x in xs.iter() {
            seq.push(tri_of(x)?);
        }
        used.extend_from_slice(&seq);
        push_group(out, &seq, tets.closed[k], false);
    }
    used.sort_unstable();
    for &t in tris {
        if used.binary_search(&t).is_err() {
            push_group(out, &[t], false, false);
        }
    }
    Ok(())
}

fn push_group(out: &mut Fans, items: &[SimplexHandle], closed: bool, oriented: bool) {
    if out.offsets.is_empty() {
        out.offsets.push(0);
    }
    out.items.extend_from_slice(items);
    out.offsets.push(out.items.len() as u32);
    out.closed.push(closed);
    out.oriented.push(oriented);
}

/// Groups `pieces` into chains joined through sides shared by exactly two pieces, each chain in
/// order, and appends them to `out` by ascending lowest handle. With `wound`, a chain whose
/// pieces agree with the winding (each piece's `next` side is the following piece's `prev`
/// side) is listed in that direction and marked oriented.
fn chains(pieces: &mut [Piece], wound: bool, out: &mut Fans) {
    pieces.sort_unstable_by_key(|p| p.handle);
    // Side vertex -> pieces having it.
    let mut sides = Scratch::<Vec<(u32, u32)>>::take();
    for (i, p) in pieces.iter().enumerate() {
        sides.extend([(p.prev, i as u32), (p.next, i as u32)]);
    }
    sides.sort_unstable();
    let joined = |i: usize, x: u32| -> Option<usize> {
        let lo = sides.partition_point(|s| s.0 < x);
        let hi = sides.partition_point(|s| s.0 <= x);
        if hi - lo != 2 {
            return None;
        }
        let (a, b) = (sides[lo].1 as usize, sides[lo + 1].1 as usize);
        Some(if a == i { b } else { a })
    };
    let mut seen = Scratch::<Vec<bool>>::take();
    seen.resize(pieces.len(), false);
    let mut chain = Scratch::<Vec<usize>>::take();
    for start in 0..pieces.len() {
        if seen[start] {
            continue;
        }
        walk_chain(pieces, start, &joined, &mut seen, &mut chain);
        let closed = chain.len() >= 3
            && joined(chain[0], pieces[chain[0]].prev).is_some()
            && joined(chain[0], pieces[chain[0]].next).is_some();
        let oriented = orient(pieces, &mut chain, closed, wound);
        if out.offsets.is_empty() {
            out.offsets.push(0);
        }
        out.items.extend(chain.iter().map(|&i| pieces[i].handle));
        out.offsets.push(out.items.len() as u32);
        out.closed.push(closed);
        out.oriented.push(oriented);
    }
    if out.offsets.is_empty() {
        out.offsets.push(0);
    }
}

/// The chain containing `start` into `chain`, from one end (or from `start` on a cycle),
/// marking it seen.
fn walk_chain(
    pieces: &[Piece],
    start: usize,
    joined: &dyn Fn(usize, u32) -> Option<usize>,
    seen: &mut [bool],
    chain: &mut Vec<usize>,
) {
    // From `cur`, entered through side `arrived`, leave through its other side.
    let step = |cur: usize, arrived: u32| -> (u32, Option<usize>) {
        let p = pieces[cur];
        let side = if p.prev == arrived { p.next } else { p.prev };
        (side, joined(cur, side))
    };
    // Walk back to an end; coming back to `start` means a cycle.
    let (mut first, mut arrived) = (start, pieces[start].next);
    loop {
        match step(first, arrived) {
            (_, None) => break,
            (_, Some(j)) if j == start => break,
            (side, Some(j)) => {
                // Both pieces have the shared side vertex.
                arrived = side;
                first = j;
            }
        }
    }
    // Walk forward from `first`, leaving through the side other than the open one (an end) or
    // through `next` (a cycle).
    let open_side = {
        let p = pieces[first];
        if joined(first, p.prev).is_none() {
            p.prev
        } else {
            p.next
        }
    };
    chain.clear();
    chain.push(first);
    seen[first] = true;
    let (mut cur, mut came) = (first, open_side);
    while let (side, Some(j)) = step(cur, came) {
        if seen[j] {
            break;
        }
        seen[j] = true;
        chain.push(j);
        cur = j;
        came = side;
    }
}

/// Puts a chain in winding order when it has one: rotates a cycle to start at its lowest
/// piece, and reverses the chain when its pieces follow the winding backwards. Returns whether
/// the chain is oriented.
fn orient(pieces: &[Piece], chain: &mut [usize], closed: bool, wound: bool) -> bool {
    if closed {
        let low = (0..chain.len()).min_by_key(|&i| chain[i]).unwrap();
        chain.rotate_left(low);
    }
    if !wound {
        return false;
    }
    let forward = |c: &[usize]| {
        let n = c.len();
        let steps = if closed { n } else { n.saturating_sub(1) };
        (0..steps).all(|i| {
            let (a, b) = (pieces[c[i]], pieces[c[(i + 1) % n]]);
            a.next == b.prev
        })
    };
    if forward(chain) {
        return true;
    }
    let reverse = |c: &mut [usize]| {
        if closed {
            c[1..].reverse();
        } else {
            c.reverse();
        }
    };
    reverse(chain);
    if forward(chain) {
        return true;
    }
    reverse(chain);
    false
}
