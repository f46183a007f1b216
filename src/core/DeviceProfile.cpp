#include "core/DeviceProfile.h"

namespace bounce {

std::string_view profileName(DeviceProfile p) { return p == DeviceProfile::Llvmpipe ? "llvmpipe" : "gpu"; }

Expected<DeviceProfile> parseProfile(std::string_view text, std::string_view source) {
    if (text == "llvmpipe") return DeviceProfile::Llvmpipe;
    if (text == "gpu") return DeviceProfile::Gpu;
    return makeError("{}='{}' is not a device profile (llvmpipe or gpu)", source, text);
}

Expected<ProfileKey> splitProfileKey(const std::string& key) {
    const size_t at = key.rfind('@');
    if (at == std::string::npos) return ProfileKey{key, std::nullopt};
    const std::string suffix = key.substr(at + 1);
    if (suffix == "llvmpipe") return ProfileKey{key.substr(0, at), DeviceProfile::Llvmpipe};
    if (suffix == "gpu") return ProfileKey{key.substr(0, at), DeviceProfile::Gpu};
    return makeError("setting '{}': '@{}' is not a device profile (llvmpipe or gpu)", key, suffix);
}

DeviceProfile profileOfRenderer(std::string_view renderer) {
    // Mesa's software rasterisers name themselves in GL_RENDERER ("llvmpipe (LLVM 15.0.6, 256 bits)",
    // "softpipe", "Software Rasterizer"); zink over lavapipe says "zink (llvmpipe ...)" or "lavapipe".
    for (std::string_view name : {"llvmpipe", "softpipe", "swrast", "lavapipe", "Software Rasterizer"})
        if (renderer.find(name) != std::string_view::npos) return DeviceProfile::Llvmpipe;
    return DeviceProfile::Gpu;
}

Expected<DeviceProfile> resolveProfile(std::string_view renderer, std::string_view override) {
    if (!override.empty()) return parseProfile(override, "BOUNCE_PROFILE");
    return profileOfRenderer(renderer);
}

}  // namespace bounce
