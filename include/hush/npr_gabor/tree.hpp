// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The hierarchical point sequence of one NPR Gabor triangle (docs/npr-gabor.md,
// "Huge triangles"): the triangle is subdivided at its edge midpoints (object-
// space barycentrics) into four children, recursively; every node P holds one
// point of the sequence (its own point, uniform in P) and a uniformly random
// order of its four children. The sequence of P is
//   s_P(0) = P's own point,  s_P(i) = s_{child at slot d}(q),
//   d = (i - 1) mod 4, q = floor((i - 1) / 4)   for i >= 1,
// so the node reached from the root through slots d_1 ... d_k holds the root's
// indices J = index + stride i with index = sum_m 4^(m-1) (1 + d_m) (its own
// point) and stride = 4^k. Every point lies in its node, so a subtree whose
// screen triangle misses the image can be skipped without changing any other
// point, its index or its weight: the culled walk emits exactly the points that
// generating all of them and culling each would keep. The marginal of every
// point is uniform on the triangle (uniform child at every level, uniform own
// point), so the noise's autocovariance and spectrum are those of independent
// points (only the diagonal of the double sum survives: zero-mean amplitudes).
//
// This header is the definition both stage-1 backends implement: the CPU walk
// (npr_gabor.hpp) and the GPU passes (backends/glsl) produce the same nodes.
//   - the root is the triangle: seed = its key, index 0, stride 1, corners the
//     identity (so its own point is the point 0 of the flat sequence);
//   - a node takes kNprGaborWordsPerNode words of hush::rng(seed,
//     kNprGaborStream): word 0 [u:16 | v:16] its own point, local barycentrics
//     (1 - sqrt u, sqrt u (1 - v), sqrt u v) of its corners; word 1
//     [amplitude:16 | angle:16] (2 half - 1, 2 pi half); word 2 the child order,
//     entry (word * 24) >> 32 of kNprGaborChildOrder;
//   - geometric child c < 3 keeps corner c and takes the midpoints of the
//     edges from corner c to the other two, in corner order; child 3 (the
//     middle) has as corner i the midpoint of the edge opposite corner i;
//   - child c's seed is hash32(seed, c).
// Midpoints of dyadic barycentrics are exact in floating point to depth 52
// (double) and 23 (float), far beyond any index below kNprGaborMaxPoints.

#ifndef HUSH_NPR_GABOR_TREE_HPP
#define HUSH_NPR_GABOR_TREE_HPP

#include <cstdint>

#include "hush/config.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/rng.hpp"
#include "hush/detail/constants.hpp"

namespace hush {
namespace detail {

struct npr_tree_node {
  std::uint32_t seed = 0;    // the node's seed (the root's: the triangle's key)
  std::uint64_t index = 0;   // J of the node's own point
  std::uint64_t stride = 1;  // 4^depth: the subtree holds J = index + stride i
  // corner[i][k]: barycentric coordinate k (of the root triangle) of corner i.
  double corner[3][3] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
};

// The node's words: its own point's position, its value, its children's order.
struct npr_tree_words {
  std::uint32_t point = 0, value = 0, order = 0;
};

HUSH_INLINE npr_tree_words npr_tree_words_of(std::uint32_t seed) {
  rng r(seed, constants::kNprGaborStream);
  npr_tree_words w;
  w.point = r.next_u32();
  w.value = r.next_u32();
  w.order = r.next_u32();
  return w;
}

// The geometric child (0 ... 3) at slot (0 ... 3) of a node with order word w.
HUSH_INLINE unsigned npr_tree_child_at(std::uint32_t order_word, unsigned slot) {
  const auto p = static_cast<unsigned>(
      (static_cast<std::uint64_t>(order_word) * constants::kNprGaborChildOrders) >> 32);
  return (constants::kNprGaborChildOrder[p] >> (2 * slot)) & 3u;
}

// The node at `slot` of p (words: p's words). No overflow check: callers only
// descend while index + stride * (1 + slot) is below the point count, which
// kNprGaborMaxPoints keeps far below 2^64.
HUSH_INLINE npr_tree_node npr_tree_child(const npr_tree_node& p, const npr_tree_words& w,
                                         unsigned slot) {
  const unsigned c = npr_tree_child_at(w.order, slot);
  npr_tree_node n;
  n.seed = hash32(p.seed, c);
  n.index = p.index + p.stride * (1u + slot);
  n.stride = p.stride * 4u;
  for (unsigned i = 0; i < 3; ++i) {
    // Corner i of child c < 3: corner c itself (i == c) or the midpoint of
    // corners c and i; of the middle child: the midpoint opposite corner i.
    const unsigned a = c < 3 ? c : (i + 1) % 3;
    const unsigned b = c < 3 ? i : (i + 2) % 3;
    for (unsigned k = 0; k < 3; ++k)
      n.corner[i][k] = 0.5 * (p.corner[a][k] + p.corner[b][k]);
  }
  return n;
}

}  // namespace detail
}  // namespace hush

#endif  // HUSH_NPR_GABOR_TREE_HPP
