// broad_phase_grid.cpp — Max Grid (the hand-built-vs-engine report, 3.2 and
// 5.11.2), rebuilt from scratch every update: no persistent state, so it
// suits scenes where everything moves.
//
// Cell size S: the largest extent (max of width, height of the fattened box)
// among the dynamic proxies that are not outliers. Every proxy with extent ≤
// S goes into the ONE cell holding its box centre; two such proxies can only
// overlap when their centres are at most S apart on each axis, i.e. in the
// same or adjacent cells. So each proxy looks at its own cell and its
// neighbours; to find each pair once it looks at its own cell (entries after
// it) and the four "forward" neighbours (+1,0), (−1,+1), (0,+1), (+1,+1) —
// for every pair of adjacent cells exactly one is the other's forward
// neighbour. Only pairs with a dynamic proxy matter, so static and kinematic
// proxies do not set S.
//
// Outliers: dynamic proxies larger than 4× the 15/16-quantile power-of-two
// extent class (so one huge box cannot turn the grid into one cell), every
// static/kinematic proxy larger than S (grounds, walls), and anything beyond
// ±2^54 raw (≈ 4.2e6 m, outside any world; keeps cell arithmetic far from
// overflow). Each outlier scans the cells its box can reach (its box grown by
// S/2, clamped to the occupied cell range), or every grid entry when that is
// fewer, then the outliers after it. Cost O(outliers × min(cells, n)).
//
// Cells: integer coordinates floor((lower + upper) / 2S) of the raw Q32 sums
// (one division per axis per proxy; exact). When the occupied cell range has
// at most 4n + 64 cells (crowded scenes, the common case) the buckets are
// that range's cells in row-major order: a cell's forward neighbours are the
// next bucket and three consecutive buckets one row up, so the search reads
// nearby memory and compares no keys (~2× faster than hashing at 16k
// circles). Otherwise (sparse worlds) packed (uint32 cx, uint32 cy) keys are
// hashed by a fixed 64-bit mixer into a power-of-two table ≥ 2× the proxies,
// and a lookup compares the full cell key, so collisions only cost time.
// Either way a counting sort by bucket places the entries (ascending shape
// index inside a bucket). Nothing depends on addresses or on a hash map's
// iteration order.
//
// Rejected: a dense array only (memory grows with the scene's spread);
// inserting each proxy into every cell its box overlaps (duplicates to
// remove).
#include <bit>

#include "physics/broad_phase.h"
#include "physics/world.h"

namespace tandem {

namespace {

constexpr int64_t k_grid_coordinate_limit = int64_t{1} << 54;  // raw; larger boxes are outliers
constexpr int64_t k_min_cell_size = int64_t{1} << 24;          // raw (≈ 0.004 m)
// Grid cell coordinates stay within ±2^30 (|lower + upper| < 2^55, cell ≥
// 2^25), so cx = −2^31 never occurs: it marks outliers.
constexpr uint64_t k_outlier_cell = 0x8000000080000000ull;

uint64_t box_extent(const AABB& b) {
  const uint64_t w = static_cast<uint64_t>(b.upper.x.raw) - static_cast<uint64_t>(b.lower.x.raw);
  const uint64_t h = static_cast<uint64_t>(b.upper.y.raw) - static_cast<uint64_t>(b.lower.y.raw);
  return w > h ? w : h;
}

bool within_limit(Q32 v) { return v.raw > -k_grid_coordinate_limit && v.raw < k_grid_coordinate_limit; }

int64_t floor_div(int64_t a, int64_t d) {
  int64_t q = a / d;
  if (a % d < 0) --q;
  return q;
}

uint64_t pack_cell(int64_t cx, int64_t cy) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(cx)) << 32) | static_cast<uint32_t>(cy);
}

uint32_t cell_bucket(uint64_t key, uint32_t bits) {
  key ^= key >> 33;
  key *= 0xFF51AFD7ED558CCDull;
  key ^= key >> 33;
  key *= 0xC4CEB9FE1A85EC53ull;
  key ^= key >> 33;
  return static_cast<uint32_t>(key >> (64u - bits));
}

int64_t clamp_coordinate(int64_t v) {
  const int64_t lim = int64_t{1} << 56;
  return v < -lim ? -lim : (v > lim ? lim : v);
}

/// The candidate test on two grid entries (kind skip, count, box, filters).
inline void test_entries(World* world, const GridEntry& a, const GridEntry& b, int64_t* candidates) {
  if ((a.dynamic | b.dynamic) == 0) return;
  ++*candidates;
  if (aabb_overlaps(a.box, b.box)) broad_phase_emit_overlapping(world, a.shape, b.shape);
}

