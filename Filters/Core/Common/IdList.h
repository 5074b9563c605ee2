// Lists of offending ids in error messages (shared by the core's input checks).
#ifndef OTPARAM_COMMON_IDLIST_H
#define OTPARAM_COMMON_IDLIST_H

#include <algorithm>
#include <sstream>
#include <string>

namespace otparam
{

// "3, 17, 42" or "3, 17, ... (25 in all)": messages stay readable on meshes with thousands of
// problems.
template <typename Ids>
std::string idList(const Ids& ids)
{
  std::ostringstream out;
  const size_t shown = std::min<size_t>(ids.size(), 8);
  for (size_t i = 0; i < shown; ++i)
  {
    out << (i ? ", " : "") << ids[i];
  }
  if (ids.size() > shown)
  {
    out << ", ... (" << ids.size() << " in all)";
  }
  return out.str();
}

} // namespace otparam

#endif
