#include "core/Check.h"

#include <spdlog/spdlog.h>

#include <cstdlib>

namespace bounce::detail {
void checkFailed(const char* file, int line, const char* expr, const std::string& message) {
    spdlog::critical("{}:{}: check failed: {}: {}", file, line, expr, message);
    spdlog::shutdown();
    std::abort();
}
}  // namespace bounce::detail
