// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BoundingBoxTree.h
 * @brief A bounding-volume hierarchy over axis-aligned boxes, for culling the pairwise work
 * of the subdivision: whole groups of patches below a tangent plane are skipped at once
 * (paper §4.1 uses interval boxes of patches in the same way).
 *
 * Input: one box per item; the tree splits at the median of the box centres along the longest
 * axis (std::nth_element) down to leaves of at most leafSize items. Complexity: building
 * O(n log n), a traversal O(nodes entered).
 */
#ifndef SPHCOVER_BOUNDINGBOXTREE_H
#define SPHCOVER_BOUNDINGBOXTREE_H

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace sphcover
{

struct Box
{
  glm::dvec3 Lower{ 0.0 };
  glm::dvec3 Upper{ 0.0 };

  glm::dvec3 Centre() const { return 0.5 * (this->Lower + this->Upper); }
  double Diagonal() const;
  /// Distance from p to the nearest point of the box (0 inside).
  double DistanceTo(const glm::dvec3& p) const;
  /// Largest value of n . (x - p) over the box's corners x: the box is on or below the plane
  /// through p with normal n iff this is <= 0.
  double MaxHeightAbove(const glm::dvec3& p, const glm::dvec3& n) const;
  void Extend(const Box& other);
};

class BoundingBoxTree
{
public:
  struct Node
  {
    Box Bounds;
    /// Children (internal node) or -1.
    int32_t Left = -1;
    int32_t Right = -1;
    /// Items [First, First + Count) of Items() (leaf node).
    int32_t First = 0;
    int32_t Count = 0;
    /// A per-traversal mark the user may set (e.g. "contains new items").
    bool Flag = false;
    bool IsLeaf() const { return this->Left < 0; }
  };

  /// Builds the tree over the boxes (item k is boxes[k]); deterministic.
  explicit BoundingBoxTree(const std::vector<Box>& boxes, int leafSize = 4);

  const std::vector<Node>& Nodes() const { return this->NodeList; }
  /// Item indices in leaf order.
  const std::vector<int32_t>& Items() const { return this->ItemList; }

  /// Sets each node's Flag to whether any of its items has flags[item] true.
  void MarkItems(const std::vector<bool>& flags);

  /// Depth-first traversal: `enter(node)` decides whether to descend into a node (both internal
  /// and leaf nodes); `visit(item)` is called for every item of an entered leaf.
  template<typename Enter, typename Visit>
  void Traverse(Enter&& enter, Visit&& visit) const
  {
    if (this->NodeList.empty())
    {
      return;
    }
    int32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
      const Node& node = this->NodeList[static_cast<size_t>(stack[--top])];
      if (!enter(node))
      {
        continue;
      }
      if (node.IsLeaf())
      {
        for (int32_t k = node.First; k < node.First + node.Count; ++k)
        {
          visit(this->ItemList[static_cast<size_t>(k)]);
        }
      }
      else
      {
        stack[top++] = node.Right;
        stack[top++] = node.Left;
      }
    }
  }

private:
  int32_t Build(const std::vector<Box>& boxes,
    int32_t first,
    int32_t count,
    int leafSize,
    int depth);

  std::vector<Node> NodeList;
  std::vector<int32_t> ItemList;
};

} // namespace sphcover

#endif
