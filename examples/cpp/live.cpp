#include <topoplex.hpp>
#include <cstdio>

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
  topoplex::Structure ig(mesh.to_complex(), topoplex::Kind::IG);
  return mesh.top_count(2) == 3 && mesh.top_count(1) == 0 ? 0 : 1;
}
