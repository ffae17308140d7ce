// broad_phase_tree.cpp — a dynamic AABB tree (bounding-volume hierarchy)
// kept between updates.
//
// Leaves hold each proxy's fattened box grown by k_tree_margin; a leaf is
// re-inserted only when the shape's fattened box leaves it (or is much
// smaller than it, so a shrunk or teleported shape does not keep a huge box).
// Each update synchronises the tree with the shapes in ascending shape index
// (remove, insert, re-insert), then collides the tree with itself (each leaf
// pair whose tree boxes overlap is met once, at its lowest common ancestor;
// about half the time of one top-down query per dynamic proxy in the 4k
// circles benchmark). The tree's boxes are larger than the fattened ones, so
// every hit goes through the exact test before it is emitted.
//
// Insertion picks the sibling by the surface-area heuristic in 2D (perimeter
// as the cost), in exact integer arithmetic on raw Q32 values (perimeters of
// in-range boxes are < 2^58, sums of a few stay < 2^61); on equal cost it
// takes child1 — the whole procedure is a function of the tree and the box,
// so the same operations in the same order build the same tree everywhere.
// After an insert or a removal every ancestor is refitted and tried for one
// local rotation that shrinks it (a child swaps with a grandchild when that
// makes the grandchild's new parent box smaller). Rejected: AVL-style height
// balancing — it kept the tree shallow but glued distant subtrees together;
// in the 4k circles benchmark a proxy's query visited ~360 nodes, against
// ~50 with the area-reducing rotations (trees of height 15 and 21).
//
// Node pool: a vector with a LIFO free list (deterministic because the
// operations are); it only grows.
#include "physics/broad_phase.h"
#include "physics/world.h"