/// Calls f(entry) for every grid entry that may overlap `box`: a grid proxy
/// overlapping it has lower + upper within [2·box.lower − S, 2·box.upper + S]
/// on each axis, so the cells of that range (clamped to the occupied range)
/// are read — row by row in the dense layout; cell by cell through the hash
/// when there are fewer cells than entries, else every entry.
template <typename F>
void for_each_entry_near(const Grid& g, const AABB& box, F&& f) {
  const size_t grid_count = g.entries.size();
  if (grid_count == 0) return;
  const int64_t cell = g.cell_size;
  const int64_t span = 2 * cell;
  const int64_t lx = clamp_coordinate(box.lower.x.raw), ux = clamp_coordinate(box.upper.x.raw);
  const int64_t ly = clamp_coordinate(box.lower.y.raw), uy = clamp_coordinate(box.upper.y.raw);
  int64_t x0 = floor_div(2 * lx - cell, span), x1 = floor_div(2 * ux + cell, span);
  int64_t y0 = floor_div(2 * ly - cell, span), y1 = floor_div(2 * uy + cell, span);
  x0 = x0 < g.min_cx ? g.min_cx : x0;
  x1 = x1 > g.max_cx ? g.max_cx : x1;
  y0 = y0 < g.min_cy ? g.min_cy : y0;
  y1 = y1 > g.max_cy ? g.max_cy : y1;
  if (x0 > x1 || y0 > y1) return;
  const GridEntry* entries = g.entries.data();
  const uint32_t* starts = g.bucket_start.data();
  const uint64_t cells = static_cast<uint64_t>(x1 - x0 + 1) * static_cast<uint64_t>(y1 - y0 + 1);
  if (g.dense) {
    const size_t w = static_cast<size_t>(g.width);
    for (int64_t cy = y0; cy <= y1; ++cy) {
      const size_t row = static_cast<size_t>(cy - g.min_cy) * w;
      const uint32_t begin = starts[row + static_cast<size_t>(x0 - g.min_cx)];
      const uint32_t end = starts[row + static_cast<size_t>(x1 - g.min_cx) + 1];
      for (uint32_t ej = begin; ej < end; ++ej) f(entries[ej]);
    }
  } else if (cells <= static_cast<uint64_t>(grid_count)) {
    for (int64_t cx = x0; cx <= x1; ++cx) {
      for (int64_t cy = y0; cy <= y1; ++cy) {
        const uint64_t key = pack_cell(cx, cy);
        const uint32_t nb = cell_bucket(key, g.bucket_bits);
        const uint32_t nend = starts[nb + 1];
        for (uint32_t ej = starts[nb]; ej < nend; ++ej) {
          if (entries[ej].cell == key) f(entries[ej]);
        }
      }
    }
  } else {
    for (size_t ej = 0; ej < grid_count; ++ej) f(entries[ej]);
  }
}

