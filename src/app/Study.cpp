#include "app/Study.h"

#include "app/Options.h"
#include "core/FileIo.h"
#include "render/RenderSettings.h"
#include "scene/JsonLocator.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bounce::study {

namespace fs = std::filesystem;
using nlohmann::json;

const char* jobKindName(JobKind kind) {
    switch (kind) {
        case JobKind::Reference: return "reference";
        case JobKind::Render: return "render";
        case JobKind::Compare: return "compare";
        case JobKind::Temporal: return "temporal";
    }
    return "?";
}

const char* animationName(TemporalSpec::Animation a) {
    switch (a) {
        case TemporalSpec::Animation::Play: return "play";
        case TemporalSpec::Animation::Hold: return "hold";
        case TemporalSpec::Animation::Step: return "step";
    }
    return "?";
}

const Job* Study::findJob(const std::string& id) const {
    for (const Job& j : jobs)
        if (j.id == id) return &j;
    return nullptr;
}

std::string scopeName(const ReferenceScope& s) {
    std::string name = s.bounces < 0 ? "all" : fmt::format("b{}", s.bounces);
    if (s.indirectOnly) name += "-indirect";
    if (s.diffuseOnly) name += "-diffuse";
    return name;
}

json scopeJson(const ReferenceScope& s) {
    return {{"bounces", s.bounces < 0 ? json("unbounded") : json(s.bounces)},
            {"indirectOnly", s.indirectOnly},
            {"diffuseOnly", s.diffuseOnly},
            {"component", std::string(componentName(s.component))}};
}

namespace {

// Folder-name-safe text: letters, digits, '.', '-', '+'; anything else becomes '-'. Long names keep
// their start and gain a hash of the whole, so two long settings lists never share a folder.
std::string safeName(const std::string& text) {
    std::string out;
    for (char c : text) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+' || c == '_') ? c : '-';
    constexpr size_t kMaxLength = 64;  // well under any file system's 255-byte name limit
    if (out.size() > kMaxLength) {
        uint32_t h = 2166136261u;  // FNV-1a
        for (char c : text) h = (h ^ static_cast<uint8_t>(c)) * 16777619u;
        out = fmt::format("{}-{:08x}", out.substr(0, kMaxLength - 9), h);
    }
    return out;
}

std::string knownList(const std::vector<std::string>& names) { return fmt::format("{}", fmt::join(names, ", ")); }

// Error reporting with the study file's line numbers: "study.json:12: techniques[1].grid: ...".
class Checker {
public:
    Checker(std::string file, std::string_view text) : m_file(std::move(file)), m_locator(text) {}

    Error error(const std::string& pointer, const std::string& message) const {
        return Error{fmt::format("{}:{}: {}: {}", m_file, m_locator.line(pointer), keyPath(pointer), message)};
    }
    Error errorAt(const std::string& pointer, const std::string& message) const {  // message already names the key
        return Error{fmt::format("{}:{}: {}", m_file, m_locator.line(pointer), message)};
    }

    Expected<void> keys(const json& object, const std::string& pointer, const std::vector<std::string>& known) const {
        if (!object.is_object()) return error(pointer, fmt::format("expected an object with keys {}", knownList(known)));
        for (const auto& [key, value] : object.items())
            if (std::find(known.begin(), known.end(), key) == known.end())
                return error(pointer + "/" + key, fmt::format("unknown key '{}' (known: {})", key, knownList(known)));
        return {};
    }

    Expected<int> integer(const json& v, const std::string& pointer, int lo, int hi) const {
        if (!v.is_number_integer() || v.get<int64_t>() < lo || v.get<int64_t>() > hi)
            return error(pointer, fmt::format("{} is not an integer in [{}, {}]", v.dump(), lo, hi));
        return static_cast<int>(v.get<int64_t>());
    }
    Expected<double> number(const json& v, const std::string& pointer, double lo, double hi) const {
        if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < lo || v.get<double>() > hi)
            return error(pointer, fmt::format("{} is not a number in [{}, {}]", v.dump(), lo, hi));
        return v.get<double>();
    }
    Expected<bool> boolean(const json& v, const std::string& pointer) const {
        if (!v.is_boolean()) return error(pointer, fmt::format("{} is not true or false", v.dump()));
        return v.get<bool>();
    }
    Expected<std::string> string(const json& v, const std::string& pointer) const {
        if (!v.is_string()) return error(pointer, fmt::format("{} is not a string", v.dump()));
        return v.get<std::string>();
    }
    // A setting or scene parameter value: string, number or boolean, as the --set text.
    Expected<std::string> scalar(const json& v, const std::string& pointer) const {
        if (v.is_string()) return v.get<std::string>();
        if (v.is_boolean()) return std::string(v.get<bool>() ? "true" : "false");
        if (v.is_number()) return v.dump();
        return error(pointer, fmt::format("{} is not a string, number or boolean", v.dump()));
    }

