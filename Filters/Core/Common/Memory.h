// Memory the machine can still give, and the check that turns a run that would not fit into a
// message instead of swapping the machine to a halt (a surface of 1e7 triangles needs ~13 GiB).
#ifndef OTPARAM_COMMON_MEMORY_H
#define OTPARAM_COMMON_MEMORY_H

#include <cstdint>
#include <string>

namespace otparam
{

// Bytes the system can give without swapping (Linux: MemAvailable of /proc/meminfo; else the
// free physical pages), or -1 when unknown.
std::int64_t availableMemoryBytes();

// "" when `needed` bytes fit in `limit` (limit 0: availableMemoryBytes(); unknown: fits), else
// a sentence naming what needs them (`what`, e.g. "mapping a surface of 5000000 vertices"),
// both amounts, and what to do.
std::string checkMemory(const std::string& what, std::int64_t needed, std::int64_t limit = 0);

} // namespace otparam

#endif