/// Builds the grid from the pre-pass's proxies (cells, buckets, entries,
/// outliers). Returns false when no pair can exist (fewer than two proxies or
/// none dynamic): the pair search is then skipped. The grid is built anyway
/// for queries, its cell size then taken from every proxy.
bool grid_build(World* world) {
  BroadPhase& bp = world->broad_phase;
  Grid& g = bp.grid;
  const size_t n = bp.proxies.size();
  g.cell_size = 0;
  g.outliers.clear();
  g.outlier_shapes.clear();
  // Every entry is built from the current boxes: none is stale.
  for (const int32_t s : g.dirty) g.is_dirty[static_cast<size_t>(s)] = 0;
  g.dirty.clear();
  g.entries.clear();
  g.min_cx = 0;
  g.min_cy = 0;
  g.max_cx = -1;
  g.max_cy = -1;
  g.width = 1;
  g.dense = true;
  if (n == 0) return false;

  // Cell size from the dynamic proxies' extents, ignoring outsized ones (from
  // every proxy when none is dynamic: only queries will read the grid).
  int32_t histogram[65] = {};
  int32_t dynamic_count = 0;
  for (size_t i = 0; i < n; ++i) {
    if (bp.proxy_dynamic[i] == 0) continue;
    ++histogram[std::bit_width(box_extent(bp.fat_bounds[i]))];
    ++dynamic_count;
  }
  const bool pairs_possible = n >= 2 && dynamic_count > 0;
  const uint8_t sizing_flag = dynamic_count > 0 ? 1 : 0;  // proxies with proxy_dynamic ≥ this set the size
  int32_t sizing_count = dynamic_count;
  if (dynamic_count == 0) {
    for (size_t i = 0; i < n; ++i) ++histogram[std::bit_width(box_extent(bp.fat_bounds[i]))];
    sizing_count = static_cast<int32_t>(n);
  }
  const uint64_t typical_limit = broad_phase_typical_limit(histogram, sizing_count);
  uint64_t size = 0;
  for (size_t i = 0; i < n; ++i) {
    if (bp.proxy_dynamic[i] < sizing_flag) continue;
    const uint64_t e = box_extent(bp.fat_bounds[i]);
    if (e <= typical_limit && e > size) size = e;
  }
  if (size < static_cast<uint64_t>(k_min_cell_size)) size = static_cast<uint64_t>(k_min_cell_size);
  if (size > static_cast<uint64_t>(k_grid_coordinate_limit)) size = static_cast<uint64_t>(k_grid_coordinate_limit);
  const int64_t cell = static_cast<int64_t>(size);
  const int64_t span = 2 * cell;  // cells are indexed by lower + upper = 2 × centre
  g.cell_size = cell;

  // Cells of the grid proxies; outliers aside.
  g.proxy_cell.resize(n);
  g.proxy_bucket.resize(n);
  size_t grid_count = 0;
  int64_t min_cx = INT64_MAX, max_cx = INT64_MIN, min_cy = INT64_MAX, max_cy = INT64_MIN;
  for (size_t i = 0; i < n; ++i) {
    const AABB& b = bp.fat_bounds[i];
    if (box_extent(b) > size || !within_limit(b.lower.x) || !within_limit(b.lower.y) || !within_limit(b.upper.x) ||
        !within_limit(b.upper.y)) {
      g.proxy_cell[i] = k_outlier_cell;
      g.outliers.push_back(static_cast<int32_t>(i));
      g.outlier_shapes.push_back(bp.proxies[i]);
      continue;
    }
    const int64_t cx = floor_div(b.lower.x.raw + b.upper.x.raw, span);
    const int64_t cy = floor_div(b.lower.y.raw + b.upper.y.raw, span);
    min_cx = cx < min_cx ? cx : min_cx;
    max_cx = cx > max_cx ? cx : max_cx;
    min_cy = cy < min_cy ? cy : min_cy;
    max_cy = cy > max_cy ? cy : max_cy;
    g.proxy_cell[i] = pack_cell(cx, cy);
    ++grid_count;
  }

  // Buckets: a dense row-major array of the occupied cell range when it has
  // at most 4n + 64 cells (neighbours are then adjacent in memory and need no
  // key compare), otherwise a hash table ≥ 2n buckets. Then a counting sort
  // of the grid proxies by bucket (stable: ascending shape index inside one).
  const uint64_t width = grid_count > 0 ? static_cast<uint64_t>(max_cx - min_cx) + 1 : 1;
  const uint64_t height = grid_count > 0 ? static_cast<uint64_t>(max_cy - min_cy) + 1 : 1;
  const bool dense = width * height <= 4 * static_cast<uint64_t>(grid_count) + 64;
  uint32_t bits = 0;
  size_t table = 0;
  if (dense) {
    table = static_cast<size_t>(width * height);
  } else {
    bits = static_cast<uint32_t>(std::bit_width(2 * grid_count + 15));
    table = size_t{1} << bits;
  }
  g.bucket_bits = bits;
  g.bucket_start.assign(table + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    const uint64_t key = g.proxy_cell[i];
    if (key == k_outlier_cell) continue;
    uint32_t b;
    if (dense) {
      const int64_t cx = static_cast<int32_t>(static_cast<uint32_t>(key >> 32));
      const int64_t cy = static_cast<int32_t>(static_cast<uint32_t>(key & 0xFFFFFFFFu));
      b = static_cast<uint32_t>(static_cast<uint64_t>(cy - min_cy) * width + static_cast<uint64_t>(cx - min_cx));
    } else {
      b = cell_bucket(key, bits);
    }
    g.proxy_bucket[i] = b;
    ++g.bucket_start[b + 1];
  }
  for (size_t b = 1; b <= table; ++b) g.bucket_start[b] += g.bucket_start[b - 1];
  g.entries.resize(grid_count);
  for (size_t i = 0; i < n; ++i) {
    if (g.proxy_cell[i] == k_outlier_cell) continue;
    const uint32_t slot = g.bucket_start[g.proxy_bucket[i]]++;
    g.entries[slot] = GridEntry{bp.fat_bounds[i], g.proxy_cell[i], bp.proxies[i], bp.proxy_dynamic[i]};
  }
  for (size_t b = table; b > 0; --b) g.bucket_start[b] = g.bucket_start[b - 1];
  g.bucket_start[0] = 0;
  if (grid_count > 0) {
    g.min_cx = min_cx;
    g.min_cy = min_cy;
    g.max_cx = max_cx;
    g.max_cy = max_cy;
  }
  g.width = width;
  g.dense = dense;
  return pairs_possible;
}

}  // namespace

