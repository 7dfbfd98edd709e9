#pragma once
// Per-pass GPU timing with timestamp pairs (glQueryCounter, never nested GL_TIME_ELAPSED), kept in
// a ring of `frames_in_flight` query sets, one a frame. The frame path never waits for a result:
// begin_frame() collects, oldest first, the frames whose every query reports
// GL_QUERY_RESULT_AVAILABLE, and stops at the first that is not yet. When the frame's slot still
// holds a frame not collected (the GPU is a whole ring behind), that frame is not timed: its passes
// still open their debug groups, skipped_frames() counts it, and the report says how many. Only
// drain() (end of a run, tests) waits. Every sample carries the number of the frame it was taken in.
//
// Every pass opens a KHR_debug group of the same name, so GPU debuggers show the frame as named
// passes too.
//
// A pass named `within` another (pass(name, within)) is one of that pass's dispatches, e.g. an
// iterative solve's accelerate and residual passes inside the solve: it always opens its debug group,
// and takes a timestamp pair of its own only with set_detail(true) (`ranryu profile --detail`). A
// solve issues some thousands of such dispatches a frame, and a pair each costs GPU time the frame
// rate would show (docs/PERFORMANCE.md "Passes within passes, timed apart"), so by default their time
// is their parent's. Without detail its calls are counted, frame by frame as the timed ones are, so a
// report can name them (untimed_calls()). Passes nest one level: a pass within a pass within another
// is an Error.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "gl/objects.h"

namespace ranryu::profile {

struct PassId {
    std::uint16_t index = 0;
};

// What one pass took, over the frames that were read back.
struct PassSamples {
    std::string name;
    int within = -1;             // the index of the pass it runs within, or -1 (a pass of its own)
    // Per frame read back in which it ran within its parent without detail (GpuTimer::set_detail):
    // its calls, and the frame's number. Trimmed with the rest of the history.
    std::vector<std::uint32_t> untimed;
    std::vector<std::uint64_t> untimed_frames;
    std::vector<double> ms;      // per frame in which the pass ran: sum of its calls' times
    std::vector<int> calls;      // per frame in which the pass ran: number of calls
    std::vector<std::uint64_t> frames;   // per frame in which the pass ran: its number (0 = the timer's first)
};

class GpuTimer {
public:
    // `calls_per_frame`: timed passes a frame is expected to make. A frame that makes more doubles its
    // slot's query pool (an allocation when a new maximum is reached, never once a run has settled).
    GpuTimer(int frames_in_flight = 4, int calls_per_frame = 512);

    // Names a pass. The same name always gives the same id; call at start-up.
    PassId pass(std::string_view name);
    // Names a pass that runs only inside `within`'s scope (above): timed apart only with detail. The
    // same name always gives the same id; naming it again within another pass, or within a pass that
    // is itself within one, is an Error. `within` must be a pass named before (an id from pass()).
    PassId pass(std::string_view name, PassId within);
    const std::string& name(PassId id) const { return passes_[id.index].name; }
    // Whether passes named within others take timestamps of their own (default: no).
    void set_detail(bool on) { detail_ = on; }
    bool detail() const { return detail_; }
    // Per pass (by PassId index): the calls a pass within another made untimed (detail off) in the
    // frames read back since the last reset_samples(), as frame_ms() counts frames (a frame the timer
    // skipped counts none; a pass of its own none either: its calls are in its samples).
    std::vector<std::uint64_t> untimed_calls() const;

    // Collects the frames whose results are available (never waits), then opens frame
    // `frames_begun()`: timed when its slot is free, otherwise skipped (counted).
    void begin_frame();
    void end_frame();
    std::uint32_t begin(PassId id);   // use Scope instead; returns the pair's first query, or kUntimed
    void end(std::uint32_t begin_query);
    static constexpr std::uint32_t kUntimed = 0xFFFFFFFFu;   // begin() in a skipped frame

    // Collects, oldest first, the frames whose results are available; never waits. Returns how many.
    std::size_t poll();
    // Waits for every outstanding query and collects it. End of a run and tests only.
    void drain();
    // Forgets all samples so far (e.g. after warm-up frames); keeps the pass names.
    void reset_samples();

    const std::vector<PassSamples>& passes() const { return passes_; }
    // Pass indices in the order their first samples came back: the order they run in a frame.
    const std::vector<std::uint16_t>& first_use_order() const { return order_; }
    const std::vector<double>& frame_ms() const { return frame_ms_; }   // GPU span of each frame read back
    const std::vector<std::uint64_t>& frame_numbers() const { return frame_numbers_; }   // of each, in order
    // Per pass (by PassId index): its ms in the frame read back last, 0 where it did not run then. What
    // the window's overlay shows: results that came back frames late, never waited for.
    const std::vector<double>& last_frame_ms() const { return scratch_ms_; }
    static constexpr std::size_t kMaxFrames = 65536;   // history kept; the older half goes when it fills
    std::uint64_t frames_read() const { return frame_ms_.size(); }
    std::uint64_t frames_begun() const { return frame_; }
    // Frames not timed because the ring was full at their begin_frame() (since the last reset_samples()).
    std::uint64_t skipped_frames() const { return skipped_; }
    std::size_t depth() const { return slots_.size(); }

    // RAII scope of one pass: debug group + timestamp pair.
    class Scope {
    public:
        Scope(GpuTimer& t, PassId id);
        ~Scope();
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        GpuTimer& timer_;
        std::uint32_t query_;
        int outer_;   // the pass open around this one (GpuTimer::open_), restored at its end
    };
    Scope scope(PassId id) { return Scope(*this, id); }

private:
    struct Record {
        std::uint16_t pass;
        std::uint32_t query;   // index of the begin query in the slot; end is query + 1
    };
    struct Slot {
        gl::Queries queries;
        std::vector<Record> records;   // reserved once; cleared, never shrunk
        std::vector<std::uint32_t> untimed;   // per pass: calls untimed this frame (sized by pass())
        std::uint64_t frame = 0;       // the frame whose queries these are
        bool pending = false;          // ended, not yet collected
    };
    // Whether every query of `s` has its result (GL_QUERY_RESULT_AVAILABLE; asks, never waits).
    bool available(const Slot& s) const;
    void collect(Slot& s);   // reads with GL_QUERY_RESULT: call when available(), or to wait (drain)

    std::vector<PassSamples> passes_;
    std::vector<std::uint16_t> order_;
    std::vector<Slot> slots_;
    std::vector<double> frame_ms_;
    std::vector<std::uint64_t> frame_numbers_;
    std::vector<double> scratch_ms_;   // per pass, for one frame: the last one read back
    std::vector<int> scratch_calls_;
    bool detail_ = false;
    int open_ = -1;   // the innermost open Scope's pass, or -1: the one GL errors are named after
    std::size_t current_ = 0;
    std::size_t max_calls_;   // initial pool per slot, in timestamp pairs
    std::size_t next_ = 0;     // the slot the next timed frame takes; slots fill in ring order
    std::uint64_t frame_ = 0;
    std::uint64_t skipped_ = 0;
    bool in_frame_ = false;
    bool timed_ = false;       // the open frame has a slot
};

}  // namespace ranryu::profile
