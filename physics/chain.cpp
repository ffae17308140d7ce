// chain.cpp — chain builders: a vertex list to one-sided segments with ghost
// vertices (collision.h). Only validation and bookkeeping: the collision of a
// chain segment lives in manifold.cpp.
#include <string>

#include "physics/collision.h"

namespace tandem {

Status make_chain_segments(const Vec2* points, int32_t count, bool loop, int32_t chain_id,
                                   ChainSegment* out_segments, int32_t capacity, int32_t* out_count) {
  Status status;
  *out_count = 0;
  const int32_t min_points = loop ? 3 : 4;
  if (points == nullptr || count < min_points) {
    status.code = StatusCode::invalid_argument;
    status.message = std::string("chain: ") + (loop ? "a loop" : "an open chain") + " needs at least " +
                     std::to_string(min_points) + " points, got " + std::to_string(points ? count : 0) +
                     (loop ? "" : " (the first and last points are ghost vertices only)");
    return status;
  }
  // Consecutive vertices (and, for a loop, last → first) must be distinct.
  const int32_t edges = loop ? count : count - 1;
  for (int32_t i = 0; i < edges; ++i) {
    const int32_t j = (i + 1) % count;
    if (distance_squared(points[i], points[j]) < k_linear_slop * k_linear_slop) {
      status.code = StatusCode::invalid_argument;
      status.message = "chain: points " + std::to_string(i) + " and " + std::to_string(j) + " are " +
                       to_string(distance(points[i], points[j])) + " m apart, need at least " +
                       to_string(k_linear_slop) + " m";
      return status;
    }
  }
  const int32_t segments = loop ? count : count - 3;
  if (segments > capacity || out_segments == nullptr) {
    status.code = StatusCode::invalid_argument;
    status.message = "chain: " + std::to_string(segments) + " segments do not fit the output capacity of " +
                     std::to_string(capacity);
    return status;
  }
  auto at = [&](int32_t k) { return points[((k % count) + count) % count]; };
  for (int32_t s = 0; s < segments; ++s) {
    // Open chains start at point 1 (point 0 is the first ghost).
    const int32_t i = loop ? s : s + 1;
    ChainSegment seg;
    seg.ghost1 = at(i - 1);
    seg.segment = Segment{at(i), at(i + 1)};
    seg.ghost2 = at(i + 2);
    seg.chain_id = chain_id;
    out_segments[s] = seg;
  }
  *out_count = segments;
  return status;
}

}  // namespace tandem
