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

// Gives the heap's free pages back to the system (glibc: malloc_trim; elsewhere nothing), so that
// large allocations that follow do not add to freed memory the allocator still holds (the OT
// solver's Newton iterations, DampedNewton.cxx).
void returnFreedMemory();

} // namespace otparam

#endif
