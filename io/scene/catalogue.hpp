// raceway's bearing catalogue: `[bearing] designation = "6205"` fills a scene's bearing geometry,
// its cage and the defaults a first scene needs.
//
// The data (io/scene/bearing_catalogue.toml, compiled in) are the ISO 15 boundary dimensions of
// the deep groove 60, 62 and 63 series, the angular contact 72..B, the four-point QJ2.. and the
// cylindrical roller NU, NJ and NUP series, the ISO 355 boundary dimensions of the tapered roller
// 302 and 322 series, and the internal geometry that a source in the repository publishes; the
// rest of the internal geometry is estimated by the rules of catalogue.cpp (catalogue_tapered.cpp
// for tapered bearings).
// docs/catalogue.md gives the source of every number and every rule. The scene overrides any
// value: the catalogue fills only keys the scene does not give.
#pragma once

#include <string>
#include <vector>

#include "io/scene/scene.hpp"

namespace raceway::scene {

/// Every designation of the catalogue ("6000" .. "32220"), in the catalogue's order.
std::vector<std::string> catalogue_designations();

/// What `raceway check` prints about a scene's catalogue values: each filled key with its value and
/// source, the keys the scene gave instead, and the first-scene defaults with why; "" for a scene
/// without a designation.
std::string describe_catalogue_values(const Scene& scene);

}  // namespace raceway::scene
