// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/BoundingBoxTree.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <numeric>

namespace sphcover
{

double Box::Diagonal() const
{
  return glm::length(this->Upper - this->Lower);
}

double Box::DistanceTo(const glm::dvec3& p) const
{
  const glm::dvec3 nearest = glm::clamp(p, this->Lower, this->Upper);
  return glm::length(p - nearest);
}

double Box::MaxHeightAbove(const glm::dvec3& p, const glm::dvec3& n) const
{
  // The corner farthest along n.
  const glm::dvec3 corner(n.x >= 0 ? this->Upper.x : this->Lower.x,
    n.y >= 0 ? this->Upper.y : this->Lower.y,
    n.z >= 0 ? this->Upper.z : this->Lower.z);
  return glm::dot(n, corner - p);
}

void Box::Extend(const Box& other)
{
  this->Lower = glm::min(this->Lower, other.Lower);
  this->Upper = glm::max(this->Upper, other.Upper);
}

BoundingBoxTree::BoundingBoxTree(const std::vector<Box>& boxes, int leafSize)
{
  if (boxes.empty())
  {
    return;
  }
  this->ItemList.resize(boxes.size());
  std::iota(this->ItemList.begin(), this->ItemList.end(), 0);
  this->NodeList.reserve(2 * boxes.size() / static_cast<size_t>(std::max(1, leafSize)) + 1);
  this->Build(boxes, 0, static_cast<int32_t>(boxes.size()), std::max(1, leafSize), 0);
}

int32_t BoundingBoxTree::Build(const std::vector<Box>& boxes,
  int32_t first,
  int32_t count,
  int leafSize,
  int depth)
{
  const int32_t index = static_cast<int32_t>(this->NodeList.size());
  this->NodeList.emplace_back();
  Box bounds = boxes[static_cast<size_t>(this->ItemList[static_cast<size_t>(first)])];
  for (int32_t k = first + 1; k < first + count; ++k)
  {
    bounds.Extend(boxes[static_cast<size_t>(this->ItemList[static_cast<size_t>(k)])]);
  }
  this->NodeList[static_cast<size_t>(index)].Bounds = bounds;
  // The traversal stack holds 128 entries: depth stays far below with median splits, but cap it.
  if (count <= leafSize || depth >= 60)
  {
    this->NodeList[static_cast<size_t>(index)].First = first;
    this->NodeList[static_cast<size_t>(index)].Count = count;
    return index;
  }
  // Median split of the box centres along the longest axis; ties by item index keep the tree
  // (and every traversal order) deterministic.
  const glm::dvec3 extent = bounds.Upper - bounds.Lower;
  const int axis =
    extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  auto begin = this->ItemList.begin() + first;
  auto middle = begin + count / 2;
  std::nth_element(begin,
    middle,
    begin + count,
    [&](int32_t a, int32_t b)
    {
      const double ca =
        boxes[static_cast<size_t>(a)].Lower[axis] + boxes[static_cast<size_t>(a)].Upper[axis];
      const double cb =
        boxes[static_cast<size_t>(b)].Lower[axis] + boxes[static_cast<size_t>(b)].Upper[axis];
      return ca < cb || (ca == cb && a < b);
    });
  const int32_t left = this->Build(boxes, first, count / 2, leafSize, depth + 1);
  const int32_t right =
    this->Build(boxes, first + count / 2, count - count / 2, leafSize, depth + 1);
  this->NodeList[static_cast<size_t>(index)].Left = left;
  this->NodeList[static_cast<size_t>(index)].Right = right;
  return index;
}

void BoundingBoxTree::MarkItems(const std::vector<bool>& flags)
{
  // Children are created after their parent, so a reverse sweep sees children first.
  for (size_t n = this->NodeList.size(); n-- > 0;)
  {
    Node& node = this->NodeList[n];
    if (node.IsLeaf())
    {
      node.Flag = false;
      for (int32_t k = node.First; k < node.First + node.Count; ++k)
      {
        node.Flag = node.Flag || flags[static_cast<size_t>(this->ItemList[static_cast<size_t>(k)])];
      }
    }
    else
    {
      node.Flag = this->NodeList[static_cast<size_t>(node.Left)].Flag ||
        this->NodeList[static_cast<size_t>(node.Right)].Flag;
    }
  }
}

} // namespace sphcover
