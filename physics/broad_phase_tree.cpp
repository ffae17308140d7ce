// broad_phase_tree.cpp — a dynamic AABB tree (bounding-volume hierarchy)
// kept between updates.
//
// Leaves hold each proxy's fattened box grown by k_tree_margin; a leaf is
// re-inserted only when the shape's fattened box leaves it (or is much
// smaller than it, so a shrunk or teleported shape does not keep a huge box).
// Each update synchronises the tree with the shapes in ascending shape index
// (remove, insert, re-insert), then queries it with every dynamic proxy's
// fattened box. A hit on a dynamic shape with a lower index is skipped (that
// pair was found from the lower one's query); static and kinematic proxies
// never query, so a pair with one of them is found once, from the dynamic
// side. The tree's boxes are larger than the fattened ones, so every hit goes
// through the exact test before it is emitted.
//
// Insertion picks the sibling by the surface-area heuristic in 2D (perimeter
// as the cost), in exact integer arithmetic on raw Q32 values (perimeters of
// in-range boxes are < 2^58, sums of a few stay < 2^61); on equal cost it
// takes child1 — the whole procedure is a function of the tree and the box,
// so the same operations in the same order build the same tree everywhere.
// After an insert or a removal every ancestor is rebalanced with an AVL-style
// rotation when its children's heights differ by more than one.
//
// Node pool: a vector with a LIFO free list (deterministic because the
// operations are); it only grows.
#include "physics/broad_phase.h"
#include "physics/world.h"

