#include "core/Resources.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>

namespace bounce {

namespace {

struct Budget {
    uint64_t bytes = std::numeric_limits<uint64_t>::max();
    std::string source = "unlimited";
    void consider(uint64_t value, const char* what) {
        if (value > 0 && value < bytes) {
            bytes = value;
            source = what;
        }
    }
};

Budget budget() {
    Budget b;
    const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGESIZE);
    if (pages > 0 && pageSize > 0) b.consider(static_cast<uint64_t>(pages) * static_cast<uint64_t>(pageSize), "physical memory");
    for (const auto& [resource, what] : {std::pair{RLIMIT_AS, "address-space limit (ulimit -v)"},
                                         std::pair{RLIMIT_DATA, "data-segment limit (ulimit -d)"}}) {
        rlimit limit{};
        if (::getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
            b.consider(static_cast<uint64_t>(limit.rlim_cur), what);
    }
    std::ifstream cgroup("/sys/fs/cgroup/memory.max");
    std::string text;
    if (cgroup >> text && text != "max") {
        try {
            b.consider(std::stoull(text), "cgroup memory.max");
        } catch (const std::exception&) {
        }
    }
    return b;
}

}  // namespace

uint64_t memoryBudgetBytes() { return budget().bytes; }
std::string memoryBudgetSource() { return budget().source; }

Expected<void> checkMemoryBudget(uint64_t bytes, const std::string& what) {
    const Budget b = budget();
    if (bytes > b.bytes)
        return makeError("{} need about {}, more than the {} this process may use ({})", what, formatBytes(bytes),
                         formatBytes(b.bytes), b.source);
    return {};
}

uint64_t residentBytes() {
    std::FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return 0;
    unsigned long long size = 0, resident = 0;
    const int n = std::fscanf(f, "%llu %llu", &size, &resident);
    std::fclose(f);
    if (n != 2) return 0;
    return static_cast<uint64_t>(resident) * static_cast<uint64_t>(::sysconf(_SC_PAGESIZE));
}

std::string formatBytes(uint64_t bytes) {
    const double b = static_cast<double>(bytes);
    if (b >= 1e9) return fmt::format("{:.1f} GB", b * 1e-9);
    if (b >= 1e6) return fmt::format("{:.1f} MB", b * 1e-6);
    if (b >= 1e3) return fmt::format("{:.1f} kB", b * 1e-3);
    return fmt::format("{} B", bytes);
}

}  // namespace bounce
