#pragma once
// Logging goes through spdlog; this header only fixes the project's conventions (stderr, one line).
#include <spdlog/spdlog.h>

namespace bounce {
// Sets the global level from a name (trace, debug, info, warn, error, off). Unknown names keep "info".
void setLogLevel(const std::string& level);
}
