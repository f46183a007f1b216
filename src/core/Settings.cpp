#include "core/Settings.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <set>
#include <utility>

namespace bounce {

namespace {

std::string formatFloat(float v) { return fmt::format("{:g}", v); }

class Describer final : public SettingsVisitor {
public:
    std::vector<SettingDescription> out;
    std::string pending;  // the per-profile defaults of the next field
    void profileDefaults(std::string_view, int&, const PerProfile<int>& d) override {
        pending = fmt::format("llvmpipe {}, gpu {}", d.llvmpipe, d.gpu);
    }
    void profileDefaults(std::string_view, float&, const PerProfile<float>& d) override {
        pending = fmt::format("llvmpipe {}, gpu {}", formatFloat(d.llvmpipe), formatFloat(d.gpu));
    }
    void profileDefaults(std::string_view, bool&, const PerProfile<bool>& d) override {
        pending = fmt::format("llvmpipe {}, gpu {}", d.llvmpipe, d.gpu);
    }
    void profileDefaults(std::string_view, std::string&, const PerProfile<std::string_view>& d) override {
        pending = fmt::format("llvmpipe {}, gpu {}", d.llvmpipe, d.gpu);
    }
    void push(SettingDescription d) {
        d.profileDefaults = std::exchange(pending, {});
        out.push_back(std::move(d));
    }
    void field(std::string_view n, bool& v, std::string_view doc) override {
        push({std::string(n), "bool", v ? "true" : "false", std::string(doc), "true|false"});
    }
    void field(std::string_view n, int& v, std::string_view doc, int lo, int hi) override {
        push({std::string(n), "int", std::to_string(v), std::string(doc), fmt::format("{}..{}", lo, hi)});
    }
    void field(std::string_view n, float& v, std::string_view doc, float lo, float hi) override {
        push({std::string(n), "float", formatFloat(v), std::string(doc),
                       fmt::format("{}..{}", formatFloat(lo), formatFloat(hi))});
    }
    void field(std::string_view n, std::string& v, std::string_view doc, std::span<const std::string_view> c) override {
        push({std::string(n), "choice", v, std::string(doc), fmt::format("{}", fmt::join(c, "|"))});
    }
};

class Applier final : public SettingsVisitor {
public:
    Applier(const std::map<std::string, std::string>& values, std::string_view context)
        : m_values(values), m_context(context) {}
    std::set<std::string> used;
    std::vector<std::string> known;
    std::string error;

    void field(std::string_view n, bool& v, std::string_view) override {
        const std::string* text = find(n);
        if (!text) return;
        if (*text == "true" || *text == "1" || *text == "on" || *text == "yes") v = true;
        else if (*text == "false" || *text == "0" || *text == "off" || *text == "no") v = false;
        else fail(n, *text, "expected true or false");
    }
    void field(std::string_view n, int& v, std::string_view, int lo, int hi) override {
        const std::string* text = find(n);
        if (!text) return;
        int parsed = 0;
        auto [end, ec] = std::from_chars(text->data(), text->data() + text->size(), parsed);
        if (ec != std::errc() || end != text->data() + text->size()) return fail(n, *text, "expected an integer");
        if (parsed < lo || parsed > hi) return fail(n, *text, fmt::format("out of range {}..{}", lo, hi));
        v = parsed;
    }
    void field(std::string_view n, float& v, std::string_view, float lo, float hi) override {
        const std::string* text = find(n);
        if (!text) return;
        char* end = nullptr;
        const float parsed = std::strtof(text->c_str(), &end);
        if (text->empty() || end != text->c_str() + text->size() || !std::isfinite(parsed))
            return fail(n, *text, "expected a finite number");
        if (parsed < lo || parsed > hi)
            return fail(n, *text, fmt::format("out of range {}..{}", formatFloat(lo), formatFloat(hi)));
        v = parsed;
    }
    void field(std::string_view n, std::string& v, std::string_view, std::span<const std::string_view> c) override {
        const std::string* text = find(n);
        if (!text) return;
        for (auto choice : c)
            if (choice == *text) {
                v = *text;
                return;
            }
        fail(n, *text, fmt::format("expected one of {}", fmt::join(c, ", ")));
    }

private:
    const std::string* find(std::string_view n) {
        known.emplace_back(n);
        auto it = m_values.find(std::string(n));
        if (it == m_values.end()) return nullptr;
        used.insert(it->first);
        return &it->second;
    }
    void fail(std::string_view n, const std::string& text, const std::string& why) {
        if (error.empty()) error = fmt::format("{}: setting '{}' = '{}': {}", m_context, n, text, why);
    }
    const std::map<std::string, std::string>& m_values;
    std::string_view m_context;
};

class ProfileApplier final : public SettingsVisitor {
public:
    explicit ProfileApplier(DeviceProfile p) : m_profile(p) {}
    void field(std::string_view, bool&, std::string_view) override {}
    void field(std::string_view, int&, std::string_view, int, int) override {}
    void field(std::string_view, float&, std::string_view, float, float) override {}
    void field(std::string_view, std::string&, std::string_view, std::span<const std::string_view>) override {}

protected:
    void profileDefaults(std::string_view, int& v, const PerProfile<int>& d) override { v = d[m_profile]; }
    void profileDefaults(std::string_view, float& v, const PerProfile<float>& d) override { v = d[m_profile]; }
    void profileDefaults(std::string_view, bool& v, const PerProfile<bool>& d) override { v = d[m_profile]; }
    void profileDefaults(std::string_view, std::string& v, const PerProfile<std::string_view>& d) override {
        v = std::string(d[m_profile]);
    }

private:
    DeviceProfile m_profile;
};

class JsonWriter final : public SettingsVisitor {
public:
    nlohmann::json out = nlohmann::json::object();
    void field(std::string_view n, bool& v, std::string_view) override { out[std::string(n)] = v; }
    void field(std::string_view n, int& v, std::string_view, int, int) override { out[std::string(n)] = v; }
    void field(std::string_view n, float& v, std::string_view, float, float) override { out[std::string(n)] = v; }
    void field(std::string_view n, std::string& v, std::string_view, std::span<const std::string_view>) override {
        out[std::string(n)] = v;
    }
};

}  // namespace

std::vector<SettingDescription> describeSettings(Configurable& target) {
    Describer d;
    target.visitSettings(d);
    return d.out;
}

Expected<void> applySettings(Configurable& target, const std::map<std::string, std::string>& values,
                             std::string_view context) {
    Applier a(values, context);
    target.visitSettings(a);
    if (!a.error.empty()) return Error{a.error};
    for (const auto& [name, value] : values)
        if (!a.used.count(name))
            return makeError("{}: unknown setting '{}' (known: {})", context, name,
                             a.known.empty() ? std::string("none") : fmt::format("{}", fmt::join(a.known, ", ")));
    return {};
}

void applyProfileDefaults(Configurable& target, DeviceProfile profile) {
    ProfileApplier a(profile);
    target.visitSettings(a);
}

nlohmann::json settingsToJson(Configurable& target) {
    JsonWriter w;
    target.visitSettings(w);
    return w.out;
}

Expected<std::pair<std::string, std::string>> parseAssignment(std::string_view text) {
    const size_t eq = text.find('=');
    if (eq == std::string_view::npos || eq == 0)
        return makeError("'{}' is not of the form name=value", text);
    return std::pair<std::string, std::string>{std::string(text.substr(0, eq)), std::string(text.substr(eq + 1))};
}

}  // namespace bounce
