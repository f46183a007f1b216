// bounce._bounce: the C++ half of `import bounce` (python/bounce/__init__.py is the public API, with
// docstrings; python/bounce/__init__.pyi its types). It adds no lab logic: every call goes to the
// library functions the `bounce` commands call (app/RenderSession.h, app/CpuJobOptions.h,
// app/Comparison.h, app/StudyRun.h, app/Report.h, scene/SceneEdits.h, ...), so the same input gives the
// same pixels, numbers and one-line error messages. What is here is plumbing: numpy conversion, the GL
// thread (GlThread.h), the GIL released around rendering, tracing and comparing, errors as exceptions.
#include "GlThread.h"

#include "app/Cli.h"
#include "app/Comparison.h"
#include "app/CpuJobOptions.h"
#include "app/Options.h"
#include "app/ProcessContext.h"
#include "app/RenderSession.h"
#include "app/Report.h"
#include "app/RunRecord.h"
#include "app/StudyRun.h"
#include "core/ImageIo.h"
#include "core/Log.h"
#include "core/Resources.h"
#include "metrics/FlickerMeter.h"
#include "gpu/Objects.h"
#include "render/RenderSettings.h"
#include "scene/CameraPath.h"
#include "scene/SceneEdits.h"
#include "scene/SceneLoader.h"
#include "techniques/Registry.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <future>
#include <mutex>
#include <new>
#include <set>
#include <stdexcept>

namespace py = pybind11;

namespace bounce::python {
namespace {

// An input problem: raised in Python as bounce.Error with the command line's one-line message.
struct BounceError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

template <class T>
T unwrap(Expected<T> value) {
    if (!value) throw BounceError(value.error().message);
    return std::move(*value);
}
void unwrap(const Expected<void>& value) {
    if (!value) throw BounceError(value.error().message);
}

template <class F>
auto onGlThread(F&& f) {
    const py::gil_scoped_release release;
    return GlThread::instance().run(std::forward<F>(f));
}

// ---- numpy --------------------------------------------------------------------------------------

py::array_t<float> toNumpy(const Image& image) {
    py::array_t<float> out({image.height(), image.width(), 3});
    std::memcpy(out.mutable_data(), image.data(), image.pixelCount() * sizeof(glm::vec3));
    return out;
}

py::array_t<float> toNumpy(const ErrorMap& map) {
    py::array_t<float> out({map.height(), map.width()});
    std::memcpy(out.mutable_data(), map.values().data(), map.values().size() * sizeof(float));
    return out;
}

// An H x W x 3 array of any real type (converted to float32, row 0 the top, as EXR files).
Image fromNumpy(const py::handle& object, const std::string& label) {
    const auto array = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(object);
    if (!array) throw BounceError(fmt::format("{}: not an array of numbers", label));
    if (array.ndim() != 3 || array.shape(2) != 3)
        throw BounceError(fmt::format("{}: expected an H x W x 3 array (linear RGB), got {} dimensions{}", label, array.ndim(),
                                      array.ndim() == 3 ? fmt::format(" of shape ({}, {}, {})", array.shape(0), array.shape(1), array.shape(2)) : ""));
    const auto h = array.shape(0), w = array.shape(1);
    if (h < 1 || w < 1 || h > kMaxImageSide || w > kMaxImageSide)
        throw BounceError(fmt::format("{}: {} x {} pixels: each side must be between 1 and {}", label, w, h, kMaxImageSide));
    Image image(static_cast<int>(w), static_cast<int>(h));
    std::memcpy(image.data(), array.data(), image.pixelCount() * sizeof(glm::vec3));
    return image;
}

glm::vec3 vec3(const std::array<float, 3>& v) { return {v[0], v[1], v[2]}; }
std::array<float, 3> array3(glm::vec3 v) { return {v.x, v.y, v.z}; }

// ---- scenes --------------------------------------------------------------------------------------

// A scene shared by the Python object, its renderers and its references: edits show in the next
// frame. Every access goes through the GL thread, which orders it with rendering.
struct PyScene {
    std::shared_ptr<Scene> scene;
    std::string asked;  // the name or path it was loaded from (records)
    SceneParams params;
    // Bumped by object moves: a renderer that saw another value re-uploads the objects first.
    std::shared_ptr<std::atomic<uint64_t>> objectRevision = std::make_shared<std::atomic<uint64_t>>(0);
};

PyScene loadPyScene(const std::string& nameOrPath, const std::map<std::string, std::string>& params) {
    PyScene s;
    s.asked = nameOrPath;
    std::vector<std::string> assignments;
    for (const auto& [k, v] : params) assignments.push_back(k + "=" + v);
    // Loaded on the calling thread: scene loading touches no GL.
    Scene scene = [&] {
        const py::gil_scoped_release release;
        return unwrap(loadSceneWithParams(nameOrPath, assignments));
    }();
    s.params = SceneParams(params.begin(), params.end());
    s.scene = std::make_shared<Scene>(std::move(scene));
    return s;
}

const char* lightTypeName(LightType t) {
    switch (t) {
        case LightType::Point: return "point";
        case LightType::Spot: return "spot";
        case LightType::Directional: return "directional";
        case LightType::Area: return "area";
    }
    return "?";
}

py::dict poseDict(const CameraPose& p) {
    py::dict d;
    d["position"] = array3(p.position);
    d["target"] = array3(p.target);
    d["up"] = array3(p.up);
    d["fov"] = p.verticalFov;
    return d;
}

// ---- renderers -----------------------------------------------------------------------------------

struct PyRenderer;
// Live renderers, released before the context at interpreter exit.
std::mutex g_renderersMutex;
std::set<PyRenderer*> g_renderers;

struct PyRenderer {
    PyScene scene;
    std::unique_ptr<RenderSession> session;
    Component component = Component::Full;
    uint64_t seenRevision = 0;