namespace tandem {

namespace {

using namespace tandem::literals;

/// How far a leaf's box reaches beyond the fattened shape box, m. 0.1 m made
/// the 4k circles step ~1.5× slower (re-inserts outweighed fewer candidates).
constexpr Q32 k_tree_margin = 0.2_q32;

/// Clamp for raw coordinates in cost sums (far outside any world).
constexpr int64_t k_cost_limit = int64_t{1} << 56;

inline int64_t clamp_raw(int64_t v) { return v < -k_cost_limit ? -k_cost_limit : (v > k_cost_limit ? k_cost_limit : v); }

/// Perimeter 2·(w + h) in raw units, from clamped coordinates (< 2^60).
inline int64_t perimeter_raw(const AABB& b) {
  const int64_t w = clamp_raw(b.upper.x.raw) - clamp_raw(b.lower.x.raw);
  const int64_t h = clamp_raw(b.upper.y.raw) - clamp_raw(b.lower.y.raw);
  return 2 * (w + h);
}

/// aabb_union on raw values (the same result; inlined in the hot loops).
inline AABB union_box(const AABB& a, const AABB& b) {
  AABB u;
  u.lower.x.raw = a.lower.x.raw < b.lower.x.raw ? a.lower.x.raw : b.lower.x.raw;
  u.lower.y.raw = a.lower.y.raw < b.lower.y.raw ? a.lower.y.raw : b.lower.y.raw;
  u.upper.x.raw = a.upper.x.raw > b.upper.x.raw ? a.upper.x.raw : b.upper.x.raw;
  u.upper.y.raw = a.upper.y.raw > b.upper.y.raw ? a.upper.y.raw : b.upper.y.raw;
  return u;
}

int32_t allocate_node(DynamicTree* t) {
  int32_t index;
  if (t->free_list != -1) {
    index = t->free_list;
    t->free_list = t->nodes[static_cast<size_t>(index)].parent;
  } else {
    index = static_cast<int32_t>(t->nodes.size());
    t->nodes.emplace_back();
  }
  TreeNode& n = t->nodes[static_cast<size_t>(index)];
  n = TreeNode{};
  return index;
}

void free_node(DynamicTree* t, int32_t index) {
  TreeNode& n = t->nodes[static_cast<size_t>(index)];
  n.parent = t->free_list;
  n.height = -1;
  n.child1 = -1;
  n.child2 = -1;
  n.shape = -1;
  t->free_list = index;
}

TreeNode& node(DynamicTree* t, int32_t i) { return t->nodes[static_cast<size_t>(i)]; }

int32_t max_i(int32_t a, int32_t b) { return a > b ? a : b; }

/// One local rotation at inner node `ia` (children B, C) when it shrinks the
/// tree: B swaps with a child of C, or C with a child of B, whichever leaves
/// the changed child's box with the smallest perimeter, if that is smaller
/// than now. The leaves under `ia` stay the same, so its box does not change.
/// Candidates are tried in a fixed order and only a strictly better one
/// replaces the current best, so the choice is a function of the boxes.
void rotate(DynamicTree* t, int32_t ia) {
  TreeNode& a = node(t, ia);
  if (a.child1 == -1 || a.height < 2) return;
  const int32_t ib = a.child1;
  const int32_t ic = a.child2;
  TreeNode& b = node(t, ib);
  TreeNode& c = node(t, ic);
  // Options: 0 none, 1 B↔C.child1, 2 B↔C.child2, 3 C↔B.child1, 4 C↔B.child2.
  int32_t best = 0;
  int64_t best_gain = 0;
  AABB best_box{};
  const auto consider = [&](int32_t option, const AABB& kept, const AABB& moved, int64_t current) {
    const AABB box = union_box(kept, moved);
    const int64_t gain = current - perimeter_raw(box);
    if (gain > best_gain) {
      best_gain = gain;
      best = option;
      best_box = box;
    }
  };
  if (c.child1 != -1) {
    const int64_t current = perimeter_raw(c.box);
    consider(1, node(t, c.child2).box, b.box, current);
    consider(2, node(t, c.child1).box, b.box, current);
  }
  if (b.child1 != -1) {
    const int64_t current = perimeter_raw(b.box);
    consider(3, node(t, b.child2).box, c.box, current);
    consider(4, node(t, b.child1).box, c.box, current);
  }
  if (best == 0) return;
  if (best <= 2) {
    // B moves under C, replacing one of C's children, which moves up to A.
    const int32_t iup = best == 1 ? c.child1 : c.child2;
    if (best == 1) {
      c.child1 = ib;
    } else {
      c.child2 = ib;
    }
    b.parent = ic;
    a.child1 = iup;
    node(t, iup).parent = ia;
    c.box = best_box;
    c.height = 1 + max_i(node(t, c.child1).height, node(t, c.child2).height);
  } else {
    const int32_t iup = best == 3 ? b.child1 : b.child2;
    if (best == 3) {
      b.child1 = ic;
    } else {
      b.child2 = ic;
    }
    c.parent = ib;
    a.child2 = iup;
    node(t, iup).parent = ia;
    b.box = best_box;
    b.height = 1 + max_i(node(t, b.child1).height, node(t, b.child2).height);
  }
  a.height = 1 + max_i(node(t, a.child1).height, node(t, a.child2).height);
}

/// Refits boxes and heights from `index` to the root, rotating on the way.
void refit_upwards(DynamicTree* t, int32_t index) {
  while (index != -1) {
    TreeNode& n = node(t, index);
    const TreeNode& c1 = node(t, n.child1);
    const TreeNode& c2 = node(t, n.child2);
    n.height = 1 + max_i(c1.height, c2.height);
    n.box = union_box(c1.box, c2.box);
    rotate(t, index);
    index = node(t, index).parent;
  }
}

void insert_leaf(DynamicTree* t, int32_t leaf) {
  if (t->root == -1) {
    t->root = leaf;
    node(t, leaf).parent = -1;
    return;
  }
  const AABB box = node(t, leaf).box;
  int32_t index = t->root;
  while (node(t, index).child1 != -1) {
    const TreeNode& n = node(t, index);
    const int64_t area = perimeter_raw(n.box);
    const int64_t combined = perimeter_raw(union_box(n.box, box));
    const int64_t cost_here = 2 * combined;            // new parent of n and the leaf
    const int64_t inherited = 2 * (combined - area);   // growth pushed onto descendants
    int64_t cost[2];
    const int32_t child[2] = {n.child1, n.child2};
    for (int32_t k = 0; k < 2; ++k) {
      const TreeNode& c = node(t, child[k]);
      const int64_t grown = perimeter_raw(union_box(c.box, box));
      cost[k] = (c.child1 == -1 ? grown : grown - perimeter_raw(c.box)) + inherited;
    }
    if (cost_here < cost[0] && cost_here < cost[1]) break;
    index = cost[0] <= cost[1] ? child[0] : child[1];
  }
  const int32_t sibling = index;
  const int32_t old_parent = node(t, sibling).parent;
  const int32_t parent = allocate_node(t);
  TreeNode& p = node(t, parent);
  p.parent = old_parent;
  p.box = union_box(box, node(t, sibling).box);
  p.height = node(t, sibling).height + 1;
  p.child1 = sibling;
  p.child2 = leaf;
  node(t, sibling).parent = parent;
  node(t, leaf).parent = parent;
  if (old_parent != -1) {
    TreeNode& op = node(t, old_parent);
    if (op.child1 == sibling) {
      op.child1 = parent;
    } else {
      op.child2 = parent;
    }
  } else {
    t->root = parent;
  }
  refit_upwards(t, parent);
}

void remove_leaf(DynamicTree* t, int32_t leaf) {
  if (leaf == t->root) {
    t->root = -1;
    return;
  }
  const int32_t parent = node(t, leaf).parent;
  const int32_t grand = node(t, parent).parent;
  const int32_t sibling = node(t, parent).child1 == leaf ? node(t, parent).child2 : node(t, parent).child1;
  if (grand != -1) {
    TreeNode& g = node(t, grand);
    if (g.child1 == parent) {
      g.child1 = sibling;
    } else {
      g.child2 = sibling;
    }
    node(t, sibling).parent = grand;
    free_node(t, parent);
    refit_upwards(t, grand);
  } else {
    t->root = sibling;
    node(t, sibling).parent = -1;
    free_node(t, parent);
  }
}

/// True when the leaf box should be rebuilt around `fat`.
bool needs_reinsert(const AABB& stored, const AABB& fat) {
  if (!aabb_contains(stored, fat)) return true;
  return !aabb_contains(aabb_fatten(fat, k_tree_margin * 4), stored);
}

/// Brings shape s's leaf up to date: removed when the shape takes no part
/// (or its slot is at or beyond `cap`), re-inserted when its fattened box
/// left the leaf's box (needs_reinsert), inserted when new.
void sync_shape(BroadPhase* bp, int32_t s, int32_t cap) {
  DynamicTree& t = bp->tree;
  const size_t si = static_cast<size_t>(s);
  int32_t leaf = t.leaf_of_shape[si];
  const bool takes_part = s < cap && bp->shape_kind[si] != k_proxy_none;
  if (leaf != -1) {
    if (takes_part && !needs_reinsert(node(&t, leaf).box, bp->shape_fat[si])) return;
    remove_leaf(&t, leaf);
    free_node(&t, leaf);
    t.leaf_of_shape[si] = -1;
    leaf = -1;
  }
  if (!takes_part) return;
  leaf = allocate_node(&t);
  TreeNode& n = node(&t, leaf);
  n.box = aabb_fatten(bp->shape_fat[si], k_tree_margin);
  n.shape = s;
  n.height = 0;
  insert_leaf(&t, leaf);
  t.leaf_of_shape[si] = leaf;
}

}  // namespace

void tree_reset(DynamicTree* tree) {
  tree->nodes.clear();
  tree->root = -1;
  tree->free_list = -1;
  tree->leaf_of_shape.clear();
}

void tree_sync(World* world) {
  BroadPhase& bp = world->broad_phase;
  DynamicTree& t = bp.tree;
  const int32_t cap = id_pool_capacity(world->shape_pool);
  if (t.leaf_of_shape.size() < static_cast<size_t>(cap)) t.leaf_of_shape.resize(static_cast<size_t>(cap), -1);

  // Synchronise with the shapes, ascending shape index (slots beyond the
  // pool, which a restore may leave, lose their leaves).
  const int32_t slots = static_cast<int32_t>(t.leaf_of_shape.size());
  for (int32_t s = 0; s < slots; ++s) sync_shape(&bp, s, cap);
}

void tree_sync_changed(World* world) {
  BroadPhase& bp = world->broad_phase;
  DynamicTree& t = bp.tree;
  const int32_t cap = id_pool_capacity(world->shape_pool);
  if (t.leaf_of_shape.size() < static_cast<size_t>(cap)) t.leaf_of_shape.resize(static_cast<size_t>(cap), -1);
  for (const int32_t s : bp.changed) sync_shape(&bp, s, cap);
}

void tree_update(World* world) {
  tree_sync(world);
  BroadPhase& bp = world->broad_phase;
  DynamicTree& t = bp.tree;

  // All overlapping leaf pairs in one traversal of the tree against itself:
  // a node's pairs are those inside each child plus those across the two
  // children, so each leaf pair is met exactly once, at its lowest common
  // ancestor. Items on the stack are node pairs (a, b); a == b means "pairs
  // inside a". Across two nodes, the one with the larger box is split (a
  // leaf never is; on a tie the first), a function of the tree alone.
  if (t.root == -1) return;
  int64_t candidates = 0;
  std::vector<int32_t>& stack = t.stack;
  stack.clear();
  stack.push_back(t.root);
  stack.push_back(t.root);
  while (!stack.empty()) {
    const int32_t ib = stack.back();
    stack.pop_back();
    const int32_t ia = stack.back();
    stack.pop_back();
    const TreeNode& a = t.nodes[static_cast<size_t>(ia)];
    if (ia == ib) {
      if (a.child1 == -1) continue;
      const int32_t c1 = a.child1, c2 = a.child2;
      stack.push_back(c1);
      stack.push_back(c1);
      stack.push_back(c2);
      stack.push_back(c2);
      stack.push_back(c1);
      stack.push_back(c2);
      continue;
    }
    const TreeNode& b = t.nodes[static_cast<size_t>(ib)];
    if (!aabb_overlaps(a.box, b.box)) continue;
    const bool a_leaf = a.child1 == -1;
    const bool b_leaf = b.child1 == -1;
    if (a_leaf && b_leaf) {
      const size_t sa = static_cast<size_t>(a.shape);
      const size_t sb = static_cast<size_t>(b.shape);
      if (bp.shape_kind[sa] != k_proxy_dynamic && bp.shape_kind[sb] != k_proxy_dynamic) continue;
      ++candidates;
      if (aabb_overlaps(bp.shape_fat[sa], bp.shape_fat[sb])) broad_phase_emit_overlapping(world, a.shape, b.shape);
      continue;
    }
    const bool split_a = b_leaf || (!a_leaf && perimeter_raw(a.box) >= perimeter_raw(b.box));
    if (split_a) {
      const int32_t c1 = a.child1, c2 = a.child2;
      stack.push_back(c1);
      stack.push_back(ib);
      stack.push_back(c2);
      stack.push_back(ib);
    } else {
      const int32_t c1 = b.child1, c2 = b.child2;
      stack.push_back(ia);
      stack.push_back(c1);
      stack.push_back(ia);
      stack.push_back(c2);
    }
  }
  bp.candidate_count += candidates;
}

void tree_query(World* world, BroadPhaseQuery* q) {
  BroadPhase& bp = world->broad_phase;
  DynamicTree& t = bp.tree;
  if (t.root == -1) return;
  // Depth first. A box query takes child1 first; a ray takes first the child
  // whose box centre comes first along the ray's dominant axis (child1 on a
  // tie), so a closest-hit query usually meets its hit early and pulls the
  // ray in. Either order is a function of the tree and the query alone.
  const auto magnitude = [](int64_t v) { return v < 0 ? uint64_t{0} - static_cast<uint64_t>(v) : static_cast<uint64_t>(v); };
  const bool along_x = magnitude(q->translation.x.raw) >= magnitude(q->translation.y.raw);
  const int64_t dir = along_x ? q->translation.x.raw : q->translation.y.raw;
  // Doubled centre on that axis (< 2^62 for any tree box), negated for a ray
  // going the negative way: smaller comes first.
  const auto key = [&](const AABB& b) {
    const int64_t c2 = along_x ? b.lower.x.raw + b.upper.x.raw : b.lower.y.raw + b.upper.y.raw;
    return dir < 0 ? -c2 : c2;
  };
  std::vector<int32_t>& stack = t.stack;
  stack.clear();
  stack.push_back(t.root);
  while (!stack.empty()) {
    const int32_t i = stack.back();
    stack.pop_back();
    const TreeNode& n = t.nodes[static_cast<size_t>(i)];
    if (!q->accepts(n.box)) continue;
    if (n.child1 != -1) {
      const bool swap = q->is_ray && key(t.nodes[static_cast<size_t>(n.child2)].box) <
                                         key(t.nodes[static_cast<size_t>(n.child1)].box);
      stack.push_back(swap ? n.child1 : n.child2);
      stack.push_back(swap ? n.child2 : n.child1);
      continue;
    }
    if (q->accepts(bp.shape_fat[static_cast<size_t>(n.shape)])) q->offer(n.shape);
  }
}

int32_t tree_validate(const DynamicTree& tree) {
  if (tree.root == -1) return 0;
  if (tree.nodes[static_cast<size_t>(tree.root)].parent != -1) return -1;
  int32_t leaves = 0;
  std::vector<int32_t> stack{tree.root};
  while (!stack.empty()) {
    const int32_t i = stack.back();
    stack.pop_back();
    const TreeNode& n = tree.nodes[static_cast<size_t>(i)];
    if (n.child1 == -1) {
      if (n.height != 0 || n.shape < 0) return -1;
      ++leaves;
      continue;
    }
    const TreeNode& c1 = tree.nodes[static_cast<size_t>(n.child1)];
    const TreeNode& c2 = tree.nodes[static_cast<size_t>(n.child2)];
    if (c1.parent != i || c2.parent != i) return -1;
    if (n.height != 1 + max_i(c1.height, c2.height)) return -1;
    if (!aabb_contains(n.box, c1.box) || !aabb_contains(n.box, c2.box)) return -1;
    stack.push_back(n.child1);
    stack.push_back(n.child2);
  }
  return leaves;
}

}  // namespace tandem
