// distance.cpp — GJK distance with witness points, linear shape cast and time
// of impact by conservative advancement, and the sweep interpolation.
//
// Design notes
// ------------
// GJK (shape_distance). The classic 2D algorithm on the Minkowski difference
// B − A with a simplex of ≤ 3 vertices and barycentric sub-solvers (the same
// structure as Box2D's, written for fixed point):
//   * No cache: every call starts from vertex 0 of each proxy, so the result
//     is a function of the input alone.
//   * Everything runs in A's local frame (B's points are moved there once),
//     so coordinates are the size of the shapes and their separation, not of
//     the world.
//   * Support ties go to the lowest index (strict > comparison).
//   * Termination: a support pair already in the simplex (before it was
//     reduced) ends the loop — the main criterion, which also catches
//     two-cycles; an exactly zero search direction; a triangle containing the
//     origin; or k_max_gjk_iterations support steps. The simplex is always
//     solved after the last step, so the result is the closest point of a
//     valid simplex — an upper bound on the true distance — even when the loop
//     could not converge.
//   * The triangle solver scales the three sub-areas by the SIGN of the
//     triangle's area instead of the area itself (the factor cancels in the
//     barycentric weights), so no product of two areas is ever formed.
//   * Distance and normal come from the simplex geometry, not from the
//     difference of the witness points: one vertex → |w|, w/|w|; an edge →
//     the unit perpendicular of the edge and the projection of w1 on it. This
//     keeps the normal accurate when the shapes nearly touch.
// Range: dot products of Minkowski points must stay below 2^31, i.e. the
// shapes' extents plus their separation below ~30,000 m. Shapes further apart
// than that saturate (and report a fault in debug builds).
//
// shape_cast and time_of_impact: conservative advancement (Mirtich). At time t
// take the core distance d and normal n; no point of B can approach A faster
// than u = (relative linear velocity)·(−n) + ω_A·r_A + ω_B·r_B, so t can
// advance by (d − target)/u without passing the first contact. target is
// max(linear slop, rA + rB − linear slop) in core distance (Box2D's choice:
// polygons stop a slop apart, rounded shapes a slop into each other), and the
// iteration stops within k_linear_slop/4 above it (time_of_impact_to takes
// the caller's target instead, within a quarter of it when that is smaller).
// Each advance is compared as (d − target) ≥ (t_max − t)·u before dividing, so no quotient overflows.
// Iterations are bounded (k_max_cast_iterations, k_max_toi_iterations); when
// they run out the result is "no hit" / ToiState::failed with the last safe
// time — never a time past the true contact.
//
// Sweeps interpolate the rotation linearly and normalise it (nlerp). Its
// angular speed is not constant: between rotations θ apart it peaks at
// 2·tan(θ/2) (at t = 1/2), which is what time_of_impact uses as ω, instead
// of θ. For θ near π the bound blows up; it is capped at k_max_nlerp_rate and
// the advancement then simply takes more (bounded) iterations.
#include "physics/collision.h"

