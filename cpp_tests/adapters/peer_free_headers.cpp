// The adapters' peer-free headers (topoplex/adapter.hpp, topoplex/manifold_parts.hpp) compile on
// their own, strictly (C++17, -Wall -Wextra -Werror -pedantic), where no peer is installed:
// built as an object library, so a warning fails the build.
#include <topoplex/adapter.hpp>
#include <topoplex/manifold_parts.hpp>

std::size_t topoplex_adapters_peer_free_parts(const topoplex::Complex &c) {
  return topoplex::SurfaceParts::cut(c).size() + topoplex::SurfaceParts::iqm(c).size() +
         topoplex::adapt::surface_listing(c, "none").listing.size();
}
