#include "app/Cli.h"

#include "app/Options.h"
#include "app/ProcessContext.h"
#include "core/Log.h"
#include "scene/SceneLoader.h"

#include <iostream>
#include <new>

namespace bounce {

std::string oneLine(const std::string& message) {
    std::string line;
    for (char c : message) {
        if (c == '\r') continue;
        if (c == '\n') line += " | ";
        else line += c;
    }
    while (line.size() >= 3 && line.compare(line.size() - 3, 3, " | ") == 0) line.resize(line.size() - 3);
    return line;
}

int failCommand(const std::string& command, const std::string& message) {
    std::cerr << "bounce" << (command.empty() ? "" : " " + command) << ": " << oneLine(message) << "\n";
    return 1;
}

int runCli(int argc, char** argv) {
    CLI::App app{"bounce: real-time global illumination techniques side by side, measured against ground truth"};
    app.require_subcommand(1);
    std::string logLevel = "warn";
    app.add_option("--log-level", logLevel, "trace, debug, info, warn, error, off")->capture_default_str();
    std::string gpu;
    app.add_option("--gpu", gpu,
                   "EGL device index for headless GL (`bounce info` lists them; overrides BOUNCE_EGL_DEVICE; docs/gpu.md)");
    CommandAction action;
    registerListCommand(app, action);
    registerInfoCommand(app, action);
    registerRenderCommand(app, action);
    registerViewCommand(app, action);
    registerReferenceCommand(app, action);
    registerCompareCommand(app, action);
    registerPhotonMapCommand(app, action);
    registerSweepCommand(app, action);
    registerReportCommand(app, action);
    // CLI11 reports an unknown command as "a subcommand is required"; name it instead.
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--log-level" || arg == "--gpu") {
            ++i;
            continue;
        }
        if (arg.rfind("-", 0) == 0) break;
        bool known = false;
        std::string names;
        for (const CLI::App* sub : app.get_subcommands({})) {
            known |= sub->get_name() == arg;
            names += (names.empty() ? "" : ", ") + sub->get_name();
        }
        if (!known) return failCommand("", fmt::format("unknown command '{}' (known: {})", arg, names));
        break;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::string sub;
        for (const CLI::App* s : app.get_subcommands()) sub = s->get_name();
        std::string what = e.what();
        for (char& c : what)
            if (c == '\n') c = ' ';  // one line, as every bounce error
        std::cerr << "bounce" << (sub.empty() ? "" : " " + sub) << ": " << what << " (see --help)\n";
        return 1;  // bad input is exit status 1 whatever CLI11's own code for it (README)
    }
    setLogLevel(logLevel);
    const std::string command0 = app.get_subcommands().empty() ? "" : app.get_subcommands().front()->get_name();
    if (!gpu.empty()) {
        // Checked before any work: an index past the enumeration fails here, naming the device count.
        if (auto r = selectGpu(gpu, "--gpu"); !r.ok()) return failCommand(command0, r.error().message);
    }
    // Scene files' `settings` are checked against every technique's declared settings, whatever runs.
    setSceneSettingCheck(checkSceneSetting);
    if (!action) return failCommand("", "no command");
    const std::string command = app.get_subcommands().empty() ? "" : app.get_subcommands().front()->get_name();
    try {
        return action();
    } catch (const std::bad_alloc&) {
        // Sizes are checked against the memory before work starts; this is what those checks missed.
        return failCommand(command, "out of memory (std::bad_alloc): try a smaller --size or fewer samples");
    } catch (const std::exception& e) {
        // Library exceptions (assimp, OpenEXR, json) are input problems reported as one line.
        return failCommand(command, e.what());
    }
}

}  // namespace bounce