namespace tandem {
namespace {

struct SimplexVertex {
  Vec2 wa;  ///< support point of A, A's frame, m
  Vec2 wb;  ///< support point of B, A's frame, m
  Vec2 w;   ///< wb − wa, m
  Q32 a;    ///< barycentric weight, [0, 1]
  int32_t index_a = 0;
  int32_t index_b = 0;
};

struct Simplex {
  std::array<SimplexVertex, 3> v{};
  int32_t count = 0;
};

/// The index of the point with the largest projection on d (lowest on ties).
int32_t find_support(const ShapeProxy& proxy, Vec2 d) {
  int32_t best = 0;
  Q32 best_value = dot(proxy.points[0], d);
  for (int32_t i = 1; i < proxy.count; ++i) {
    const Q32 value = dot(proxy.points[static_cast<size_t>(i)], d);
    if (value > best_value) {
      best = i;
      best_value = value;
    }
  }
  return best;
}

SimplexVertex make_vertex(const ShapeProxy& a, const ShapeProxy& b, int32_t ia, int32_t ib) {
  SimplexVertex v;
  v.wa = a.points[static_cast<size_t>(ia)];
  v.wb = b.points[static_cast<size_t>(ib)];
  v.w = v.wb - v.wa;
  v.a = Q32::one();
  v.index_a = ia;
  v.index_b = ib;
  return v;
}

/// x / sum for 0 ≤ x ≤ sum, sum > 0: a weight in [0, 1].
Q32 weight(Q32 x, Q32 sum) { return clamp(x, Q32::zero(), sum) / sum; }

/// Closest point of the segment w1–w2 to the origin (Voronoi regions).
void solve2(Simplex* s) {
  SimplexVertex& v1 = s->v[0];
  SimplexVertex& v2 = s->v[1];
  const Vec2 e12 = v2.w - v1.w;
  const Q32 d12_2 = -dot(v1.w, e12);  // origin beyond w1 when ≤ 0
  const Q32 d12_1 = dot(v2.w, e12);   // origin beyond w2 when ≤ 0
  if (d12_2 <= Q32::zero()) {
    v1.a = Q32::one();
    s->count = 1;
    return;
  }
  if (d12_1 <= Q32::zero()) {
    v2.a = Q32::one();
    v1 = v2;
    s->count = 1;
    return;
  }
  v1.a = weight(d12_1, d12_1 + d12_2);
  v2.a = Q32::one() - v1.a;
  s->count = 2;
}

/// Closest point of the triangle w1–w2–w3 to the origin.
void solve3(Simplex* s) {
  SimplexVertex& v1 = s->v[0];
  SimplexVertex& v2 = s->v[1];
  SimplexVertex& v3 = s->v[2];
  const Vec2 w1 = v1.w, w2 = v2.w, w3 = v3.w;
  const Vec2 e12 = w2 - w1, e13 = w3 - w1, e23 = w3 - w2;
  const Q32 d12_1 = dot(w2, e12), d12_2 = -dot(w1, e12);
  const Q32 d13_1 = dot(w3, e13), d13_2 = -dot(w1, e13);
  const Q32 d23_1 = dot(w3, e23), d23_2 = -dot(w2, e23);
  // Sub-areas scaled by the sign of the triangle's area (see the notes).
  const int sg = sign(cross(e12, e13));
  const Q32 d123_1 = cross(w2, w3) * sg;
  const Q32 d123_2 = cross(w3, w1) * sg;
  const Q32 d123_3 = cross(w1, w2) * sg;
  const Q32 zero = Q32::zero();

  if (d12_2 <= zero && d13_2 <= zero) {  // vertex 1
    v1.a = Q32::one();
    s->count = 1;
    return;
  }
  if (d12_1 > zero && d12_2 > zero && d123_3 <= zero) {  // edge 12
    v1.a = weight(d12_1, d12_1 + d12_2);
    v2.a = Q32::one() - v1.a;
    s->count = 2;
    return;
  }
  if (d13_1 > zero && d13_2 > zero && d123_2 <= zero) {  // edge 13
    v1.a = weight(d13_1, d13_1 + d13_2);
    v3.a = Q32::one() - v1.a;
    v2 = v3;
    s->count = 2;
    return;
  }
  if (d12_1 <= zero && d23_2 <= zero) {  // vertex 2
    v2.a = Q32::one();
    v1 = v2;
    s->count = 1;
    return;
  }
  if (d13_1 <= zero && d23_1 <= zero) {  // vertex 3
    v3.a = Q32::one();
    v1 = v3;
    s->count = 1;
    return;
  }
  if (d23_1 > zero && d23_2 > zero && d123_1 <= zero) {  // edge 23
    v2.a = weight(d23_1, d23_1 + d23_2);
    v3.a = Q32::one() - v2.a;
    v1 = v3;
    s->count = 2;
    return;
  }
  // Inside the triangle. Rounding can leave a sub-area slightly negative; the
  // weights are clamped to [0, 1] (they only matter for witness points, which
  // coincide here).
  const Q32 sum = max(d123_1, zero) + max(d123_2, zero) + max(d123_3, zero);
  if (sum.raw == 0) {
    // A degenerate triangle that matched no region (rounding): keep the
    // vertex nearest the origin. Deterministic; not reached in tests.
    SimplexVertex best = v1;
    for (const SimplexVertex& v : {v2, v3}) {
      if (length(v.w) < length(best.w)) best = v;
    }
    v1 = best;
    v1.a = Q32::one();
    s->count = 1;
    return;
  }
  v1.a = weight(d123_1, sum);
  v2.a = weight(d123_2, sum);
  v3.a = Q32::one() - v1.a - v2.a;
  s->count = 3;
}

/// A direction from the simplex towards the origin (not normalised).
Vec2 search_direction(const Simplex& s) {
  if (s.count == 1) return -s.v[0].w;
  const Vec2 e12 = s.v[1].w - s.v[0].w;
  const Q32 side = cross(e12, -s.v[0].w);
  return side > Q32::zero() ? left_perp(e12) : right_perp(e12);
}

/// The rigid transform of a proxy's points.
ShapeProxy transformed(const ShapeProxy& p, Transform xf) {
  ShapeProxy out = p;
  for (int32_t i = 0; i < p.count; ++i) {
    out.points[static_cast<size_t>(i)] = transform_point(xf, p.points[static_cast<size_t>(i)]);
  }
  return out;
}

/// Largest distance of a proxy's points from a centre, m.
Q32 max_extent(const ShapeProxy& p, Vec2 center) {
  Q32 r;
  for (int32_t i = 0; i < p.count; ++i) r = max(r, distance(p.points[static_cast<size_t>(i)], center));
  return r;
}

/// Upper bound of the angular speed of the nlerp from q1 to q2 over unit
/// time: 2·tan(θ/2) = 2·sin θ/(1 + cos θ), rad per unit time.
Q32 nlerp_rate(Rot q1, Rot q2) {
  const Q32 c = dot(Vec2{q1.c, q1.s}, Vec2{q2.c, q2.s});
  const Q32 s = abs(cross(Vec2{q1.c, q1.s}, Vec2{q2.c, q2.s}));
  const Q32 den = Q32::one() + c;
  // 2s/den ≤ cap ⟺ 2s ≤ cap·den: compare before dividing.
  if (s * 2 >= k_max_nlerp_rate * den) return k_max_nlerp_rate;
  return s * 2 / den;
}

}  // namespace

// ---------------------------------------------------------------------------
// Proxies
// ---------------------------------------------------------------------------

ShapeProxy make_proxy(const Vec2* points, int32_t count, Q32 radius) {
  ShapeProxy p;
  p.radius = radius;
  if (points == nullptr || count < 1) {
    p.count = 1;  // a single point at the origin
    return p;
  }
  p.count = count < k_max_polygon_vertices ? count : k_max_polygon_vertices;
  for (int32_t i = 0; i < p.count; ++i) p.points[static_cast<size_t>(i)] = points[i];
  return p;
}

ShapeProxy make_proxy(const Circle& circle) { return make_proxy(&circle.center, 1, circle.radius); }

ShapeProxy make_proxy(const Capsule& capsule) {
  const Vec2 pts[2] = {capsule.center1, capsule.center2};
  return make_proxy(pts, 2, capsule.radius);
}

ShapeProxy make_proxy(const Polygon& polygon) {
  return make_proxy(polygon.vertices.data(), polygon.count, polygon.radius);
}

ShapeProxy make_proxy(const Segment& segment) {
  const Vec2 pts[2] = {segment.point1, segment.point2};
  return make_proxy(pts, 2, Q32::zero());
}

// ---------------------------------------------------------------------------
// GJK
// ---------------------------------------------------------------------------

DistanceOutput shape_distance(const DistanceInput& input) {
  const ShapeProxy& proxy_a = input.proxy_a;
  // B in A's frame.
  const ShapeProxy proxy_b = transformed(input.proxy_b, inv_mul_transforms(input.transform_a, input.transform_b));

  Simplex s;
  s.v[0] = make_vertex(proxy_a, proxy_b, 0, 0);
  s.count = 1;
  int32_t iterations = 0;
  for (;;) {
    std::array<int32_t, 3> saved_a{}, saved_b{};
    const int32_t saved_count = s.count;
    for (int32_t i = 0; i < saved_count; ++i) {
      saved_a[static_cast<size_t>(i)] = s.v[static_cast<size_t>(i)].index_a;
      saved_b[static_cast<size_t>(i)] = s.v[static_cast<size_t>(i)].index_b;
    }
    if (s.count == 2) solve2(&s);
    if (s.count == 3) solve3(&s);
    if (s.count == 3) break;  // the origin is inside the triangle: overlap
    if (iterations == k_max_gjk_iterations) break;
    const Vec2 d = search_direction(s);
    if (d.x.raw == 0 && d.y.raw == 0) break;  // the origin is on the simplex
    const int32_t ia = find_support(proxy_a, -d);
    const int32_t ib = find_support(proxy_b, d);
    ++iterations;
    bool duplicate = false;
    for (int32_t i = 0; i < saved_count; ++i) {
      duplicate = duplicate || (saved_a[static_cast<size_t>(i)] == ia && saved_b[static_cast<size_t>(i)] == ib);
    }
    if (duplicate) break;
    s.v[static_cast<size_t>(s.count)] = make_vertex(proxy_a, proxy_b, ia, ib);
    ++s.count;
  }

  // Witness points, core distance and normal in A's frame.
  Vec2 pa, pb, normal;
  Q32 dist;
  if (s.count == 1) {
    pa = s.v[0].wa;
    pb = s.v[0].wb;
    normal = length_and_normalize(s.v[0].w, &dist);
  } else if (s.count == 2) {
    const SimplexVertex& v1 = s.v[0];
    const SimplexVertex& v2 = s.v[1];
    pa = v1.a * v1.wa + v2.a * v2.wa;
    pb = v1.a * v1.wb + v2.a * v2.wb;
    const Vec2 n = normalize(left_perp(v2.w - v1.w));
    const Q32 proj = dot(n, v1.w);
    normal = proj < Q32::zero() ? -n : n;
    dist = abs(proj);
    if (dist.raw == 0) normal = {};
  } else {
    pa = s.v[0].a * s.v[0].wa + s.v[1].a * s.v[1].wa + s.v[2].a * s.v[2].wa;
    pb = pa;
  }

  DistanceOutput out;
  out.iterations = iterations;
  out.simplex_count = s.count;
  if (input.use_radii) {
    const Q32 ra = input.proxy_a.radius, rb = input.proxy_b.radius;
    if (dist.raw == 0) {
      const Vec2 mid{(pa.x + pb.x) / 2, (pa.y + pb.y) / 2};
      pa = mid;
      pb = mid;
    } else {
      // Keep the points on the surfaces even when the rounded shapes overlap.
      dist = max(dist - ra - rb, Q32::zero());
      pa = mul_add(pa, ra, normal);
      pb = mul_sub(pb, rb, normal);
    }
  }
  out.distance = dist;
  out.point_a = transform_point(input.transform_a, pa);
  out.point_b = transform_point(input.transform_a, pb);
  out.normal = rotate(input.transform_a.q, normal);
  return out;
}

// ---------------------------------------------------------------------------
// Shape cast
// ---------------------------------------------------------------------------

CastOutput shape_cast(const ShapeCastInput& input) {
  CastOutput out;
  const auto miss = [&out] {
    CastOutput m;
    m.iterations = out.iterations;
    return m;
  };
  const Q32 max_fraction = clamp(input.max_fraction, Q32::zero(), Q32::one());
  const Q32 total_radius = input.proxy_a.radius + input.proxy_b.radius;
  Q32 target = max(k_linear_slop, total_radius - k_linear_slop);
  const Q32 tolerance = k_linear_slop / 4;

  DistanceInput din;
  din.proxy_a = input.proxy_a;
  din.proxy_b = input.proxy_b;
  din.transform_a = input.transform_a;
  din.transform_b = input.transform_b;
  din.use_radii = false;
  const Vec2 delta = input.translation_b;
  Q32 fraction;
  for (int32_t iteration = 0; iteration < k_max_cast_iterations; ++iteration) {
    out.iterations = iteration + 1;
    const DistanceOutput d = shape_distance(din);
    if (d.distance < target + tolerance) {
      if (iteration == 0 && input.can_encroach && d.distance > k_linear_slop * 2) {
        // Already touching: allow moving one more slop closer.
        target = d.distance - k_linear_slop;
      } else {
        // Hit (at fraction 0: initial overlap).
        out.hit = true;
        out.fraction = fraction;
        out.normal = d.normal;
        out.point = mul_add(d.point_a, input.proxy_a.radius, d.normal);
        return out;
      }
    }
    // B approaches A along −normal at `closing` m per unit fraction.
    const Q32 closing = -dot(delta, d.normal);
    if (closing <= Q32::zero()) return miss();  // moving apart
    const Q32 gap = d.distance - target;
    if (gap >= (max_fraction - fraction) * closing) return miss();  // not before max_fraction
    fraction += gap / closing;
    din.transform_b.p = mul_add(input.transform_b.p, fraction, delta);
  }
  return miss();  // did not converge
}

// ---------------------------------------------------------------------------
// Time of impact
// ---------------------------------------------------------------------------

Transform sweep_transform(const Sweep& sweep, Q32 t) {
  const Vec2 c = mul_add(sweep.c1, t, sweep.c2 - sweep.c1);
  const Rot q = rot_normalize({sweep.q1.c + t * (sweep.q2.c - sweep.q1.c), sweep.q1.s + t * (sweep.q2.s - sweep.q1.s)});
  return {c - rotate(q, sweep.local_center), q};
}

namespace {

/// Conservative advancement to the core distance `target` within `tolerance`.
ToiOutput advance_to_impact(const ToiInput& input, Q32 target, Q32 tolerance) {
  ToiOutput out;
  const Q32 t_max = clamp(input.max_fraction, Q32::zero(), Q32::one());

  const Sweep& sa = input.sweep_a;
  const Sweep& sb = input.sweep_b;
  const Vec2 v_rel = (sb.c2 - sb.c1) - (sa.c2 - sa.c1);  // m per unit time
  const Q32 spin = nlerp_rate(sa.q1, sa.q2) * max_extent(input.proxy_a, sa.local_center) +
                   nlerp_rate(sb.q1, sb.q2) * max_extent(input.proxy_b, sb.local_center);

  DistanceInput din;
  din.proxy_a = input.proxy_a;
  din.proxy_b = input.proxy_b;
  din.use_radii = false;
  Q32 t;
  for (int32_t iteration = 0; iteration < k_max_toi_iterations; ++iteration) {
    out.iterations = iteration + 1;
    din.transform_a = sweep_transform(sa, t);
    din.transform_b = sweep_transform(sb, t);
    const DistanceOutput d = shape_distance(din);
    if (d.distance.raw == 0) {
      out.state = ToiState::overlapped;
      out.fraction = t;
      return out;
    }
    if (d.distance < target + tolerance) {
      out.state = ToiState::hit;
      out.fraction = t;
      return out;
    }
    const Q32 closing = spin - dot(v_rel, d.normal);
    const Q32 gap = d.distance - target;
    if (closing <= Q32::zero() || gap >= (t_max - t) * closing) {
      out.state = ToiState::separated;
      out.fraction = t_max;
      return out;
    }
    t += gap / closing;
  }
  out.state = ToiState::failed;
  out.fraction = t;
  return out;
}

}  // namespace

ToiOutput time_of_impact(const ToiInput& input) {
  const Q32 total_radius = input.proxy_a.radius + input.proxy_b.radius;
  return advance_to_impact(input, max(k_linear_slop, total_radius - k_linear_slop), k_linear_slop / 4);
}

ToiOutput time_of_impact_to(const ToiInput& input, Q32 target) {
  return advance_to_impact(input, target, min(k_linear_slop, target) / 4);
}

}  // namespace tandem
