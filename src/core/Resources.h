#pragma once
// What the process may use and uses: the memory budget that size checks compare against, and the
// resident set size that run records and the soak benchmark report (bench/soak/run.py).
#include "core/Error.h"

#include <cstdint>
#include <string>

namespace bounce {

// Bytes this process can expect to allocate: the smallest of physical memory, the address-space and
// data-segment limits (RLIMIT_AS, RLIMIT_DATA) and the cgroup's memory.max when there is one.
uint64_t memoryBudgetBytes();
// What memoryBudgetBytes() is, in words ("physical memory", "address-space limit", ...).
std::string memoryBudgetSource();

// An error naming `what` when `bytes` exceed memoryBudgetBytes(), before anything is allocated.
Expected<void> checkMemoryBudget(uint64_t bytes, const std::string& what);

// Resident set size of this process in bytes (/proc/self/statm), 0 where unavailable.
uint64_t residentBytes();

// "1.5 GB" (decimal units).
std::string formatBytes(uint64_t bytes);

}  // namespace bounce
