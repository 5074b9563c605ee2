#include "Common/Memory.h"

#include <fstream>
#include <iomanip>
#include <sstream>
#include <unistd.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace otparam
{

std::int64_t availableMemoryBytes()
{
  // MemAvailable counts the page cache the kernel can drop; free pages alone undercount it.
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::int64_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
  {
    if (key == "MemAvailable:")
    {
      return kib * 1024;
    }
  }
  const long pages = sysconf(_SC_AVPHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
  return pages > 0 && pageSize > 0 ? static_cast<std::int64_t>(pages) * pageSize : -1;
}

std::string checkMemory(const std::string& what, std::int64_t needed, std::int64_t limit)
{
  if (limit <= 0)
  {
    limit = availableMemoryBytes();
  }
  if (limit < 0 || needed <= limit)
  {
    return {};
  }
  constexpr double GiB = 1024.0 * 1024.0 * 1024.0;
  std::ostringstream msg;
  msg << std::fixed << std::setprecision(1) << what << " needs about " << needed / GiB
      << " GiB of memory, but " << limit / GiB
      << " GiB are available: free memory, use a machine with more, or decimate the input "
         "(e.g. with vtkQuadricDecimation).";
  return msg.str();
}

void returnFreedMemory()
{
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

} // namespace otparam
