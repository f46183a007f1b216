#include "techniques/nichols/VplWindow.h"

#include "core/Check.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"

#include <algorithm>

namespace bounce::nichols {

int VplWindow::size() {
    const int limit = gl::Context::current()->info().maxUniformBlockSize / static_cast<int>(sizeof(VplRecord));
    // Round down to a multiple of 16 records (768 bytes): window offsets stay multiples of 256 bytes.
    return std::max(16, std::min(kMaxRecords, limit) / 16 * 16);
}

std::vector<std::pair<std::string, std::string>> VplWindow::defines() {
    return {{"VPL_WINDOW", std::to_string(size())}};
}

std::vector<std::pair<std::string, std::string>> VplWindow::withDefines(std::vector<std::pair<std::string, std::string>> defines) {
    for (auto& d : VplWindow::defines()) defines.push_back(std::move(d));
    return defines;
}

int VplWindow::perDraw(int budget) {
    const int n = std::max(1, std::min(size(), budget));
    return n >= kAlignRecords ? n / kAlignRecords * kAlignRecords : n;
}

int VplWindow::bind(const gl::Buffer& cache, int first, int count) {
    const int records = size();
    const int windowFirst = first / kAlignRecords * kAlignRecords;
    BOUNCE_CHECK(first >= 0 && count >= 1 && first - windowFirst + count <= records,
                 "VPLs [{}, {}) lie in one window of {} from {}", first, first + count, records, windowFirst);
    const size_t offset = static_cast<size_t>(windowFirst) * sizeof(VplRecord);
    BOUNCE_CHECK(offset < cache.size(), "VPL window start {} inside the cache of {} bytes", windowFirst, cache.size());
    GLint alignment = 0;
    glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
    BOUNCE_CHECK(alignment > 0 && offset % static_cast<size_t>(alignment) == 0, "VPL window offset {} aligned to {}", offset, alignment);
    const size_t range = static_cast<size_t>(records) * sizeof(VplRecord);
    BOUNCE_CHECK(offset + range <= cache.size(), "VPL window [{}, {}) bytes inside the padded cache of {} bytes", offset,
                 offset + range, cache.size());
    cache.bindRange(GL_UNIFORM_BUFFER, BINDING_UBO_VPL_WINDOW, offset, range);
    return windowFirst;
}

int VplWindow::paddedRecords(int records) {
    return (std::max(records, 1) - 1) / kAlignRecords * kAlignRecords + size();
}

}  // namespace bounce::nichols