    PyRenderer(const PyScene& s, const std::string& technique, const std::string& size, const std::vector<std::string>& settings,
               const std::string& componentName)
        : scene(s) {
        // The command's checks in its order: size, component, technique; then the session's.
        const glm::ivec2 pixels = unwrap(parseSize(size));
        auto c = parseComponent(componentName);
        if (!c) throw BounceError("--component: " + c.error().message);
        component = *c;
        seenRevision = scene.objectRevision->load();
        session = onGlThread([&] {
            auto t = unwrap(createRenderTechnique(technique));
            // Frames here always carry their timings (the run record): a measured context, as `render --stats`.
            return unwrap(RenderSession::create(scene.scene, std::move(t), pixels, settings, 0, gl::measuredContextConfig()));
        });
        const std::lock_guard lock(g_renderersMutex);
        g_renderers.insert(this);
    }
    ~PyRenderer() {
        close();
        const std::lock_guard lock(g_renderersMutex);
        g_renderers.erase(this);
    }
    void close() {
        if (!session) return;
        onGlThread([&] { session.reset(); });
    }
    RenderSession& open() {
        if (!session) throw BounceError("this renderer was closed");
        return *session;
    }
    Component pick(const std::optional<std::string>& name) const {
        if (!name) return component;
        auto c = parseComponent(*name);
        if (!c) throw BounceError("--component: " + c.error().message);
        return *c;
    }
    // On the GL thread: objects moved since the last frame are uploaded again.
    void sync() {
        const uint64_t revision = scene.objectRevision->load();
        if (revision != seenRevision) {
            session->invalidateObjects();
            seenRevision = revision;
        }
    }
    nlohmann::json extra(Component c, size_t count, uint32_t start) const {
        return {{"command", "python"}, {"component", std::string(componentName(c))}, {"frame_count", count}, {"start_frame", start}};
    }

