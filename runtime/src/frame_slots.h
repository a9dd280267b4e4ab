#pragma once
// Per-frame GPU resources of the renderer. StageTimers: the GL_TIME_ELAPSED queries of one
// frame's stages. FrameSlots: a ring of kFramesInFlight slots for pipelined rendering; each slot
// keeps what its frame leaves for the CPU (timer queries, a GPU-side copy of the draw command and
// cull stats, the resolved image in a pixel-pack buffer) behind a fence, so the CPU collects a
// frame only once the GPU has finished it and never waits on the frame it has just submitted.
#include <array>
#include <cstddef>

#include "gl/gl_object.h"
#include "meadow/runtime/renderer.h"
#include "shared/blade_types.h"

namespace meadow::runtime {

class DrawPass;

enum Stage { kPrepass, kPhysics, kCulling, kShadows, kDraw, kResolve, kStageCount };

class StageTimers {
public:
    StageTimers();

    void reset() { ran_ = {}; }  // before a frame's first stage
    template <class Work>
    void time(Stage stage, Work&& work) {
        glBeginQuery(GL_TIME_ELAPSED, queries_[stage].id());
        work();
        glEndQuery(GL_TIME_ELAPSED);
        ran_[stage] = true;
    }
    // The GPU milliseconds of the stages that ran (GL_QUERY_RESULT: waits unless the frame has
    // completed); 0 for the others.
    void readInto(FrameStats& stats) const;

private:
    std::array<gl::Query, kStageCount> queries_;
    std::array<bool, kStageCount> ran_{};
};

// The counts of a frame's draw command and cull stats buffers.
void setCounts(FrameStats& stats, const gpu::DrawCommandGpu& command,
               const gpu::CullStatsGpu& culled);

struct FrameSlot {
    StageTimers timers;
    gl::Buffer counters;  // DrawCommandGpu then CullStatsGpu, copied on the GPU
    gl::Buffer pixels;    // RGBA8 rows, bottom first (GL_PIXEL_PACK_BUFFER); created when needed
    gl::Sync done;        // signals once the frame and its copies have completed
    FrameStats stats;     // what the CPU knew when it submitted the frame
    bool hasImage = false;
    double submitted_ms = 0.0;  // the renderer's clock when the frame's submission began
};

class FrameSlots {
public:
    static constexpr int kFramesInFlight = 3;

    FrameSlots(int width_px, int height_px);

    // Forgets every pending frame (after a call that threw: its frames are never delivered).
    void clear();
    [[nodiscard]] int pendingCount() const { return pending_; }
    [[nodiscard]] bool full() const { return pending_ == kFramesInFlight; }
    // The slot the next frame records into; not full().
    [[nodiscard]] FrameSlot& next();
    // After next()'s frame has been recorded: copies its counts from the scene's buffers and,
    // with `imageSource`, its resolved image into the slot, all on the GPU, then fences and
    // flushes. The slot is pending from now on.
    void submit(const gl::Buffer& drawCommand, const gl::Buffer& cullStats,
                const DrawPass* imageSource);
    // The oldest pending slot, once the GPU has completed it (waits for its fence only).
    // Throws RuntimeError if it does not complete within kFrameTimeout_ns.
    [[nodiscard]] const FrameSlot& waitOldest() const;
    // The oldest pending frame, read from its completed slot, which becomes free. frame_ms is
    // left to the caller. Call waitOldest() first.
    [[nodiscard]] RenderedFrame takeOldest();
    // The submission time of the pending frame after the oldest; there must be one.
    [[nodiscard]] double secondOldestSubmitted_ms() const;

private:
    int width_px_, height_px_;
    std::array<FrameSlot, kFramesInFlight> slots_;
    int oldest_ = 0, pending_ = 0;
};

}  // namespace meadow::runtime
