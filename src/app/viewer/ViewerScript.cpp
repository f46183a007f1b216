#include "app/viewer/ViewerScript.h"

#include "core/FileIo.h"

#include <charconv>
#include <cmath>
#include <sstream>

namespace bounce {

namespace {

bool parseNumber(const std::string& s, float& out) {
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && end == s.data() + s.size() && std::isfinite(out);
}

}  // namespace

float ScriptAction::number(size_t i) const {
    float v = 0.0f;
    parseNumber(args.at(i), v);
    return v;
}

const std::vector<ScriptActionInfo>& scriptActions() {
    static const std::vector<ScriptActionInfo> actions{
        {"technique", 1, 1, "s", "NAME: side A's technique", false},
        {"set", 1, 1, "s", "NAME=VALUE: a setting of side A's technique", false},
        {"b-technique", 1, 1, "s", "NAME: side B renders this technique", false},
        {"b-set", 1, 1, "s", "NAME=VALUE: a setting of side B's technique", false},
        {"b-reference", 1, 1, "s", "FILE.exr: side B shows this stored image", false},
        {"ab", 1, 1, "s", "off|split|wipe: A alone, side by side, or a wipe at the divider", false},
        {"wipe", 1, 1, "n", "FRACTION: wipe divider position, 0..1 of the image width", false},
        {"heatmap", 1, 1, "s", "on|off: FLIP heat map over the image", false},
        {"component", 1, 1, "s", "full|direct|indirect", false},
        {"view", 1, 1, "s", "NAME: a debug view (see the panel's list), or 'image'", false},
        {"layer", 1, 1, "n", "N: the layer shown of a 2D-array debug view (radiosity hemicubes: 5 k + face, face 0 the top)", false},
        {"frame", 1, 1, "n", "N: scene frame (time N / frameRate)", false},
        {"play", 0, 0, "", "start the animation", false},
        {"pause", 0, 0, "", "stop the animation", false},
        {"step", 0, 1, "n", "[N]: advance N frames (default 1)", false},
        {"speed", 1, 1, "n", "X: animation frames per displayed frame", false},
        {"select", 1, 1, "s", "light:I, object:I or object (the first animated one): what the arrow keys and ctrl-drag move", false},
        {"move", 3, 3, "nnn", "DX DY DZ: move the selected light or object (metres)", false},
        {"orbit", 3, 3, "nnn", "YAW PITCH DISTANCE: orbit camera about its target (degrees, degrees, metres)", false},
        {"bookmark", 1, 1, "s", "NAME: bookmark the camera", false},
        {"goto", 1, 1, "s", "NAME: jump to a bookmark", false},
        {"key", 0, 0, "", "record a camera-path key at the current scene time", false},
        {"reference", 1, 1, "n", "SPP: start the background path-traced reference of this view (side B)", false},
        {"wait", 1, 1, "n", "N: show N frames", false},
        {"wait-reference", 0, 0, "", "show frames until the background reference is done", false},
        {"wait-file", 1, 2, "sn", "FILE [SECONDS]: show frames until FILE exists (default 60 s, then fail): the signal of a test driving real input events", false},
        {"save-path", 1, 1, "s", "FILE.json: the recorded camera path", true},
        {"save-bookmarks", 1, 1, "s", "FILE.json: the bookmarks", true},
        {"capture", 1, 1, "s", "FILE.exr|png: side A's image at its render size", true},
        {"capture-b", 1, 1, "s", "FILE.exr|png: side B's image", true},
        {"screenshot", 1, 1, "s", "FILE.png|exr: the view (PNG: as displayed; EXR: side A's radiance)", true},
        {"window-shot", 1, 1, "s", "FILE.png: the whole window, panel included", true},
        {"metrics", 1, 1, "s", "FILE.json: relMSE and FLIP of A against B now", true},
        {"state", 1, 1, "s", "FILE.json: frame, time, render size, scale, A/B mode, path keys (for tests)", true},
        {"quit", 0, 0, "", "close the viewer", false},
    };
    return actions;
}

const ScriptActionInfo* findScriptAction(const std::string& verb) {
    for (const ScriptActionInfo& a : scriptActions())
        if (verb == a.verb) return &a;
    return nullptr;
}

Expected<std::vector<ScriptAction>> parseViewerScript(const std::string& text, const std::string& source) {
    std::vector<ScriptAction> out;
    std::istringstream lines(text);
    std::string lineText;
    for (int line = 1; std::getline(lines, lineText); ++line) {
        std::istringstream words(lineText);
        ScriptAction a;
        a.line = line;
        if (!(words >> a.verb) || a.verb[0] == '#') continue;
        for (std::string w; words >> w;) a.args.push_back(w);
        const ScriptActionInfo* info = findScriptAction(a.verb);
        if (!info) {
            std::string known;
            for (const ScriptActionInfo& k : scriptActions()) known += (known.empty() ? "" : ", ") + std::string(k.verb);
            return makeError("{}:{}: unknown action '{}' (known: {})", source, line, a.verb, known);
        }
        const int n = static_cast<int>(a.args.size());
        if (n < info->minArgs || n > info->maxArgs)
            return makeError("{}:{}: '{}' takes {} argument(s): {}", source, line, a.verb,
                             info->minArgs == info->maxArgs ? std::to_string(info->minArgs)
                                                            : fmt::format("{} to {}", info->minArgs, info->maxArgs),
                             info->doc);
        for (int i = 0; i < n; ++i) {
            float v;
            if (info->numbers[i] == 'n' && !parseNumber(a.args[static_cast<size_t>(i)], v))
                return makeError("{}:{}: '{}': argument {} '{}' is not a number", source, line, a.verb, i + 1,
                                 a.args[static_cast<size_t>(i)]);
        }
        out.push_back(std::move(a));
    }
    return out;
}

Expected<std::vector<ScriptAction>> readViewerScript(const std::string& path) {
    BOUNCE_TRY(std::string text, readTextFile(path));
    return parseViewerScript(text, path);
}

}  // namespace bounce