void grid_sync(World* world) { (void)grid_build(world); }

void grid_update(World* world) {
  if (!grid_build(world)) return;  // no pair can have a dynamic shape
  BroadPhase& bp = world->broad_phase;
  Grid& g = bp.grid;
  const uint64_t width = g.width;
  const uint64_t height = g.entries.empty() ? 1 : static_cast<uint64_t>(g.max_cy - g.min_cy) + 1;
  const bool dense = g.dense;
  const uint32_t bits = g.bucket_bits;
  const size_t table = g.bucket_start.size() - 1;

  const GridEntry* entries = g.entries.data();
  const uint32_t* starts = g.bucket_start.data();
  int64_t candidates = 0;

  // Grid against grid: own cell (later entries) and the forward neighbours
  // (+1,0), (−1,+1), (0,+1), (+1,+1).
  if (dense) {
    const size_t w = static_cast<size_t>(width);
    const size_t h = static_cast<size_t>(height);
    for (size_t y = 0; y < h; ++y) {
      for (size_t x = 0; x < w; ++x) {
        const size_t c = y * w + x;
        const uint32_t end = starts[c + 1];
        if (starts[c] == end) continue;
        // Forward ranges: the right cell, and the up to three cells above
        // (contiguous in the dense order).
        const uint32_t right_begin = x + 1 < w ? starts[c + 1] : 0;
        const uint32_t right_end = x + 1 < w ? starts[c + 2] : 0;
        uint32_t up_begin = 0, up_end = 0;
        if (y + 1 < h) {
          const size_t x0 = x > 0 ? x - 1 : x;
          const size_t x1 = x + 1 < w ? x + 1 : x;
          up_begin = starts[(y + 1) * w + x0];
          up_end = starts[(y + 1) * w + x1 + 1];
        }
        for (uint32_t ei = starts[c]; ei < end; ++ei) {
          const GridEntry& e = entries[ei];
          for (uint32_t ej = ei + 1; ej < end; ++ej) test_entries(world, e, entries[ej], &candidates);
          for (uint32_t ej = right_begin; ej < right_end; ++ej) test_entries(world, e, entries[ej], &candidates);
          for (uint32_t ej = up_begin; ej < up_end; ++ej) test_entries(world, e, entries[ej], &candidates);
        }
      }
    }
  } else {
    static constexpr int64_t k_forward[4][2] = {{1, 0}, {-1, 1}, {0, 1}, {1, 1}};
    for (size_t b = 0; b < table; ++b) {
      const uint32_t end = starts[b + 1];
      for (uint32_t ei = starts[b]; ei < end; ++ei) {
        const GridEntry& e = entries[ei];
        for (uint32_t ej = ei + 1; ej < end; ++ej) {
          if (entries[ej].cell == e.cell) test_entries(world, e, entries[ej], &candidates);
        }
        const int64_t cx = static_cast<int32_t>(static_cast<uint32_t>(e.cell >> 32));
        const int64_t cy = static_cast<int32_t>(static_cast<uint32_t>(e.cell & 0xFFFFFFFFu));
        for (const auto& d : k_forward) {
          const uint64_t key = pack_cell(cx + d[0], cy + d[1]);
          const uint32_t nb = cell_bucket(key, bits);
          const uint32_t nend = starts[nb + 1];
          for (uint32_t ej = starts[nb]; ej < nend; ++ej) {
            if (entries[ej].cell == key) test_entries(world, e, entries[ej], &candidates);
          }
        }
      }
    }
  }

  // Outliers against the grid, then against later outliers.
  const size_t outlier_count = g.outliers.size();
  for (size_t k = 0; k < outlier_count; ++k) {
    const size_t i = static_cast<size_t>(g.outliers[k]);
    const GridEntry o{bp.fat_bounds[i], k_outlier_cell, bp.proxies[i], bp.proxy_dynamic[i]};
    for_each_entry_near(g, o.box, [&](const GridEntry& e) { test_entries(world, o, e, &candidates); });
    for (size_t k2 = k + 1; k2 < outlier_count; ++k2) {
      const size_t j = static_cast<size_t>(g.outliers[k2]);
      const GridEntry p{bp.fat_bounds[j], k_outlier_cell, bp.proxies[j], bp.proxy_dynamic[j]};
      test_entries(world, o, p, &candidates);
    }
  }
  bp.candidate_count += candidates;
}