    static std::string keyPath(const std::string& pointer) {
        std::string out;
        size_t i = 1;
        while (i <= pointer.size() && !pointer.empty()) {
            const size_t next = pointer.find('/', i);
            const std::string part = pointer.substr(i, next == std::string::npos ? std::string::npos : next - i);
            if (!part.empty() && std::all_of(part.begin(), part.end(), ::isdigit)) out += "[" + part + "]";
            else out += (out.empty() ? "" : ".") + part;
            if (next == std::string::npos) break;
            i = next + 1;
        }
        return out.empty() ? "(top level)" : out;
    }

private:
    std::string m_file;
    JsonLocator m_locator;
};

std::string pointerKey(const std::string& key) {  // JSON pointer escaping
    std::string out;
    for (char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
    return out;
}

Expected<ReferenceScope> parseScope(const Checker& c, const json& v, const std::string& ptr, ReferenceScope scope) {
    BOUNCE_TRY_VOID(c.keys(v, ptr, {"bounces", "indirectOnly", "diffuseOnly", "component"}));
    if (v.contains("bounces")) {
        if (v["bounces"] == "unbounded") scope.bounces = -1;
        else {
            BOUNCE_TRY(scope.bounces, c.integer(v["bounces"], ptr + "/bounces", 0, 1024));
        }
    }
    if (v.contains("indirectOnly")) { BOUNCE_TRY(scope.indirectOnly, c.boolean(v["indirectOnly"], ptr + "/indirectOnly")); }
    if (v.contains("diffuseOnly")) { BOUNCE_TRY(scope.diffuseOnly, c.boolean(v["diffuseOnly"], ptr + "/diffuseOnly")); }
    if (v.contains("component")) {
        BOUNCE_TRY(const std::string name, c.string(v["component"], ptr + "/component"));
        auto component = parseComponent(name);
        if (!component) return c.error(ptr + "/component", component.error().message);
        scope.component = *component;
    }
    return scope;
}

// Splits settings into the shared renderer's and the technique's, as `--set` does.
struct SplitSettings {
    std::map<std::string, std::string> renderer, own;
};
Expected<SplitSettings> splitSettings(const std::map<std::string, std::string>& settings, const std::string& technique) {
    SplitSettings s;
    for (const auto& [key, value] : settings) {
        const size_t dot = key.find('.');
        if (dot == std::string::npos) s.own[key] = value;
        else if (key.substr(0, dot) == "renderer") s.renderer[key.substr(dot + 1)] = value;
        else if (key.substr(0, dot) == technique) s.own[key.substr(dot + 1)] = value;
        else return makeError("setting '{}': the prefix names another technique (this entry is '{}'; renderer settings start with 'renderer.')", key, technique);
    }
    return s;
}

// Checks a variant's settings on a fresh technique and renderer (no GL needed).
Expected<void> checkSettings(const TechniqueInfo& info, const std::map<std::string, std::string>& settings) {
    BOUNCE_TRY(const SplitSettings split, splitSettings(settings, info.name));
    render::RenderSettings renderer;
    BOUNCE_TRY_VOID(applySettings(renderer, split.renderer, "renderer"));
    auto technique = info.create();
    BOUNCE_TRY_VOID(applySettings(*technique, split.own, fmt::format("technique '{}'", info.name)));
    return {};
}

bool declaresSetting(const TechniqueInfo& info, const std::string& name) {
    auto technique = info.create();
    for (const SettingDescription& d : describeSettings(*technique))
        if (d.name == name) return true;
    return false;
}

std::string variantId(const std::map<std::string, std::string>& settings) {
    if (settings.empty()) return "default";
    std::string id;
    for (const auto& [k, v] : settings) id += (id.empty() ? "" : "_") + k + "-" + v;
    return safeName(id);
}

Expected<void> parseScenes(const Checker& c, const json& list, const fs::path& base, Study& study) {
    if (!list.is_array() || list.empty()) return c.error("/scenes", "expected a non-empty array of scene names or objects {name|file, params}");
    std::vector<std::string> builtins;
    for (const BuiltinSceneInfo& b : builtinScenes()) builtins.push_back(b.name);
    for (size_t i = 0; i < list.size(); ++i) {
        const std::string ptr = fmt::format("/scenes/{}", i);
        const json& v = list[i];
        SceneSpec spec;
        std::string stem;
        bool isFile = false;
        if (v.is_string()) {
            spec.source = v.get<std::string>();
        } else {
            BOUNCE_TRY_VOID(c.keys(v, ptr, {"name", "file", "params"}));
            if (v.contains("name") == v.contains("file"))
                return c.error(ptr, "give exactly one of 'name' (a built-in scene) or 'file' (a scene file)");
            if (v.contains("name")) { BOUNCE_TRY(spec.source, c.string(v["name"], ptr + "/name")); }
            else {
                BOUNCE_TRY(const std::string file, c.string(v["file"], ptr + "/file"));
                isFile = true;
                spec.source = fs::absolute(base / file).lexically_normal().string();
                if (!fs::exists(spec.source)) return c.error(ptr + "/file", fmt::format("{}: file not found", spec.source));
                stem = fs::path(file).stem().string();
            }
            if (v.contains("params")) {
                if (!v["params"].is_object()) return c.error(ptr + "/params", "expected an object of scene parameters");
                for (const auto& [k, pv] : v["params"].items()) {
                    BOUNCE_TRY(spec.params[k], c.scalar(pv, ptr + "/params/" + pointerKey(k)));
                }
            }
        }
        if (!isFile) {
            if (std::find(builtins.begin(), builtins.end(), spec.source) == builtins.end())
                return c.error(v.is_string() ? ptr : ptr + "/name",
                               fmt::format("unknown built-in scene '{}' (known: {}; a scene file goes in {{\"file\": ...}})",
                                           spec.source, knownList(builtins)));
            stem = spec.source;
        }
        // Loading checks the parameters (names and ranges) and the file; it is cheap next to any job.
        auto scene = loadScene(spec.source, spec.params);
        if (!scene) return c.error(ptr, scene.error().message);
        std::string id = stem;
        for (const auto& [k, pv] : spec.params) id += "_" + k + "-" + pv;
        spec.id = safeName(id);
        for (const SceneSpec& other : study.scenes)
            if (other.id == spec.id) return c.error(ptr, fmt::format("scene '{}' is listed twice", spec.id));
        study.scenes.push_back(std::move(spec));
    }
    return {};
}

// Expands one entry of "techniques" into variants (list x grid x seeds).
Expected<void> parseTechnique(const Checker& c, const json& v, const std::string& ptr, Study& study) {
    std::vector<std::string> names;
    for (const TechniqueInfo& t : registeredTechniques()) names.push_back(t.name);
    json entry = v.is_string() ? json{{"name", v}} : v;
    if (!v.is_string()) BOUNCE_TRY_VOID(c.keys(v, ptr, {"name", "settings", "grid", "list", "scope"}));
    if (!entry.contains("name")) return c.error(ptr, fmt::format("missing 'name' (a technique: {}, or \"*\" for every one)", knownList(names)));
    const std::string namePtr = v.is_string() ? ptr : ptr + "/name";
    BOUNCE_TRY(const std::string name, c.string(entry["name"], namePtr));
    std::vector<const TechniqueInfo*> infos;
    for (const TechniqueInfo& t : registeredTechniques())
        if (name == "*" || t.name == name) infos.push_back(&t);
    if (infos.empty()) return c.error(namePtr, fmt::format("unknown technique '{}' (known: {}, or \"*\" for every one)", name, knownList(names)));

    std::map<std::string, std::string> fixed;
    if (entry.contains("settings")) {
        if (!entry["settings"].is_object()) return c.error(ptr + "/settings", "expected an object of settings");
        for (const auto& [k, sv] : entry["settings"].items()) { BOUNCE_TRY(fixed[k], c.scalar(sv, ptr + "/settings/" + pointerKey(k))); }
    }
    std::vector<std::map<std::string, std::string>> points{{}};
    std::vector<std::string> pointPtrs{ptr};
    if (entry.contains("list")) {
        const json& list = entry["list"];
        if (!list.is_array() || list.empty()) return c.error(ptr + "/list", "expected a non-empty array of settings objects");
        points.clear();
        pointPtrs.clear();
        for (size_t i = 0; i < list.size(); ++i) {
            const std::string ip = fmt::format("{}/list/{}", ptr, i);
            if (!list[i].is_object()) return c.error(ip, "expected an object of settings");
            std::map<std::string, std::string> p;
            for (const auto& [k, sv] : list[i].items()) { BOUNCE_TRY(p[k], c.scalar(sv, ip + "/" + pointerKey(k))); }
            points.push_back(std::move(p));
            pointPtrs.push_back(ip);
        }
    }
    if (entry.contains("grid")) {
        const json& grid = entry["grid"];
        if (!grid.is_object() || grid.empty()) return c.error(ptr + "/grid", "expected an object of setting name -> array of values");
        for (const auto& [k, values] : grid.items()) {  // nlohmann objects iterate in key order: stable
            const std::string kp = ptr + "/grid/" + pointerKey(k);
            if (!values.is_array() || values.empty()) return c.error(kp, "expected a non-empty array of values");
            std::vector<std::map<std::string, std::string>> next;
            std::vector<std::string> nextPtrs;
            for (size_t p = 0; p < points.size(); ++p)
                for (size_t i = 0; i < values.size(); ++i) {
                    auto point = points[p];
                    if (point.count(k)) return c.error(kp, fmt::format("setting '{}' is in both 'list' and 'grid'", k));
                    BOUNCE_TRY(point[k], c.scalar(values[i], fmt::format("{}/{}", kp, i)));
                    next.push_back(std::move(point));
                    nextPtrs.push_back(fmt::format("{}/{}", kp, i));
                }
            points = std::move(next);
            pointPtrs = std::move(nextPtrs);
        }
    }
    for (const TechniqueInfo* info : infos) {
        ReferenceScope scope = info->scope;
        if (entry.contains("scope")) { BOUNCE_TRY(scope, parseScope(c, entry["scope"], ptr + "/scope", scope)); }
        for (size_t p = 0; p < points.size(); ++p) {
            std::map<std::string, std::string> settings = fixed;
            for (const auto& [k, val] : points[p]) {
                if (settings.count(k)) return c.error(pointPtrs[p], fmt::format("setting '{}' is in both 'settings' and 'list'/'grid'", k));
                settings[k] = val;
            }
            if (auto ok = checkSettings(*info, settings); !ok)
                return c.error(name == "*" ? ptr : pointPtrs[p], ok.error().message);
            std::vector<std::map<std::string, std::string>> seeded{settings};
            // A technique with a random seed gets one variant per study seed; deterministic ones get one.
            if (!study.seeds.empty() && !settings.count("seed") && declaresSetting(*info, "seed")) {
                seeded.clear();
                for (uint64_t s : study.seeds) {
                    auto withSeed = settings;
                    withSeed["seed"] = std::to_string(s);
                    if (auto ok = checkSettings(*info, withSeed); !ok) return c.error("/seeds", ok.error().message);
                    seeded.push_back(std::move(withSeed));
                }
            }
            for (auto& s : seeded) {
                Variant var{info->name, variantId(s), s, scope};
                const bool duplicate = std::any_of(study.variants.begin(), study.variants.end(), [&](const Variant& o) {
                    return o.technique == var.technique && o.id == var.id;
                });
                if (!duplicate) study.variants.push_back(std::move(var));  // "*" and a named entry may overlap
            }
        }
    }
    return {};
}

Expected<void> parseTemporal(const Checker& c, const json& v, Study& study) {
    const std::string ptr = "/temporal";
    BOUNCE_TRY_VOID(c.keys(v, ptr, {"scenes", "techniques", "frames", "startFrame", "eventFrame", "animation", "threshold"}));
    TemporalSpec& t = study.temporal;
    t.enabled = true;
    constexpr int kMaxFrames = 10000;
    if (v.contains("frames")) { BOUNCE_TRY(t.frames, c.integer(v["frames"], ptr + "/frames", 2, kMaxFrames)); }
    if (v.contains("startFrame")) { BOUNCE_TRY(t.startFrame, c.integer(v["startFrame"], ptr + "/startFrame", 0, 1 << 24)); }
    t.eventFrame = t.startFrame;
    if (v.contains("eventFrame")) {
        BOUNCE_TRY(t.eventFrame, c.integer(v["eventFrame"], ptr + "/eventFrame", t.startFrame, t.startFrame + t.frames - 2));
    }
    if (v.contains("animation")) {
        BOUNCE_TRY(const std::string name, c.string(v["animation"], ptr + "/animation"));
        if (name == "play") t.animation = TemporalSpec::Animation::Play;
        else if (name == "hold") t.animation = TemporalSpec::Animation::Hold;
        else if (name == "step") t.animation = TemporalSpec::Animation::Step;
        else return c.error(ptr + "/animation", fmt::format("unknown animation '{}' (known: play, hold, step)", name));
        // Without a frame before the event nothing moves at it: the run would be a still scene.
        if (t.animation != TemporalSpec::Animation::Play && t.eventFrame == t.startFrame)
            return c.error(v.contains("eventFrame") ? ptr + "/eventFrame" : ptr + "/animation",
                           fmt::format("animation '{}' needs an eventFrame after startFrame {} (the move happens at the event)",
                                       name, t.startFrame));
    }
    if (v.contains("threshold")) { BOUNCE_TRY(t.threshold, c.number(v["threshold"], ptr + "/threshold", 0.0, 1e6)); }
    std::vector<std::string> sceneIds;
    for (const SceneSpec& s : study.scenes) sceneIds.push_back(s.id);
    if (v.contains("scenes")) {
        if (!v["scenes"].is_array()) return c.error(ptr + "/scenes", "expected an array of the study's scene ids");
        for (size_t i = 0; i < v["scenes"].size(); ++i) {
            const std::string sp = fmt::format("{}/scenes/{}", ptr, i);
            BOUNCE_TRY(const std::string id, c.string(v["scenes"][i], sp));
            const auto it = std::find(sceneIds.begin(), sceneIds.end(), id);
            if (it == sceneIds.end()) return c.error(sp, fmt::format("'{}' is not a scene of this study (known: {})", id, knownList(sceneIds)));
            t.scenes.push_back(static_cast<size_t>(it - sceneIds.begin()));
        }
    } else {
        for (size_t i = 0; i < study.scenes.size(); ++i) t.scenes.push_back(i);
    }
    if (v.contains("techniques")) {
        std::vector<std::string> names;
        for (const Variant& var : study.variants)
            if (std::find(names.begin(), names.end(), var.technique) == names.end()) names.push_back(var.technique);
        if (!v["techniques"].is_array()) return c.error(ptr + "/techniques", "expected an array of the study's technique names");
        for (size_t i = 0; i < v["techniques"].size(); ++i) {
            const std::string tp = fmt::format("{}/techniques/{}", ptr, i);
            BOUNCE_TRY(const std::string name, c.string(v["techniques"][i], tp));
            if (std::find(names.begin(), names.end(), name) == names.end())
                return c.error(tp, fmt::format("'{}' is not a technique of this study (known: {})", name, knownList(names)));
            t.techniques.insert(name);
        }
    }
    return {};
}

json sceneSpecJson(const SceneSpec& s) { return {{"id", s.id}, {"source", s.source}, {"params", s.params}}; }

void expand(Study& study) {
    std::vector<Job> stage1, stage2;
    std::map<std::string, json> references;  // id -> spec
    const auto referenceJob = [&](size_t scene, const ReferenceScope& scope, uint32_t frame) {
        ReferenceScope key = scope;
        key.component = Component::Full;  // the path tracer's image does not depend on the technique's component
        const std::string id = fmt::format("reference/{}/{}/f{:04}", study.scenes[scene].id, scopeName(key), frame);
        if (!references.count(id)) {
            Job j;
            j.kind = JobKind::Reference;
            j.id = id;
            j.stage = 1;
            j.scene = scene;
            j.scope = key;
            j.frame = frame;
            json scopeSpec = scopeJson(key);
            scopeSpec.erase("component");
            j.spec = {{"kind", "reference"}, {"scene", sceneSpecJson(study.scenes[scene])}, {"scope", scopeSpec},
                      {"size", {study.size.x, study.size.y}}, {"frame", frame}, {"spp", study.reference.spp},
                      {"timeLimit", study.reference.timeLimit}, {"seed", study.reference.seed},
                      // Its outputs include the variance image of the noise floors: a reference made
                      // before them (no such key) is stale, and so are the compares that read it.
                      {"outputs", {"image", "variance"}}};
            references[id] = j.spec;
            stage1.push_back(std::move(j));
        }
        return id;
    };
    for (size_t s = 0; s < study.scenes.size(); ++s) {
        for (size_t v = 0; v < study.variants.size(); ++v) {
            const Variant& var = study.variants[v];
            const std::string tail = fmt::format("{}/{}/{}", study.scenes[s].id, var.technique, var.id);
            Job render;
            render.kind = JobKind::Render;
            render.id = "render/" + tail;
            render.scene = s;
            render.variant = v;
            render.scope = var.scope;
            render.frame = study.stillFrame();
            render.spec = {{"kind", "render"}, {"scene", sceneSpecJson(study.scenes[s])}, {"technique", var.technique},
                           {"settings", var.settings}, {"renderer", study.renderer},
                           {"size", {study.size.x, study.size.y}}, {"frames", study.frames},
                           {"startFrame", study.startFrame}};
            const std::string ref = referenceJob(s, var.scope, study.stillFrame());
            Job compare;
            compare.kind = JobKind::Compare;
            compare.id = "compare/" + tail;
            compare.stage = 2;
            compare.scene = s;
            compare.variant = v;
            compare.scope = var.scope;
            compare.inputs = {render.id, ref};
            // The inputs' specs, not just their ids: a new reference (seed, spp) makes the compare stale too.
            compare.spec = {{"kind", "compare"}, {"render", render.spec}, {"reference", references[ref]},
                            {"component", std::string(componentName(var.scope.component))}};
            stage1.push_back(std::move(render));
            stage2.push_back(std::move(compare));
        }
    }
    const TemporalSpec& t = study.temporal;
    if (t.enabled)
        for (size_t s : t.scenes)
            for (size_t v = 0; v < study.variants.size(); ++v) {
                const Variant& var = study.variants[v];
                if (!t.techniques.empty() && !t.techniques.count(var.technique)) continue;
                Job j;
                j.kind = JobKind::Temporal;
                j.id = fmt::format("temporal/{}/{}/{}", study.scenes[s].id, var.technique, var.id);
                j.stage = 2;
                j.scene = s;
                j.variant = v;
                j.scope = var.scope;
                // One reference per frame of the run, of the moment it shows (held frames share one).
                for (int f = t.startFrame; f < t.startFrame + t.frames; ++f)
                    j.inputs.push_back(referenceJob(s, var.scope, t.sceneFrame(f)));
                j.spec = {{"kind", "temporal"}, {"scene", sceneSpecJson(study.scenes[s])}, {"technique", var.technique},
                          {"settings", var.settings}, {"renderer", study.renderer}, {"size", {study.size.x, study.size.y}},
                          {"frames", t.frames}, {"startFrame", t.startFrame}, {"eventFrame", t.eventFrame},
                          {"animation", animationName(t.animation)}, {"threshold", t.threshold}, {"component", std::string(componentName(var.scope.component))},
                          {"references", json::array()}};
                for (const std::string& ref : j.inputs) j.spec["references"].push_back(references[ref]);
                stage2.push_back(std::move(j));
            }
    study.jobs = std::move(stage1);
    for (Job& j : stage2) study.jobs.push_back(std::move(j));
}

}  // namespace

