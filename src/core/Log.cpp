#include "core/Log.h"

#include <spdlog/sinks/stdout_color_sinks.h>

namespace bounce {
void setLogLevel(const std::string& level) {
    static bool configured = false;
    if (!configured) {
        auto logger = spdlog::stderr_color_mt("bounce");
        logger->set_pattern("%^[%l]%$ %v");
        spdlog::set_default_logger(logger);
        configured = true;
    }
    auto parsed = spdlog::level::from_str(level);
    if (parsed == spdlog::level::off && level != "off") parsed = spdlog::level::info;
    spdlog::set_level(parsed);
}
}  // namespace bounce
