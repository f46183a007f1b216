// `bounce info`: the GL implementation a headless context gets, and the limits techniques rely on.
#include "app/Cli.h"
#include "gpu/Context.h"

#include <iostream>

namespace bounce {

void registerInfoCommand(CLI::App& root, CommandAction& action) {
    CLI::App* c = root.add_subcommand("info", "print GL vendor, renderer, version and limits (headless context)");
    c->callback([&action] {
        action = [] {
            auto context = gl::Context::createHeadless();
            if (!context.ok()) return failCommand("info", context.error().message);
            std::cout << gl::formatInfo((*context)->info());
            return 0;
        };
    });
}

}  // namespace bounce
