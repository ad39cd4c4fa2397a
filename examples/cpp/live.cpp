#include <topoplex.hpp>
#include <cstdio>
#include <vector>

int main() {
  /*      3 (4, 5)     triangles 1 2 3, 1 2 4, 1 2 5 share edge 1-2 (non-manifold);
   *     / \           wire edges 0-1 and 0-2 make a hollow triangle 0 1 2
   *    1---2
   *     \ /
   *      0                                                                  */
  topoplex::Complex c = topoplex::Complex::from_arrays(
      6, {1, 2, 3, 1, 2, 4, 1, 2, 5, 0, 1, 0, 2}, {0, 3, 6, 9, 11, 13});
  topoplex::Live mesh(c);
  // Contracting 1-2 would collapse the hollow triangle: 0 is in Lk(1) and Lk(2), not Lk(12).
  if (!mesh.link_condition(1, 2)) std::puts("1-2: link condition fails");
  topoplex::Undo undo = mesh.contract(1, 3);  // link condition holds: 1 2 3 folds away
  std::printf("%zu triangles after contracting 1-3\n", mesh.top_count(2));  // 2
  mesh.split(undo);                                                          // back to 3
  try {
    mesh.contract(0, 3);  // not an edge
  } catch (const topoplex::Error &e) {
    std::printf("refused (status %u): %s\n", static_cast<unsigned>(e.status()), e.what());
  }
  mesh.contract(0, 3, topoplex::ContractMode::Free);  // unify 0 and 3: fills 0 1 2
  // Navigate by handles: edge 1-2 now bounds triangles 0 1 2, 1 2 4 and 1 2 5.
  topoplex::Simplex e = mesh.locate({1, 2});
  bool ok = mesh.degree(e, 2) == 3 && !mesh.is_manifold(e);
  for (topoplex::Simplex t : mesh.coboundary(e, 2)) {
    std::vector<std::uint32_t> v = mesh.vertices(t);
    std::printf("triangle %u %u %u on edge 1-2\n", v[0], v[1], v[2]);
  }
  // No edge at 1 joins two of its triangles: three fans of one triangle each.
  ok = ok && mesh.fans_around(mesh.vertex(1)).size() == 3;
  mesh.compact();  // renumbers ids: handles from before are refused, never misread
  try {
    mesh.degree(e, 2);
    ok = false;
  } catch (const topoplex::Error &err) {
    ok = ok && err.status() == TPX_STATUS_STALE_GENERATION;
  }
  topoplex::Structure ig(mesh.to_complex(), topoplex::Kind::IG);
  return ok && mesh.top_count(2) == 3 && mesh.top_count(1) == 0 ? 0 : 1;
}