    py::tuple frames(uint32_t count, uint32_t start, std::optional<float> time, const std::optional<std::string>& name, bool stack) {
        if (count < 1) throw BounceError(fmt::format("frames {} must be at least 1", count));
        const Component c = pick(name);
        RenderSession& s = open();
        std::vector<Image> images;
        std::string record;
        onGlThread([&] {
            if (!session) throw BounceError("this renderer was closed");
            sync();
            std::vector<FrameStats> stats;
            for (uint32_t f = start; f < start + count; ++f) {
                stats.push_back(time ? s.renderFrame(f, *time) : s.renderFrame(f));
                // Every frame's image for frames(); the CLI's --frames keeps only the last.
                if (stack || f + 1 == start + count) images.push_back(unwrap(s.readback(c, count > 1 ? fmt::format(" of frame {}", f) : "")));
            }
            record = s.runRecord(stats, extra(c, count, start)).dump();
        });
        if (!stack) return py::make_tuple(toNumpy(images.back()), record);
        const Image& first = images.front();
        py::array_t<float> out({static_cast<py::ssize_t>(images.size()), static_cast<py::ssize_t>(first.height()),
                                static_cast<py::ssize_t>(first.width()), py::ssize_t{3}});
        float* dst = out.mutable_data();
        for (const Image& im : images) {
            std::memcpy(dst, im.data(), im.pixelCount() * sizeof(glm::vec3));
            dst += im.pixelCount() * 3;
        }
        return py::make_tuple(out, record);
    }
};

// ---- CPU ground truths ---------------------------------------------------------------------------

template <class Args>
void fillCpuArgs(Args& a, const PyScene& scene, const std::string& size, const std::string& bounces, bool indirectOnly,
                 bool diffuseOnly, uint64_t seed, double timeLimit, int threads, uint32_t frame) {
    a.scene = scene.asked;
    for (const auto& [k, v] : scene.params) a.sceneParams.push_back(k + "=" + v);
    a.size = size;
    a.bounces = bounces;
    a.indirectOnly = indirectOnly;
    a.diffuseOnly = diffuseOnly;
    a.seed = seed;
    a.timeLimit = timeLimit;
    a.threads = threads;
    a.frame = frame;
}

// A copy of the scene as it is now (edits included), taken on the GL thread so no frame is mid-way.
Scene snapshot(const PyScene& s) {
    return onGlThread([&] { return *s.scene; });
}

py::tuple reference(const PyScene& scene, const std::string& size, uint32_t spp, const std::string& bounces, bool indirectOnly,
                    bool diffuseOnly, uint64_t seed, double timeLimit, int threads, uint32_t frame) {
    ReferenceArgs args;
    fillCpuArgs(args, scene, size, bounces, indirectOnly, diffuseOnly, seed, timeLimit, threads, frame);
    args.spp = spp;
    const ReferenceJob job = unwrap(referenceJobFromArgs(args));
    const Scene copy = snapshot(scene);
    PathTracerResult result;
    std::string record;
    {
        const py::gil_scoped_release release;
        result = unwrap(runReferenceJob(copy, job));
        nlohmann::ordered_json r = referenceRunRecord(copy, job, result);
        addNoiseFloor(r, result);
        record = r.dump();
    }
    return py::make_tuple(toNumpy(result.radiance), toNumpy(result.variance), record);
}

py::tuple photonMap(const PyScene& scene, const std::string& size, uint64_t photons, int k, float maxRadius, uint32_t spp,
                    const std::string& bounces, bool indirectOnly, bool diffuseOnly, uint64_t seed, double timeLimit, int threads,
                    uint32_t frame) {
    PhotonMapArgs args;
    fillCpuArgs(args, scene, size, bounces, indirectOnly, diffuseOnly, seed, timeLimit, threads, frame);
    args.photons = photons;
    args.k = k;
    args.maxRadius = maxRadius;
    args.spp = spp;
    const PhotonMapJob job = unwrap(photonMapJobFromArgs(args));
    const Scene copy = snapshot(scene);
    PhotonMapResult result;
    std::string record;
    {
        const py::gil_scoped_release release;
        result = unwrap(runPhotonMapJob(copy, job));
        record = photonMapRunRecord(copy, job, result).dump();
    }
    return py::make_tuple(toNumpy(result.radiance), record);
}

// ---- compare -------------------------------------------------------------------------------------

bool isPath(const py::handle& o) {
    return py::isinstance<py::str>(o) || py::hasattr(o, "__fspath__");
}

py::tuple compare(const py::object& test, const py::object& reference, const py::object& variance, const std::string& toneCurve,
                  float exposureEv, double pixelsPerDegree, const std::string& heatmap) {
    // The command's option checks, in its order and words.
    ToneMap radianceToneMap{exposureEv, ToneCurve::Aces};
    auto curve = parseToneCurve(toneCurve);
    if (!curve) throw BounceError("--tonemap: " + curve.error().message);
    radianceToneMap.curve = *curve;
    if (!std::isfinite(exposureEv)) throw BounceError(fmt::format("--exposure: {} is not a finite number", exposureEv));
    if (!(pixelsPerDegree > 0.0) || !std::isfinite(pixelsPerDegree))
        throw BounceError(fmt::format("--ppd: {} is not a positive number", pixelsPerDegree));
    CompareRequest request;
    request.pixelsPerDegree = pixelsPerDegree;
    if (!heatmap.empty()) request.heatmap = unwrap(parseHeatmapMetric(heatmap));

    auto input = [&](const py::object& o, const char* label) {
        if (isPath(o)) {
            const std::string path = py::str(py::module_::import("os").attr("fspath")(o));
            const py::gil_scoped_release release;
            return unwrap(loadCompareInput(path, radianceToneMap));
        }
        return unwrap(memoryCompareInput(label, fromNumpy(o, label), radianceToneMap));
    };
    const CompareInput t = input(test, "test image");
    const CompareInput r = input(reference, "reference image");
    if (!variance.is_none()) {
        ReferenceNoise noise;
        noise.varianceImage = fromNumpy(variance, "variance image");
        request.noise = std::move(noise);
    } else if (isPath(reference) && r.radiance) {
        const std::string path = py::str(py::module_::import("os").attr("fspath")(reference));
        request.noise = unwrap(findReferenceNoise(path));
    }
    Comparison c;
    {
        const py::gil_scoped_release release;
        c = unwrap(compareInputs(t, r, request));
    }
    py::object map = c.heatmap ? py::object(toNumpy(c.heatmap->map)) : py::object(py::none());
    return py::make_tuple(comparisonJson(c).dump(), map);
}

// ---- the rest ------------------------------------------------------------------------------------

std::string describe(Configurable& target) {
    nlohmann::json out = nlohmann::json::array();
    for (const SettingDescription& d : describeSettings(target))
        out.push_back({{"name", d.name}, {"type", d.type}, {"default", d.defaultValue}, {"range", d.range}, {"doc", d.doc},
                        {"profile_defaults", d.profileDefaults}});
    return out.dump();
}

std::string techniquesJson() {
    nlohmann::json out = nlohmann::json::array();
    for (const TechniqueInfo& t : registeredTechniques()) {
        auto technique = t.create();
        const ReferenceScope& s = t.scope;
        out.push_back({{"name", t.name},
                       {"summary", t.summary},
                       {"paper", t.reference},
                       {"scope", {{"bounces", s.bounces < 0 ? nlohmann::json("unbounded") : nlohmann::json(s.bounces)},
                                  {"indirect_only", s.indirectOnly},
                                  {"diffuse_only", s.diffuseOnly},
                                  {"component", std::string(componentName(s.component))}}},
                       {"settings", nlohmann::json::parse(describe(*technique))}});
    }
    return out.dump();
}

std::string scenesJson() {
    nlohmann::json out = nlohmann::json::array();
    for (const BuiltinSceneInfo& s : builtinScenes()) out.push_back({{"name", s.name}, {"description", s.description}, {"params", s.params}});
    return out.dump();
}

std::string sweep(const std::string& file, const std::string& out, bool progress) {
    const study::Study s = [&] {
        const py::gil_scoped_release release;
        return unwrap(study::loadStudy(file, out));
    }();
    const study::InProcessRun run = onGlThread([&] {
        return unwrap(study::runStudyInProcess(s, [&](const study::Job& j, size_t i, size_t n) {
            if (progress) std::fprintf(stderr, "sweep: %zu/%zu %s\n", i + 1, n, j.id.c_str());
        }));
    });
    return nlohmann::json({{"output", s.output.string()}, {"jobs", run.jobs}, {"ran", run.ran},
                           {"finished_before", run.finishedBefore}, {"refused", run.refused}, {"failed", run.failed},
                           {"blocked", run.blocked}})
        .dump();
}

std::string resourcesJson() {
    return onGlThread([] {
        const gl::LiveResources r = gl::liveResources();
        return nlohmann::json({{"gl_objects", r.objects}, {"buffers", r.buffers}, {"textures", r.textures},
                               {"framebuffers", r.framebuffers}, {"vertex_arrays", r.vertexArrays}, {"programs", r.programs},
                               {"shaders", r.shaders}, {"queries", r.queries}, {"buffer_bytes", r.bufferBytes},
                               {"texture_bytes", r.textureBytes}, {"rss_bytes", residentBytes()}})
            .dump();
    });
}

// Interpreter exit (atexit): renderers still alive give their GL objects back, then the context goes,
// on the thread that made it, and the GL thread ends.
void shutdown() {
    const py::gil_scoped_release release;
    GlThread::instance().shutdown([] {
        const std::lock_guard lock(g_renderersMutex);
        for (PyRenderer* r : g_renderers) r->session.reset();
        releaseProcessContext();
    });
}

}  // namespace
}  // namespace bounce::python

