#pragma once
// Always-on invariant checks. A failed check is a bug in bounce, not bad input: it logs and aborts.
#include <fmt/format.h>

namespace bounce::detail {
[[noreturn]] void checkFailed(const char* file, int line, const char* expr, const std::string& message);
}

#define BOUNCE_CHECK(cond, ...)                                                               \
    do {                                                                                      \
        if (!(cond)) [[unlikely]]                                                             \
            ::bounce::detail::checkFailed(__FILE__, __LINE__, #cond, ::fmt::format(__VA_ARGS__)); \
    } while (0)
