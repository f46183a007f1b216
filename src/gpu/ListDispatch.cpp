#include "gpu/ListDispatch.h"

#include "gpu/Bindings.h"
#include "gpu/DispatchGrid.h"

namespace bounce::gl {

Expected<ListDispatch> ListDispatch::create() {
    ListDispatch d;
    BOUNCE_TRY(d.m_args, Program::build({"listDispatch.args", {{GL_COMPUTE_SHADER, "common/list_args.comp"}}}));
    return d;
}

Buffer ListDispatch::createArgs(std::string_view label) { return Buffer::create(label, 3 * sizeof(uint32_t)); }

void ListDispatch::writeArgs(const Buffer& list, const Buffer& args, uint32_t capacity, uint32_t maxX) {
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the appends' count
    list.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH2);
    args.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH3);
    m_args.set("u_maxGroupsX", maxX > 0 ? maxX : maxGroupsX());
    m_args.set("u_capacity", capacity);
    m_args.use();
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

void ListDispatch::dispatch(const Buffer& args) {
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, args.id());
    glDispatchComputeIndirect(0);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
}

}  // namespace bounce::gl
