#pragma once
// `bounce view --script FILE`: a list of viewer actions, one per line, run one after another while
// the window is open, so tests (and docs/viewer.md's screenshots) drive the same code paths as the
// mouse and keys. Blank lines and lines starting with '#' are ignored. The whole file is checked
// (action names, argument counts and numbers) before the window opens; an action that fails while
// running (an unknown technique, an unwritable file) ends the viewer with "FILE:LINE: message".
// docs/viewer.md lists the actions.
#include "core/Error.h"

#include <string>
#include <vector>

namespace bounce {

struct ScriptAction {
    int line = 0;
    std::string verb;
    std::vector<std::string> args;

    float number(size_t i) const;  // args[i] (validated as a finite number when parsed)
};

struct ScriptActionInfo {
    const char* verb;
    int minArgs, maxArgs;
    const char* numbers;  // one char per argument: 'n' number, 's' text
    const char* doc;
    bool output;  // runs after the frame was rendered and shown (captures, screenshots, metrics)
};
const std::vector<ScriptActionInfo>& scriptActions();
const ScriptActionInfo* findScriptAction(const std::string& verb);

Expected<std::vector<ScriptAction>> parseViewerScript(const std::string& text, const std::string& source);
Expected<std::vector<ScriptAction>> readViewerScript(const std::string& path);

}  // namespace bounce