using namespace bounce;
using namespace bounce::python;

PYBIND11_MODULE(_bounce, m) {
    m.doc() = "bounce's C++ core; use the `bounce` package (python/bounce/__init__.py)";
    // Never destroyed: a static Python object would be released after the interpreter is gone.
    static auto* error = new py::exception<BounceError>(m, "Error", PyExc_Exception);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const BounceError& e) {
            (*error)(oneLine(e.what()).c_str());
        } catch (const std::bad_alloc&) {
            // As the command line: sizes are checked first; this is what those checks missed.
            PyErr_SetString(PyExc_MemoryError, "out of memory (std::bad_alloc): try a smaller size or fewer samples");
        } catch (const py::builtin_exception&) {
            throw;  // pybind11's own (TypeError, ValueError, ...)
        } catch (const py::error_already_set&) {
            throw;
        } catch (const std::exception& e) {
            // Library exceptions (OpenEXR, json, filesystem) are input problems, one line as the CLI says them.
            (*error)(oneLine(e.what()).c_str());
        }
    });
    // As `bounce`: warnings and errors on stderr, scene files' settings checked against the registry.
    setLogLevel("warn");
    setSceneSettingCheck(checkSceneSetting);
    py::module_::import("atexit").attr("register")(py::cpp_function(&shutdown));

    m.def("set_log_level", [](const std::string& level) { setLogLevel(level); });
    m.def("scenes", &scenesJson);
    m.def("techniques", &techniquesJson);
    m.def("renderer_settings", [] {
        render::RenderSettings r;
        return describe(r);
    });
    m.def("gl_info", [] {
        return onGlThread([] { return gpuInfoJson(unwrap(processContext(gl::measuredContextConfig()))->info()).dump(); });
    });
    m.def("select_gpu", [](int index) {
        // `bounce --gpu N`: checked against the EGL devices now; only before the context exists.
        onGlThread([&] {
            if (processContextExists())
                throw BounceError(fmt::format("select_gpu({}): the GL context exists already (call it before the first renderer, "
                                              "study or gl_info(); or set BOUNCE_EGL_DEVICE before starting Python)", index));
            unwrap(selectGpu(std::to_string(index), "select_gpu"));
        });
    }, py::arg("index"));
    m.def("resources", &resourcesJson);

    py::class_<PyScene>(m, "Scene")
        .def_static("load", &loadPyScene, py::arg("name_or_path"), py::arg("params"))
        .def("copy", [](const PyScene& s) {
            PyScene c = s;
            c.scene = std::make_shared<Scene>(snapshot(s));
            c.objectRevision = std::make_shared<std::atomic<uint64_t>>(0);
            return c;
        })
        .def_property_readonly("asked", [](const PyScene& s) { return s.asked; })
        .def_property_readonly("params", [](const PyScene& s) { return std::map<std::string, std::string>(s.params.begin(), s.params.end()); })
        .def("info", [](const PyScene& s) {
            const Scene copy = snapshot(s);
            py::dict d;
            d["name"] = copy.name;
            d["source"] = copy.source;
            d["frame_rate"] = copy.frameRate;
            d["triangles"] = copy.triangleCount();
            py::list lights, objects;
            for (const Light& l : copy.lights) {
                py::dict ld;
                ld["name"] = l.name;
                ld["type"] = lightTypeName(l.type);
                ld["position"] = array3(l.position);
                ld["direction"] = array3(l.direction);
                ld["animated"] = l.isDynamic();
                lights.append(ld);
            }
            for (const Object& o : copy.objects) {
                py::dict od;
                od["name"] = o.name;
                od["animated"] = o.isDynamic();
                objects.append(od);
            }
            d["lights"] = lights;
            d["objects"] = objects;
            d["camera"] = poseDict(CameraPose::of(copy.camera));
            return d;
        })
        .def("move_light", [](PyScene& s, size_t i, std::array<float, 3> d) { onGlThread([&] { unwrap(moveLight(*s.scene, i, vec3(d))); }); })
        .def("set_light", [](PyScene& s, const std::string& name, std::array<float, 3> p, std::array<float, 3> d) {
            onGlThread([&] { unwrap(setLightPose(*s.scene, LightPose{name, vec3(p), vec3(d)})); });
        })
        .def("move_object", [](PyScene& s, size_t i, std::array<float, 3> d) {
            onGlThread([&] { unwrap(moveObject(*s.scene, i, vec3(d))); });
            ++*s.objectRevision;
        })
        .def("set_camera", [](PyScene& s, std::array<float, 3> p, std::array<float, 3> t, std::array<float, 3> up, float fov) {
            onGlThread([&] { unwrap(placeCamera(*s.scene, CameraPose{vec3(p), vec3(t), vec3(up), fov})); });
        });

    py::class_<CameraPath>(m, "CameraPath")
        .def_static("load", [](const std::string& path) { return unwrap(readCameraPath(path)); })
        .def_property_readonly("scene", [](const CameraPath& p) { return p.scene; })
        .def_property_readonly("start_time", &CameraPath::startTime)
        .def_property_readonly("end_time", &CameraPath::endTime)
        .def("evaluate", [](const CameraPath& p, float time) { return poseDict(p.evaluate(time)); })
        .def("frame_range", &CameraPath::frameRange)
        .def_property_readonly("lights", [](const CameraPath& p) {
            py::list out;
            for (const LightPose& l : p.lights) {
                py::dict d;
                d["name"] = l.name;
                d["position"] = array3(l.position);
                d["direction"] = array3(l.direction);
                out.append(d);
            }
            return out;
        });

    py::class_<PyRenderer>(m, "Renderer")
        .def(py::init<const PyScene&, const std::string&, const std::string&, const std::vector<std::string>&, const std::string&>(),
             py::arg("scene"), py::arg("technique"), py::arg("size"), py::arg("settings"), py::arg("component"))
        .def("frames", &PyRenderer::frames, py::arg("count"), py::arg("start"), py::arg("time"), py::arg("component"), py::arg("stack"))
        .def("close", &PyRenderer::close)
        .def_property_readonly("closed", [](const PyRenderer& r) { return !r.session; })
        .def_property_readonly("component", [](const PyRenderer& r) { return std::string(componentName(r.component)); })
        .def("settings", [](PyRenderer& r) {
            RenderSession& s = r.open();
            return onGlThread([&] {
                return nlohmann::json({{"technique", settingsToJson(s.pipeline().technique())},
                                       {"renderer", [&] {
                                            render::RenderSettings copy = s.pipeline().renderSettings();
                                            return settingsToJson(copy);
                                        }()},
                                       {"name", std::string(s.pipeline().technique().name())},
                                       {"size", {s.pipeline().size().x, s.pipeline().size().y}}})
                    .dump();
            });
        });

    m.def("reference", &reference, py::arg("scene"), py::arg("size"), py::arg("spp"), py::arg("bounces"), py::arg("indirect_only"),
          py::arg("diffuse_only"), py::arg("seed"), py::arg("time_limit"), py::arg("threads"), py::arg("frame"));
    m.def("photon_map", &photonMap, py::arg("scene"), py::arg("size"), py::arg("photons"), py::arg("k"), py::arg("max_radius"),
          py::arg("spp"), py::arg("bounces"), py::arg("indirect_only"), py::arg("diffuse_only"), py::arg("seed"),
          py::arg("time_limit"), py::arg("threads"), py::arg("frame"));
    m.def("compare", &compare, py::arg("test"), py::arg("reference"), py::arg("variance"), py::arg("tonemap"), py::arg("exposure"),
          py::arg("ppd"), py::arg("heatmap"));
    m.def("sweep", &sweep, py::arg("study"), py::arg("out"), py::arg("progress"));
    m.def("report", [](const std::string& results, const std::string& out) {
        const py::gil_scoped_release release;
        return unwrap(writeStudyReport(results, out)).string();
    }, py::arg("results"), py::arg("out"));
    m.def("read_image", [](const std::string& path) {
        Image image = [&] {
            const py::gil_scoped_release release;
            return unwrap(readImage(path));
        }();
        return toNumpy(image);
    }, py::arg("path"));
    m.def("write_image", [](const std::string& path, const py::object& array, float exposureEv, const std::string& toneCurve) {
        const Image image = fromNumpy(array, path);
        auto curve = parseToneCurve(toneCurve);
        if (!curve) throw BounceError("--tonemap: " + curve.error().message);
        const py::gil_scoped_release release;
        unwrap(writeImage(path, image, ToneMap{exposureEv, *curve}));
    }, py::arg("path"), py::arg("image"), py::arg("exposure"), py::arg("tonemap"));
    m.def("flicker", [](const py::list& frames) {
        std::vector<Image> images;
        for (size_t i = 0; i < frames.size(); ++i) images.push_back(fromNumpy(frames[i], fmt::format("frame {}", i)));
        const py::gil_scoped_release release;
        return unwrap(flicker(images));
    }, py::arg("frames"));
    m.attr("flip_default_ppd") = kFlipDefaultPixelsPerDegree;
}
