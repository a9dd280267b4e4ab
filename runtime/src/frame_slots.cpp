#include "frame_slots.h"

#include <cstring>
#include <stdexcept>
#include <string>

#include "draw_pass.h"
#include "meadow/runtime/error.h"

namespace meadow::runtime {
namespace {

constexpr double kMillisecondsPerNanosecond = 1e-6;
// A frame still running after this long is a hung or lost device: far longer than even llvmpipe
// takes for a million blades.
constexpr GLuint64 kFrameTimeout_ns = 120'000'000'000ull;
constexpr GLsizeiptr kCountersSize = sizeof(gpu::DrawCommandGpu) + sizeof(gpu::CullStatsGpu);

// A buffer mapped for reading, unmapped when it goes out of scope.
class ReadMapping {
public:
    ReadMapping(const gl::Buffer& buffer, GLsizeiptr size, const char* what)
        : id_(buffer.id()), data_(glMapNamedBufferRange(id_, 0, size, GL_MAP_READ_BIT)) {
        if (!data_)
            throw RuntimeError(std::string("renderer: mapping the ") + what +
                               " of a finished frame failed (glMapNamedBufferRange)");
    }
    ReadMapping(const ReadMapping&) = delete;
    ReadMapping& operator=(const ReadMapping&) = delete;
    ~ReadMapping() { glUnmapNamedBuffer(id_); }
    [[nodiscard]] const void* data() const { return data_; }

private:
    GLuint id_;
    const void* data_;
};

}  // namespace

StageTimers::StageTimers() {
    for (gl::Query& q : queries_) q = gl::Query::create(GL_TIME_ELAPSED);
}

void StageTimers::readInto(FrameStats& st) const {
    double* gpuTimes[kStageCount] = {&st.gpuPrepass_ms, &st.gpuPhysics_ms, &st.gpuCulling_ms,
                                     &st.gpuShadows_ms, &st.gpuDraw_ms,    &st.gpuResolve_ms};
    for (int s = 0; s < kStageCount; ++s) {
        *gpuTimes[s] = 0.0;
        if (!ran_[s]) continue;
        GLuint64 elapsed_ns = 0;
        glGetQueryObjectui64v(queries_[s].id(), GL_QUERY_RESULT, &elapsed_ns);
        *gpuTimes[s] = static_cast<double>(elapsed_ns) * kMillisecondsPerNanosecond;
    }
}

void setCounts(FrameStats& st, const gpu::DrawCommandGpu& command,
               const gpu::CullStatsGpu& culled) {
    st.bladesDrawn = command.vertexCount;
    st.culledOrientation = culled.culledOrientation;
    st.culledFrustum = culled.culledFrustum;
    st.culledDistance = culled.culledDistance;
    st.culledOcclusion = culled.culledOcclusion;
}

FrameSlots::FrameSlots(int width_px, int height_px) : width_px_(width_px), height_px_(height_px) {
    for (FrameSlot& slot : slots_) {
        slot.counters = gl::Buffer::create();
        glNamedBufferStorage(slot.counters.id(), kCountersSize, nullptr, GL_MAP_READ_BIT);
    }
}

void FrameSlots::clear() {
    for (FrameSlot& slot : slots_) slot.done = gl::Sync();
    oldest_ = 0;
    pending_ = 0;
}

FrameSlot& FrameSlots::next() {
    if (full())
        throw std::logic_error("FrameSlots::next: all " + std::to_string(kFramesInFlight) +
                               " slots are pending; take the oldest first");
    return slots_[(oldest_ + pending_) % kFramesInFlight];
}

void FrameSlots::submit(const gl::Buffer& drawCommand, const gl::Buffer& cullStats,
                        const DrawPass* imageSource) {
    FrameSlot& slot = next();
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the culling pass wrote both in a shader
    glCopyNamedBufferSubData(drawCommand.id(), slot.counters.id(), 0, 0,
                             sizeof(gpu::DrawCommandGpu));
    glCopyNamedBufferSubData(cullStats.id(), slot.counters.id(), 0, sizeof(gpu::DrawCommandGpu),
                             sizeof(gpu::CullStatsGpu));
    slot.hasImage = imageSource != nullptr;
    if (slot.hasImage) {
        if (!slot.pixels) {
            slot.pixels = gl::Buffer::create();
            glNamedBufferStorage(slot.pixels.id(), GLsizeiptr{4} * width_px_ * height_px_, nullptr,
                                 GL_MAP_READ_BIT | GL_CLIENT_STORAGE_BIT);
        }
        imageSource->packColor(slot.pixels);
    }
    slot.done = gl::Sync::fence();
    glFlush();  // the fence must reach the GPU, or waiting on it later could wait forever
    ++pending_;
}

const FrameSlot& FrameSlots::waitOldest() const {
    if (pending_ == 0) throw std::logic_error("FrameSlots::waitOldest: no frame is pending");
    const FrameSlot& slot = slots_[oldest_];
    const GLenum status =
        glClientWaitSync(slot.done.get(), GL_SYNC_FLUSH_COMMANDS_BIT, kFrameTimeout_ns);
    if (status == GL_TIMEOUT_EXPIRED)
        throw RuntimeError("renderer: frame " + std::to_string(slot.stats.frame) +
                           " did not finish on the GPU within " +
                           std::to_string(kFrameTimeout_ns / 1'000'000'000ull) +
                           " s (hung or lost device?)");
    if (status == GL_WAIT_FAILED)
        throw RuntimeError("renderer: waiting for frame " + std::to_string(slot.stats.frame) +
                           " failed (glClientWaitSync: GL_WAIT_FAILED)");
    return slot;
}

RenderedFrame FrameSlots::takeOldest() {
    if (pending_ == 0) throw std::logic_error("FrameSlots::takeOldest: no frame is pending");
    FrameSlot& slot = slots_[oldest_];
    RenderedFrame out;
    out.stats = slot.stats;
    {
        const ReadMapping counts(slot.counters, kCountersSize, "draw command and cull stats");
        gpu::DrawCommandGpu command{};
        gpu::CullStatsGpu culled{};
        std::memcpy(&command, counts.data(), sizeof command);
        std::memcpy(&culled, static_cast<const char*>(counts.data()) + sizeof command,
                    sizeof culled);
        setCounts(out.stats, command, culled);
    }
    slot.timers.readInto(out.stats);  // complete: no wait
    if (slot.hasImage) {
        const ReadMapping pixels(slot.pixels, GLsizeiptr{4} * width_px_ * height_px_, "image");
        out.image_bgr = bgrFromBottomUpRgba(pixels.data(), width_px_, height_px_);
    }
    slot.done = gl::Sync();
    oldest_ = (oldest_ + 1) % kFramesInFlight;
    --pending_;
    return out;
}

double FrameSlots::secondOldestSubmitted_ms() const {
    if (pending_ < 2)
        throw std::logic_error("FrameSlots::secondOldestSubmitted_ms: " + std::to_string(pending_) +
                               " frame(s) pending, need 2");
    return slots_[(oldest_ + 1) % kFramesInFlight].submitted_ms;
}

}  // namespace meadow::runtime