namespace tandem {

namespace {

using namespace tandem::literals;

/// How far a leaf's box reaches beyond the fattened shape box, m.
constexpr Q32 k_tree_margin = 0.1_q32;

/// Clamp for raw coordinates in cost sums (far outside any world).
constexpr int64_t k_cost_limit = int64_t{1} << 56;

int64_t clamp_raw(int64_t v) { return v < -k_cost_limit ? -k_cost_limit : (v > k_cost_limit ? k_cost_limit : v); }

/// Perimeter 2·(w + h) in raw units, from clamped coordinates (< 2^60).
int64_t perimeter_raw(const AABB& b) {
  const int64_t w = clamp_raw(b.upper.x.raw) - clamp_raw(b.lower.x.raw);
  const int64_t h = clamp_raw(b.upper.y.raw) - clamp_raw(b.lower.y.raw);
  return 2 * (w + h);
}

AABB union_box(const AABB& a, const AABB& b) { return aabb_union(a, b); }

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

/// Rebalances the subtree at `a` by one rotation when needed; returns the
/// subtree's new root.
int32_t balance(DynamicTree* t, int32_t ia) {
  TreeNode& a = node(t, ia);
  if (a.child1 == -1 || a.height < 2) return ia;
  const int32_t ib = a.child1;
  const int32_t ic = a.child2;
  const int32_t diff = node(t, ic).height - node(t, ib).height;
  if (diff > 1 || diff < -1) {
    // Lift the taller child `up`; `other` stays under a.
    const bool lift_c = diff > 1;
    const int32_t iup = lift_c ? ic : ib;
    TreeNode& up = node(t, iup);
    const int32_t i1 = up.child1;
    const int32_t i2 = up.child2;
    // up takes a's place.
    up.parent = a.parent;
    a.parent = iup;
    if (up.parent != -1) {
      TreeNode& p = node(t, up.parent);
      if (p.child1 == ia) {
        p.child1 = iup;
      } else {
        p.child2 = iup;
      }
    } else {
      t->root = iup;
    }
    // The taller of up's children stays with up; the shorter goes to a in
    // up's old place. On equal heights child1 stays (deterministic).
    const bool keep_1 = node(t, i1).height >= node(t, i2).height;
    const int32_t keep = keep_1 ? i1 : i2;
    const int32_t give = keep_1 ? i2 : i1;
    up.child1 = ia;
    up.child2 = keep;
    if (lift_c) {
      a.child2 = give;
    } else {
      a.child1 = give;
    }
    node(t, give).parent = ia;
    a.box = union_box(node(t, a.child1).box, node(t, a.child2).box);
    a.height = 1 + max_i(node(t, a.child1).height, node(t, a.child2).height);
    up.box = union_box(a.box, node(t, keep).box);
    up.height = 1 + max_i(a.height, node(t, keep).height);
    return iup;
  }
  return ia;
}

/// Refits boxes and heights from `index` to the root, rebalancing on the way.
void refit_upwards(DynamicTree* t, int32_t index) {
  while (index != -1) {
    index = balance(t, index);
    TreeNode& n = node(t, index);
    const TreeNode& c1 = node(t, n.child1);
    const TreeNode& c2 = node(t, n.child2);
    n.height = 1 + max_i(c1.height, c2.height);
    n.box = union_box(c1.box, c2.box);
    index = n.parent;
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

}  // namespace

void tree_reset(DynamicTree* tree) {
  tree->nodes.clear();
  tree->root = -1;
  tree->free_list = -1;
  tree->leaf_of_shape.clear();
}

void tree_query(const DynamicTree& tree, AABB box, std::vector<int32_t>* stack, std::vector<int32_t>* out) {
  if (tree.root == -1) return;
  stack->clear();
  stack->push_back(tree.root);
  while (!stack->empty()) {
    const int32_t i = stack->back();
    stack->pop_back();
    const TreeNode& n = tree.nodes[static_cast<size_t>(i)];
    if (!aabb_overlaps(n.box, box)) continue;
    if (n.child1 == -1) {
      out->push_back(n.shape);
    } else {
      stack->push_back(n.child2);
      stack->push_back(n.child1);
    }
  }
}

void tree_update(World* world) {
  BroadPhase& bp = world->broad_phase;
  DynamicTree& t = bp.tree;
  const int32_t cap = id_pool_capacity(world->shape_pool);
  if (t.leaf_of_shape.size() < static_cast<size_t>(cap)) t.leaf_of_shape.resize(static_cast<size_t>(cap), -1);

  // Synchronise with the shapes, ascending shape index.
  for (int32_t s = 0; s < cap; ++s) {
    const size_t si = static_cast<size_t>(s);
    int32_t leaf = t.leaf_of_shape[si];
    const bool takes_part = bp.shape_kind[si] != k_proxy_none;
    if (leaf != -1) {
      if (takes_part && !needs_reinsert(node(&t, leaf).box, bp.shape_fat[si])) continue;
      remove_leaf(&t, leaf);
      free_node(&t, leaf);
      t.leaf_of_shape[si] = -1;
      leaf = -1;
    }
    if (!takes_part) continue;
    leaf = allocate_node(&t);
    TreeNode& n = node(&t, leaf);
    n.box = aabb_fatten(bp.shape_fat[si], k_tree_margin);
    n.shape = s;
    n.height = 0;
    insert_leaf(&t, leaf);
    t.leaf_of_shape[si] = leaf;
  }

  // Query with every dynamic proxy.
  if (t.root == -1) return;
  int64_t candidates = 0;
  for (const int32_t s : bp.proxies) {
    const size_t si = static_cast<size_t>(s);
    if (bp.shape_kind[si] != k_proxy_dynamic) continue;
    const AABB box = bp.shape_fat[si];
    t.stack.clear();
    t.stack.push_back(t.root);
    while (!t.stack.empty()) {
      const int32_t i = t.stack.back();
      t.stack.pop_back();
      const TreeNode& n = t.nodes[static_cast<size_t>(i)];
      if (!aabb_overlaps(n.box, box)) continue;
      if (n.child1 != -1) {
        t.stack.push_back(n.child2);
        t.stack.push_back(n.child1);
        continue;
      }
      const int32_t other = n.shape;
      if (other == s) continue;
      const size_t oi = static_cast<size_t>(other);
      if (bp.shape_kind[oi] == k_proxy_dynamic && other < s) continue;  // found from `other`
      ++candidates;
      if (aabb_overlaps(box, bp.shape_fat[oi])) broad_phase_emit_overlapping(world, s, other);
    }
  }
  bp.candidate_count += candidates;
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
