// A bounding-box hierarchy over planar items (triangles or points), each with a value, for the
// density queries of DensityField and the triangulated source measure: the item containing a
// point, the items meeting a box, and the largest value over a region. Written by hand because
// CGAL 5.5's AABB tree is 3D only and a uniform grid degrades on conformal images, whose triangles
// shrink by 1e10 and more towards a finger tip (thousands of triangles per grid bucket). Each node
// keeps the largest value below it, so a maximum query skips every subtree that cannot raise the
// current best.
#ifndef OTPARAM_COMMON_BOXTREE_H
#define OTPARAM_COMMON_BOXTREE_H

#include "Common/Geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace otparam
{

class BoxTree
{
public:
  struct Item
  {
    Vec2 lo, hi;
    double value;
  };

  BoxTree() = default;
  explicit BoxTree(std::vector<Item> items)
  {
    const int n = static_cast<int>(items.size());
    if (n == 0)
    {
      return;
    }
    std::vector<Entry> entries(items.size());
    for (int id = 0; id < n; ++id)
    {
      entries[id] = { items[id], id };
    }
    items = std::vector<Item>(); // freed before the tree's own copy is made
    this->Nodes.resize(static_cast<size_t>(nodeCount(n)));
#pragma omp parallel
#pragma omp single
    this->build(entries, 0, n, 0);
    this->Items.resize(entries.size());
    this->Order.resize(entries.size());
    for (int k = 0; k < n; ++k)
    {
      this->Items[k] = entries[k].item;
      this->Order[k] = entries[k].id;
    }
  }

  // Calls visit(item) for every item whose box contains x, until visit returns true.
  template <typename Visit>
  bool findContaining(Vec2 x, const Visit& visit) const
  {
    return !this->Nodes.empty() && this->findContaining(0, x, visit);
  }

  // Calls visit(slot) for every item whose box meets [lo, hi], where slot is the item's place in
  // the tree's order (itemAt(slot) is its id): data the caller keeps in slot order is then read
  // from one stretch of memory per leaf (TriangulatedSource's triangles).
  template <typename Visit>
  void forOverlappingSlots(Vec2 lo, Vec2 hi, const Visit& visit) const
  {
    if (!this->Nodes.empty())
    {
      this->forOverlappingSlots(0, lo, hi, visit);
    }
  }
  int itemAt(int slot) const
  {
    return this->Order[slot];
  }
  const Item& box(int slot) const
  {
    return this->Items[slot];
  }

  // Calls consider(slot, best) for every item whose box meets [lo, hi] and whose value
  // exceeds best (slot as in forOverlappingSlots; box(slot) is the item's box and value);
  // consider may raise best. Subtrees whose box `mayMeet(boxLo, boxHi)` rules out
  // are skipped too (a query region thinner than its bounding box: a long thin triangle's box
  // covers much of the domain, and without this the first refinement steps on a 2e6-triangle
  // density took 1.6 s each).
  template <typename Consider, typename MayMeet>
  void maximize(
    Vec2 lo, Vec2 hi, double& best, const Consider& consider, const MayMeet& mayMeet) const
  {
    if (!this->Nodes.empty())
    {
      this->maximize(0, lo, hi, best, consider, mayMeet);
    }
  }

  // The item nearest to x, by `distance(item)` (never below the distance from x to the item's
  // box), the lowest id among equals as a scan in id order finds it; -1 for an empty tree.
  template <typename Distance>
  int nearest(Vec2 x, const Distance& distance) const
  {
    int best = -1;
    double bestDistance = std::numeric_limits<double>::infinity();
    if (!this->Nodes.empty())
    {
      this->nearest(0, x, distance, best, bestDistance);
    }
    return best;
  }

private:
  static constexpr int LeafSize = 8;

  struct Node
  {
    Vec2 lo, hi;
    double maximum;
    int begin, end; // range of Order
    int left = -1, right = -1;
  };

  // Nodes of the subtree over n items (the split below halves the count), level by level: the
  // subtrees of one level hold only two sizes, `size` and `size + 1` items, so this takes
  // O(log n) where counting every subtree took O(n), at every node of the build.
  static int nodeCount(int n)
  {
    std::int64_t size = n, count = 1, countPlusOne = 0, total = 0;
    while (count + countPlusOne > 0)
    {
      total += count + countPlusOne;
      const std::int64_t half = size / 2;
      std::int64_t next = 0, nextPlusOne = 0; // subtrees of half and half + 1 items
      auto split = [&](std::int64_t items, std::int64_t subtrees)
      {
        if (items > LeafSize)
        {
          (items / 2 == half ? next : nextPlusOne) += subtrees;
          (items - items / 2 == half ? next : nextPlusOne) += subtrees;
        }
      };
      split(size, count);
      split(size + 1, countPlusOne);
      size = half;
      count = next;
      countPlusOne = nextPlusOne;
    }
    return static_cast<int>(total);
  }

  // An item with its id, as the build moves it: the split's selection compares and moves the
  // boxes themselves rather than ids pointing into the item array (2.2M density triangles:
  // that indirection's cache misses made the builds ~3% of a 1.09M-point map's CPU time).
  struct Entry
  {
    Item item;
    int id;
  };

  // Fills the subtree over entries[begin, end) from Nodes[index] on, in preorder: every node's
  // place follows from the counts alone, so the two halves of a large node are built as
  // parallel tasks into the same array a serial build fills (2.2M triangles: ~0.3 s serially).
  // Afterwards entries[k] is the item in slot k: leaves read their boxes from one stretch of
  // memory (the tree walks were a third of the sampler's integrations when they gathered them
  // by id).
  void build(std::vector<Entry>& entries, int begin, int end, int index)
  {
    Node& node = this->Nodes[index];
    node.begin = begin;
    node.end = end;
    node.lo = { std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity() };
    node.hi = { -node.lo.x, -node.lo.y };
    node.maximum = -std::numeric_limits<double>::infinity();
    for (int k = begin; k < end; ++k)
    {
      const Item& item = entries[k].item;
      node.lo = { std::min(node.lo.x, item.lo.x), std::min(node.lo.y, item.lo.y) };
      node.hi = { std::max(node.hi.x, item.hi.x), std::max(node.hi.y, item.hi.y) };
      node.maximum = std::max(node.maximum, item.value);
    }
    if (end - begin <= LeafSize)
    {
      return;
    }
    // Median split of the box centres along the longer side.
    const bool alongX = node.hi.x - node.lo.x >= node.hi.y - node.lo.y;
    auto centre = [&](const Entry& entry)
    {
      const Item& item = entry.item;
      return alongX ? item.lo.x + item.hi.x : item.lo.y + item.hi.y;
    };
    const int middle = begin + (end - begin) / 2;
    std::nth_element(entries.begin() + begin, entries.begin() + middle, entries.begin() + end,
      [&](const Entry& a, const Entry& b) { return centre(a) < centre(b); });
    node.left = index + 1;
    node.right = index + 1 + nodeCount(middle - begin);
    const int left = node.left, right = node.right;
#pragma omp task if (end - begin > 65536) default(none) firstprivate(begin, middle, left)          \
  shared(entries)
    this->build(entries, begin, middle, left);
    this->build(entries, middle, end, right);
#pragma omp taskwait
  }

  static bool overlaps(const Node& node, Vec2 lo, Vec2 hi)
  {
    return node.lo.x <= hi.x && lo.x <= node.hi.x && node.lo.y <= hi.y && lo.y <= node.hi.y;
  }

  template <typename Visit>
  bool findContaining(int index, Vec2 x, const Visit& visit) const
  {
    const Node& node = this->Nodes[index];
    if (!overlaps(node, x, x))
    {
      return false;
    }
    if (node.left < 0)
    {
      for (int k = node.begin; k < node.end; ++k)
      {
        const Item& item = this->Items[k];
        if (item.lo.x <= x.x && x.x <= item.hi.x && item.lo.y <= x.y && x.y <= item.hi.y &&
          visit(this->Order[k]))
        {
          return true;
        }
      }
      return false;
    }
    return this->findContaining(node.left, x, visit) || this->findContaining(node.right, x, visit);
  }

  template <typename Visit>
  void forOverlappingSlots(int index, Vec2 lo, Vec2 hi, const Visit& visit) const
  {
    const Node& node = this->Nodes[index];
    if (!overlaps(node, lo, hi))
    {
      return;
    }
    if (node.left < 0)
    {
      for (int k = node.begin; k < node.end; ++k)
      {
        const Item& item = this->Items[k];
        if (item.lo.x <= hi.x && lo.x <= item.hi.x && item.lo.y <= hi.y && lo.y <= item.hi.y)
        {
          visit(k);
        }
      }
      return;
    }
    this->forOverlappingSlots(node.left, lo, hi, visit);
    this->forOverlappingSlots(node.right, lo, hi, visit);
  }

  template <typename Consider, typename MayMeet>
  void maximize(int index, Vec2 lo, Vec2 hi, double& best, const Consider& consider,
    const MayMeet& mayMeet) const
  {
    const Node& node = this->Nodes[index];
    if (node.maximum <= best || !overlaps(node, lo, hi) || !mayMeet(node.lo, node.hi))
    {
      return;
    }
    if (node.left < 0)
    {
      for (int k = node.begin; k < node.end; ++k)
      {
        const Item& item = this->Items[k];
        if (item.value > best && item.lo.x <= hi.x && lo.x <= item.hi.x && item.lo.y <= hi.y &&
          lo.y <= item.hi.y)
        {
          consider(k, best);
        }
      }
      return;
    }
    // The subtree with the larger maximum first: it raises best sooner, pruning more.
    int first = node.left, second = node.right;
    if (this->Nodes[second].maximum > this->Nodes[first].maximum)
    {
      std::swap(first, second);
    }
    this->maximize(first, lo, hi, best, consider, mayMeet);
    this->maximize(second, lo, hi, best, consider, mayMeet);
  }

  // Distance from x to the box, lowered by more than the rounding of the coordinates involved
  // (a point computed on an item may stick out of its box by that much): the boxes prune only
  // what is surely farther.
  static double boxDistance(const Node& node, Vec2 x)
  {
    const double dx = std::max({ node.lo.x - x.x, 0.0, x.x - node.hi.x });
    const double dy = std::max({ node.lo.y - x.y, 0.0, x.y - node.hi.y });
    const double magnitude = std::abs(x.x) + std::abs(x.y) + std::abs(node.lo.x) +
      std::abs(node.lo.y) + std::abs(node.hi.x) + std::abs(node.hi.y);
    return (1.0 - 1e-12) * std::sqrt(dx * dx + dy * dy) - 1e-14 * magnitude;
  }

  template <typename Distance>
  void nearest(int index, Vec2 x, const Distance& distance, int& best, double& bestDistance) const
  {
    const Node& node = this->Nodes[index];
    if (node.left < 0)
    {
      for (int k = node.begin; k < node.end; ++k)
      {
        const int id = this->Order[k];
        const double d = distance(id);
        if (d < bestDistance || (d == bestDistance && id < best))
        {
          best = id;
          bestDistance = d;
        }
      }
      return;
    }
    // The nearer subtree first: it lowers bestDistance sooner, pruning more.
    int first = node.left, second = node.right;
    double firstDistance = boxDistance(this->Nodes[first], x);
    double secondDistance = boxDistance(this->Nodes[second], x);
    if (secondDistance < firstDistance)
    {
      std::swap(first, second);
      std::swap(firstDistance, secondDistance);
    }
    if (firstDistance <= bestDistance)
    {
      this->nearest(first, x, distance, best, bestDistance);
    }
    if (secondDistance <= bestDistance)
    {
      this->nearest(second, x, distance, best, bestDistance);
    }
  }

  std::vector<Item> Items; // in slot order: Items[k] is item Order[k]'s
  std::vector<int> Order;
  std::vector<Node> Nodes;
};

} // namespace otparam

#endif
