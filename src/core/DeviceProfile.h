#pragma once
// The device profile: whether a run is on Mesa's llvmpipe (a software rasteriser on the CPU, with its
// own silent shader loop limit and minutes-long draws) or on a GPU. A few values that exist only for
// llvmpipe (gpu/ShaderLimits.h's loop budget, settings whose defaults were lowered to keep llvmpipe
// runs short) depend on it; everything else, and every paper default, is the same on both.
// The context's renderer string decides (gl::GpuInfo::profile); BOUNCE_PROFILE=llvmpipe|gpu overrides.
// GL-free (core): settings declare per-profile defaults (core/Settings.h), docs/gpu.md "Device profile".
#include "core/Error.h"

#include <optional>
#include <string>
#include <string_view>

namespace bounce {

enum class DeviceProfile { Llvmpipe, Gpu };

std::string_view profileName(DeviceProfile p);
// "llvmpipe" or "gpu"; `source` names the input in the error.
Expected<DeviceProfile> parseProfile(std::string_view text, std::string_view source);
// The profile of a GL renderer string: llvmpipe for Mesa's software rasterisers, gpu otherwise.
DeviceProfile profileOfRenderer(std::string_view renderer);
// profileOfRenderer unless `override` (BOUNCE_PROFILE's value) is non-empty, which must then parse.
Expected<DeviceProfile> resolveProfile(std::string_view renderer, std::string_view override);

// A scene's default setting for one profile only: "technique.setting@llvmpipe" (or "@gpu") applies on
// that profile, over the plain "technique.setting" (docs/scene.md "Settings"). Splits `key` into the
// plain key and its profile (none without a suffix); an unknown suffix is an error naming it.
struct ProfileKey {
    std::string key;
    std::optional<DeviceProfile> profile;
};
Expected<ProfileKey> splitProfileKey(const std::string& key);

// A setting's default per profile (core/Settings.h: SettingsVisitor::field with a PerProfile).
template <class T>
struct PerProfile {
    T llvmpipe;
    T gpu;
    const T& operator[](DeviceProfile p) const { return p == DeviceProfile::Llvmpipe ? llvmpipe : gpu; }
};

}  // namespace bounce
