// `bounce list`: techniques with their settings (name, type, default, range, doc), the shared
// renderer settings, and the built-in scenes with their parameters.
#include "app/Cli.h"
#include "app/viewer/ViewerSettings.h"
#include "render/RenderSettings.h"
#include "scene/SceneLoader.h"
#include "techniques/Registry.h"

#include <fmt/format.h>

#include <cstdlib>
#include <iostream>

namespace bounce {

namespace {

struct ListOptions {
    bool techniques = false, scenes = false, names = false;
};

void printSettings(Configurable& target, const std::string& prefix) {
    for (const SettingDescription& d : describeSettings(target))
        std::cout << fmt::format("    {}{:<18} {:<6} default {:<8} [{}]  {}{}\n", prefix, d.name, d.type, d.defaultValue,
                                 d.range, d.doc,
                                 d.profileDefaults.empty() ? "" : " (default per device profile: " + d.profileDefaults + ")");
}

// The device profile decides a few defaults (core/DeviceProfile.h); `bounce list` makes no context, so
// it names where the profile comes from and lists both values of such settings.
void printProfileLine() {
    const char* forced = std::getenv("BOUNCE_PROFILE");
    if (forced && *forced) {
        auto p = parseProfile(forced, "BOUNCE_PROFILE");
        std::cout << (p.ok() ? fmt::format("device profile: {} (BOUNCE_PROFILE)\n", profileName(*p))
                             : fmt::format("device profile: {}\n", p.error().message));
    } else {
        std::cout << "device profile: llvmpipe or gpu, from the GL renderer of the run's context (`bounce info` "
                     "shows it; BOUNCE_PROFILE=llvmpipe|gpu overrides); defaults shown are llvmpipe's\n";
    }
}

int runList(const ListOptions& o) {
    const bool all = !o.techniques && !o.scenes;
    if (o.techniques || all) {
        if (o.names) {
            for (const TechniqueInfo& t : registeredTechniques()) std::cout << t.name << "\n";
        } else {
            printProfileLine();
            std::cout << "techniques (bounce render --technique NAME --set NAME=VALUE):\n";
            for (const TechniqueInfo& t : registeredTechniques()) {
                std::cout << fmt::format("  {:<16} {} [{}]\n", t.name, t.summary, t.reference);
                std::cout << fmt::format("    reference scope: --bounces {}{}{}, compared with its {} output\n",
                                         t.scope.bounces < 0 ? "unbounded" : std::to_string(t.scope.bounces),
                                         t.scope.indirectOnly ? " --indirect-only" : "",
                                         t.scope.diffuseOnly ? " --diffuse-only" : "", componentName(t.scope.component));
                auto technique = t.create();
                printSettings(*technique, "");
            }
            std::cout << "renderer settings shared by every technique (--set renderer.NAME=VALUE):\n";
            render::RenderSettings r;
            printSettings(r, "renderer.");
            std::cout << "viewer settings (bounce view --set viewer.NAME=VALUE):\n";
            ViewerSettings v;
            printSettings(v, "viewer.");
        }
    }
    if (o.scenes || all) {
        if (o.names) {
            for (const BuiltinSceneInfo& s : builtinScenes()) std::cout << s.name << "\n";
        } else {
            std::cout << "built-in scenes (bounce render --scene NAME --scene-param NAME=VALUE):\n";
            for (const BuiltinSceneInfo& s : builtinScenes()) {
                std::cout << fmt::format("  {:<20} {}\n", s.name, s.description);
                for (const auto& [k, v] : s.params) std::cout << fmt::format("    {:<16} {}\n", k, v);
            }
        }
    }
    return 0;
}

}  // namespace

void registerListCommand(CLI::App& root, CommandAction& action) {
    auto o = std::make_shared<ListOptions>();
    CLI::App* c = root.add_subcommand("list", "list techniques with their settings, and built-in scenes");
    c->add_flag("--techniques", o->techniques, "only techniques");
    c->add_flag("--scenes", o->scenes, "only built-in scenes");
    c->add_flag("--names", o->names, "names only, one per line");
    c->callback([&action, o] { action = [o] { return runList(*o); }; });
}

}  // namespace bounce
