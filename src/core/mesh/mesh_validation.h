#pragma once
// Internal to the core library: the part of a polygon soup's validation (mesh_from_soup,
// primo/mesh/polygon_soup.h) that a writer needs on its own.

#include <string>

#include "primo/mesh/polygon_soup.h"

namespace primo::detail {

// The geometric checks a read mesh passes (finite coordinates, faces of non-zero area up to
// their coordinates' rounding; mesh_from_soup), on a soup whose structure is known to be
// valid: what a writer checks of the points it is about to round.
void check_soup_geometry(const PolygonSoup& soup, const std::string& source);

}  // namespace primo::detail
