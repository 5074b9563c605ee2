#include "Common/GraphSeparator.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>

namespace otparam
{

namespace
{
// Breadth-first levels from `root` (-1: not reached); returns the deepest level. `order` gets
// the reached vertices in visiting order.
int levelsFrom(const Adjacency& graph, int root, std::vector<int>& level, std::vector<int>& order)
{
  std::fill(level.begin(), level.end(), -1);
  order.clear();
  order.push_back(root);
  level[root] = 0;
  for (size_t head = 0; head < order.size(); ++head)
  {
    const int v = order[head];
    for (int e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e)
    {
      const int w = graph.targets[e];
      if (level[w] < 0)
      {
        level[w] = level[v] + 1;
        order.push_back(w);
      }
    }
  }
  return level[order.back()];
}

int degree(const Adjacency& graph, int v)
{
  return graph.offsets[v + 1] - graph.offsets[v];
}
} // namespace

double separateByLevels(const Adjacency& graph,
  const std::function<double(std::int64_t, std::int64_t, std::int64_t)>& cost,
  std::vector<SeparatorPart>& part)
{
  part.clear();
  const int n = graph.size();
  constexpr double None = std::numeric_limits<double>::infinity();
  if (n < 3)
  {
    return None;
  }
  // A pseudo-peripheral root: restart from the deepest level's vertex of least degree while
  // that makes the structure deeper (a few searches).
  std::vector<int> level(n), order, bestLevel;
  int depth = levelsFrom(graph, 0, level, order);
  bestLevel = level;
  for (int round = 0; round < 8; ++round)
  {
    int candidate = order.back();
    for (auto it = order.rbegin(); it != order.rend() && level[*it] == depth; ++it)
    {
      candidate = degree(graph, *it) < degree(graph, candidate) ? *it : candidate;
    }
    const int deeper = levelsFrom(graph, candidate, level, order);
    if (deeper <= depth)
    {
      break;
    }
    depth = deeper;
    bestLevel = level;
  }
  std::vector<std::int64_t> count(depth + 1, 0);
  std::int64_t reached = 0;
  for (int l : bestLevel)
  {
    if (l >= 0)
    {
      ++count[l];
      ++reached;
    }
  }
  const std::int64_t unreached = n - reached;
  // Each level's split: the sides before and after it, the unreached vertices with the smaller.
  auto sides = [&](std::int64_t before, int l)
  {
    const std::int64_t after = reached - before - count[l];
    return before <= after ? std::pair{ before + unreached, after }
                           : std::pair{ before, after + unreached };
  };
  int chosen = -1;
  double chosenCost = None;
  std::int64_t below = 0;
  for (int l = 0; l <= depth; ++l)
  {
    const auto [first, second] = sides(below, l);
    const double c = cost(first, second, count[l]);
    if (8 * std::min(first, second) >= n && c < chosenCost)
    {
      chosen = l;
      chosenCost = c;
    }
    below += count[l];
  }
  if (chosen < 0)
  {
    return None;
  }
  std::int64_t before = 0;
  for (int l = 0; l < chosen; ++l)
  {
    before += count[l];
  }
  const std::int64_t after = reached - before - count[chosen];
  const SeparatorPart otherComponents =
    before <= after ? SeparatorPart::First : SeparatorPart::Second;
  part.resize(n);
  for (int v = 0; v < n; ++v)
  {
    const int l = bestLevel[v];
    part[v] = l < 0 ? otherComponents
      : l < chosen  ? SeparatorPart::First
      : l > chosen  ? SeparatorPart::Second
                    : SeparatorPart::Separator;
  }
  return chosenCost;
}

} // namespace otparam
