#pragma once
// Settings declared once. A settings struct lists its fields in visit(SettingsVisitor&) with name,
// doc and range; the same list drives parsing (--set name=value), `bounce list`, the run record and
// the viewer UI. An unknown name is an error that lists the known ones.
// A setting whose default differs between device profiles (core/DeviceProfile.h: values chosen only to
// keep llvmpipe runs short) gives both in the same call, field(..., PerProfile{llvmpipe, gpu}); the
// member's initial value must be the llvmpipe one, and applyProfileDefaults() sets the other.
#include "core/DeviceProfile.h"
#include "core/Error.h"

#include <nlohmann/json_fwd.hpp>

#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace bounce {

class SettingsVisitor {
public:
    virtual ~SettingsVisitor() = default;
    virtual void field(std::string_view name, bool& value, std::string_view doc) = 0;
    virtual void field(std::string_view name, int& value, std::string_view doc, int min, int max) = 0;
    virtual void field(std::string_view name, float& value, std::string_view doc, float min, float max) = 0;
    // A choice among named options (an enum kept as its name).
    virtual void field(std::string_view name, std::string& value, std::string_view doc,
                       std::span<const std::string_view> choices) = 0;

    // The same fields with a default per device profile, declared once: the visitor first sees the
    // defaults (profileDefaults), then the field as above.
    void field(std::string_view name, int& value, std::string_view doc, int min, int max, const PerProfile<int>& defaults) {
        profileDefaults(name, value, defaults);
        field(name, value, doc, min, max);
    }
    void field(std::string_view name, float& value, std::string_view doc, float min, float max,
               const PerProfile<float>& defaults) {
        profileDefaults(name, value, defaults);
        field(name, value, doc, min, max);
    }
    void field(std::string_view name, bool& value, std::string_view doc, const PerProfile<bool>& defaults) {
        profileDefaults(name, value, defaults);
        field(name, value, doc);
    }
    void field(std::string_view name, std::string& value, std::string_view doc, std::span<const std::string_view> choices,
               const PerProfile<std::string_view>& defaults) {
        profileDefaults(name, value, defaults);
        field(name, value, doc, choices);
    }

protected:
    // Called before the field of a setting with per-profile defaults; most visitors ignore it.
    virtual void profileDefaults(std::string_view, int&, const PerProfile<int>&) {}
    virtual void profileDefaults(std::string_view, float&, const PerProfile<float>&) {}
    virtual void profileDefaults(std::string_view, bool&, const PerProfile<bool>&) {}
    virtual void profileDefaults(std::string_view, std::string&, const PerProfile<std::string_view>&) {}
};

// Anything with visit(SettingsVisitor&).
class Configurable {
public:
    virtual ~Configurable() = default;
    virtual void visitSettings(SettingsVisitor& visitor) = 0;
};

struct SettingDescription {
    std::string name, type, defaultValue, doc, range;
    std::string profileDefaults;  // "llvmpipe 32768, gpu 1024" for a per-profile default, else empty
};

// The declared settings of `target` with their current values as defaults.
std::vector<SettingDescription> describeSettings(Configurable& target);

// Applies name=value pairs. `context` names the owner in messages ("technique 'rsm'").
// Errors: unknown name (lists known names), unparsable value, value out of range.
Expected<void> applySettings(Configurable& target, const std::map<std::string, std::string>& values,
                             std::string_view context);

// Sets every setting that has per-profile defaults to its default for `profile` (others untouched).
// Call it on a fresh object before applying a scene's and the command line's values.
void applyProfileDefaults(Configurable& target, DeviceProfile profile);

// Current values as a JSON object (for run records).
nlohmann::json settingsToJson(Configurable& target);

// Splits "name=value" (for --set); errors name the offending text.
Expected<std::pair<std::string, std::string>> parseAssignment(std::string_view text);

}  // namespace bounce
