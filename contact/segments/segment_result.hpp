// What evaluating a contact segment gives, the same for every segment family: the wrench on each of
// its two bodies, the family's diagnostics and the validity flag. Planar (roller) segments use it
// with PlanarWrench and SegmentDiagnostics (roller_segments.hpp), spatial (ball) segments with
// SpatialWrench and PointDiagnostics (ball_segments.hpp).
#pragma once

namespace raceway::contact {

template <class Wrench, class Diagnostics>
struct ContactResult {
  Wrench on_a, on_b;  ///< force and moment on A and on B, each at its body's centre
  Diagnostics diagnostics;
  bool valid = true;  ///< false: a law left its valid range (recoverable: retry a smaller step)
};

}  // namespace raceway::contact