Expected<Study> loadStudy(const fs::path& file, const std::string& outputOverride) {
    const std::string name = file.string();
    auto text = readTextFile(file);
    if (!text) return text.error();
    BOUNCE_TRY(const json doc, parseJsonDocument(*text, name));
    const Checker c(name, *text);
    BOUNCE_TRY_VOID(c.keys(doc, "", {"name", "output", "size", "frames", "startFrame", "seeds", "scenes", "techniques",
                                     "renderer", "reference", "temporal"}));
    Study study;
    study.file = fs::absolute(file).lexically_normal();
    const fs::path base = study.file.parent_path();
    study.name = file.stem().string();
    if (doc.contains("name")) { BOUNCE_TRY(study.name, c.string(doc["name"], "/name")); }
    std::string output = study.name + "-results";
    if (doc.contains("output")) { BOUNCE_TRY(output, c.string(doc["output"], "/output")); }
    // --out is relative to the working folder, the file's "output" to the study file's folder.
    study.output = outputOverride.empty() ? fs::absolute(base / output) : fs::absolute(outputOverride);
    study.output = study.output.lexically_normal();
    if (doc.contains("size")) {
        BOUNCE_TRY(const std::string size, c.string(doc["size"], "/size"));
        auto parsed = parseSize(size);
        if (!parsed) return c.error("/size", parsed.error().message);
        study.size = *parsed;
    }
    constexpr int kMaxFrames = 100000;
    if (doc.contains("frames")) { BOUNCE_TRY(study.frames, c.integer(doc["frames"], "/frames", 1, kMaxFrames)); }
    if (doc.contains("startFrame")) { BOUNCE_TRY(study.startFrame, c.integer(doc["startFrame"], "/startFrame", 0, 1 << 24)); }
    if (doc.contains("seeds")) {
        if (!doc["seeds"].is_array() || doc["seeds"].empty()) return c.error("/seeds", "expected a non-empty array of integers");
        for (size_t i = 0; i < doc["seeds"].size(); ++i) {
            BOUNCE_TRY(const int seed, c.integer(doc["seeds"][i], fmt::format("/seeds/{}", i), 0, std::numeric_limits<int>::max()));
            study.seeds.push_back(static_cast<uint64_t>(seed));
        }
    }
    if (doc.contains("renderer")) {
        if (!doc["renderer"].is_object()) return c.error("/renderer", "expected an object of renderer settings");
        for (const auto& [k, v] : doc["renderer"].items()) { BOUNCE_TRY(study.renderer[k], c.scalar(v, "/renderer/" + pointerKey(k))); }
        render::RenderSettings r;
        if (auto ok = applySettings(r, study.renderer, "renderer"); !ok) return c.error("/renderer", ok.error().message);
    }
    if (doc.contains("reference")) {
        const json& r = doc["reference"];
        BOUNCE_TRY_VOID(c.keys(r, "/reference", {"spp", "timeLimit", "seed", "threads"}));
        constexpr int kMaxSpp = 1 << 20;
        if (r.contains("spp")) { BOUNCE_TRY(study.reference.spp, c.integer(r["spp"], "/reference/spp", 1, kMaxSpp)); }
        if (r.contains("timeLimit")) { BOUNCE_TRY(study.reference.timeLimit, c.number(r["timeLimit"], "/reference/timeLimit", 0.0, 1e7)); }
        if (r.contains("seed")) { BOUNCE_TRY(study.reference.seed, c.integer(r["seed"], "/reference/seed", 0, std::numeric_limits<int>::max())); }
        if (r.contains("threads")) { BOUNCE_TRY(study.reference.threads, c.integer(r["threads"], "/reference/threads", 0, 4096)); }
    }
    if (!doc.contains("scenes")) return c.error("", "missing 'scenes'");
    BOUNCE_TRY_VOID(parseScenes(c, doc["scenes"], base, study));
    if (!doc.contains("techniques")) return c.error("", "missing 'techniques'");
    if (!doc["techniques"].is_array() || doc["techniques"].empty())
        return c.error("/techniques", "expected a non-empty array of technique names or objects {name, settings, grid, list, scope}");
    for (size_t i = 0; i < doc["techniques"].size(); ++i)
        BOUNCE_TRY_VOID(parseTechnique(c, doc["techniques"][i], fmt::format("/techniques/{}", i), study));
    // Renderer settings of the study and of a variant must not disagree silently.
    for (const Variant& v : study.variants)
        for (const auto& [k, val] : study.renderer)
            if (v.settings.count("renderer." + k))
                return c.error("/renderer/" + pointerKey(k), fmt::format("also set by technique '{}' (variant {})", v.technique, v.id));
    for (Variant& v : study.variants)
        for (const auto& [k, val] : study.renderer) v.settings["renderer." + k] = val;
    if (doc.contains("temporal")) BOUNCE_TRY_VOID(parseTemporal(c, doc["temporal"], study));
    expand(study);
    return study;
}

}  // namespace bounce::study