void grid_search_changed(World* world) {
  BroadPhase& bp = world->broad_phase;
  Grid& g = bp.grid;
  const size_t cap = static_cast<size_t>(id_pool_capacity(world->shape_pool));
  if (g.is_dirty.size() < cap) g.is_dirty.resize(cap, 0);
  for (const int32_t s : bp.changed) {
    const size_t si = static_cast<size_t>(s);
    if (g.is_dirty[si] != 0) continue;
    g.is_dirty[si] = 1;
    g.dirty.push_back(s);
  }
  // Stale entries are read from the dirty list, each against every changed
  // proxy: rebuild (which empties the list) once that costs more than a
  // rebuild's pass over the proxies.
  const size_t n = static_cast<size_t>(bp.proxy_count);
  const size_t d = g.dirty.size();
  if (d > 32 + n / 64 || d * bp.changed.size() > 4 * n + 1024) {
    broad_phase_list_proxies(world);
    (void)grid_build(world);
  }
  for (const int32_t p : bp.changed) {
    const size_t pi = static_cast<size_t>(p);
    if (bp.shape_kind[pi] == k_proxy_none) continue;
    const uint8_t* dirty = g.is_dirty.data();
    for_each_entry_near(g, bp.shape_fat[pi], [&](const GridEntry& e) {
      if (dirty[static_cast<size_t>(e.shape)] == 0) broad_phase_offer_changed(world, p, e.shape);
    });
    for (const int32_t s : g.outlier_shapes) {
      if (dirty[static_cast<size_t>(s)] == 0) broad_phase_offer_changed(world, p, s);
    }
    for (const int32_t s : g.dirty) broad_phase_offer_changed(world, p, s);
  }
}

void grid_query(World* world, BroadPhaseQuery* q) {
  const BroadPhase& bp = world->broad_phase;
  const Grid& g = bp.grid;
  const auto test = [&](const GridEntry& e) {
    if (q->accepts(e.box)) q->offer(e.shape);
  };
  if (g.dense && !g.entries.empty()) {
    // Rows in the ray's vertical direction, each row's cell range from the
    // query's current box: once a closest-hit visitor has pulled the ray's
    // end in, the rows beyond it are not read.
    const int64_t cell = g.cell_size;
    const int64_t span = 2 * cell;
    const bool down = q->is_ray && q->translation.y < Q32::zero();
    const size_t w = static_cast<size_t>(g.width);
    const uint32_t* starts = g.bucket_start.data();
    for (int64_t k = 0; k <= g.max_cy - g.min_cy; ++k) {
      const int64_t cy = down ? g.max_cy - k : g.min_cy + k;
      const AABB& b = q->box;
      if (cy < floor_div(2 * clamp_coordinate(b.lower.y.raw) - cell, span)) {
        if (down) break;
        continue;
      }
      if (cy > floor_div(2 * clamp_coordinate(b.upper.y.raw) + cell, span)) {
        if (down) continue;
        break;
      }
      int64_t x0 = floor_div(2 * clamp_coordinate(b.lower.x.raw) - cell, span);
      int64_t x1 = floor_div(2 * clamp_coordinate(b.upper.x.raw) + cell, span);
      x0 = x0 < g.min_cx ? g.min_cx : x0;
      x1 = x1 > g.max_cx ? g.max_cx : x1;
      if (x0 > x1) continue;
      const size_t row = static_cast<size_t>(cy - g.min_cy) * w;
      const uint32_t end = starts[row + static_cast<size_t>(x1 - g.min_cx) + 1];
      for (uint32_t ej = starts[row + static_cast<size_t>(x0 - g.min_cx)]; ej < end; ++ej) test(g.entries[ej]);
    }
  } else {
    for_each_entry_near(g, q->box, test);
  }
  for (const int32_t i : g.outliers) {
    if (q->accepts(bp.fat_bounds[static_cast<size_t>(i)])) q->offer(bp.proxies[static_cast<size_t>(i)]);
  }
}

}  // namespace tandem
