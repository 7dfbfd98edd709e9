#include "profile/gpu_timer.h"

#include "gl/faults.h"

#include <algorithm>

#include "core/error.h"

namespace ranryu::profile {

GpuTimer::GpuTimer(int frames_in_flight, int max_calls_per_frame) : max_calls_(std::size_t(max_calls_per_frame)) {
    slots_.resize(std::size_t(frames_in_flight));
    for (Slot& s : slots_) {
        s.queries = gl::Queries(2 * max_calls_);
        s.records.reserve(max_calls_);
    }
    passes_.reserve(64);
    frame_ms_.reserve(4096);
    frame_numbers_.reserve(4096);
}

PassId GpuTimer::pass(std::string_view name) {
    for (std::size_t i = 0; i < passes_.size(); ++i)
        if (passes_[i].name == name) return PassId{std::uint16_t(i)};
    passes_.push_back(PassSamples{std::string(name), -1, {}, {}, {}, {}, {}});
    scratch_ms_.push_back(0.0);
    scratch_calls_.push_back(0);
    for (Slot& s : slots_) s.untimed.push_back(0);   // at start-up: the frame path never names a pass
    return PassId{std::uint16_t(passes_.size() - 1)};
}

PassId GpuTimer::pass(std::string_view name, PassId within) {
    if (within.index >= passes_.size()) throw Error("pass " + std::string(name) + " named within a pass not named");
    if (passes_[within.index].within >= 0)
        throw Error("pass " + std::string(name) + " named within " + passes_[within.index].name + ", itself within a pass: passes nest one level");
    const bool known = std::any_of(passes_.begin(), passes_.end(), [&](const PassSamples& p) { return p.name == name; });
    const PassId id = pass(name);
    PassSamples& p = passes_[id.index];
    if (known && p.within != int(within.index))
        throw Error("pass " + p.name + " named again within " + passes_[within.index].name + " (it was named " +
                    (p.within < 0 ? std::string("as a pass of its own") : "within " + passes_[std::size_t(p.within)].name) + ")");
    p.within = int(within.index);
    return id;
}

// The last pass's end first (among the last issued; nested passes end later): while the GPU is
// behind, that one answers no and nothing else is asked. The rest are asked too rather than assumed
// from it, so that collect() never waits on one that is not.
bool GpuTimer::available(const Slot& s) const {
    const auto ready = [&](std::uint32_t q) {
        GLuint yes = GL_FALSE;
        glGetQueryObjectuiv(s.queries[q], GL_QUERY_RESULT_AVAILABLE, &yes);
        return yes != GL_FALSE;
    };
    if (s.records.empty()) return true;
    if (!ready(s.records.back().query + 1u)) return false;
    for (const Record& r : s.records)
        if (!ready(r.query) || !ready(r.query + 1u)) return false;
    return true;
}

// Reads a slot's timestamps with GL_QUERY_RESULT: from poll() only once available() said yes, so
// nothing waits; from drain(), waiting is the point.
void GpuTimer::collect(Slot& s) {
    if (!s.pending) return;
    if (!s.records.empty()) {
        std::uint64_t first = ~0ull, final = 0;
        for (double& v : scratch_ms_) v = 0.0;
        for (int& c : scratch_calls_) c = 0;
        for (const Record& r : s.records) {
            GLuint64 t0 = 0, t1 = 0;
            glGetQueryObjectui64v(s.queries[r.query], GL_QUERY_RESULT, &t0);
            glGetQueryObjectui64v(s.queries[r.query + 1u], GL_QUERY_RESULT, &t1);
            if (passes_[r.pass].ms.empty() && scratch_calls_[r.pass] == 0 &&
                std::find(order_.begin(), order_.end(), r.pass) == order_.end())
                order_.push_back(r.pass);
            scratch_ms_[r.pass] += double(t1 >= t0 ? t1 - t0 : 0) * 1e-6;
            scratch_calls_[r.pass] += 1;
            first = std::min<std::uint64_t>(first, t0);
            final = std::max<std::uint64_t>(final, t1);
        }
        for (std::size_t p = 0; p < passes_.size(); ++p) {
            if (s.untimed[p]) {   // within a parent timed this frame, so with the frame read back
                passes_[p].untimed.push_back(s.untimed[p]);
                passes_[p].untimed_frames.push_back(s.frame);
            }
            if (!scratch_calls_[p]) continue;
            passes_[p].ms.push_back(scratch_ms_[p]);
            passes_[p].calls.push_back(scratch_calls_[p]);
            passes_[p].frames.push_back(s.frame);
        }
        frame_ms_.push_back(double(final - first) * 1e-6);
        frame_numbers_.push_back(s.frame);
        // An open-ended run (the window) keeps the latest kMaxFrames frames, halving the history when
        // it fills: memory stays bounded and the reallocation happens once per 32k frames, not per frame.
        if (frame_ms_.size() >= kMaxFrames) {
            const auto half = std::ptrdiff_t(kMaxFrames / 2);
            frame_ms_.erase(frame_ms_.begin(), frame_ms_.begin() + half);
            frame_numbers_.erase(frame_numbers_.begin(), frame_numbers_.begin() + half);
            for (PassSamples& p : passes_) {
                // A pass's samples are of the frames it ran in: those before the oldest frame kept go.
                const std::uint64_t oldest = frame_numbers_.front();
                const auto kept = [&](const std::vector<std::uint64_t>& f) {
                    return std::lower_bound(f.begin(), f.end(), oldest) - f.begin();
                };
                const auto drop = kept(p.frames);
                p.ms.erase(p.ms.begin(), p.ms.begin() + drop);
                p.calls.erase(p.calls.begin(), p.calls.begin() + drop);
                p.frames.erase(p.frames.begin(), p.frames.begin() + drop);
                const auto drop_untimed = kept(p.untimed_frames);
                p.untimed.erase(p.untimed.begin(), p.untimed.begin() + drop_untimed);
                p.untimed_frames.erase(p.untimed_frames.begin(), p.untimed_frames.begin() + drop_untimed);
            }
        }
    }
    s.records.clear();
    std::fill(s.untimed.begin(), s.untimed.end(), 0u);
    s.pending = false;
}

std::size_t GpuTimer::poll() {
    std::size_t n = 0;
    for (std::size_t k = 0; k < slots_.size(); ++k) {   // from the oldest slot, the one filled longest ago
        Slot& s = slots_[(next_ + k) % slots_.size()];
        if (!s.pending) continue;
        if (!available(s)) break;   // later frames stay behind it: samples come back in frame order
        collect(s);
        ++n;
    }
    return n;
}

void GpuTimer::begin_frame() {
    if (in_frame_) throw Error("GpuTimer::begin_frame inside a frame");
    poll();
    current_ = next_;
    timed_ = !slots_[current_].pending;
    if (timed_) {
        slots_[current_].frame = frame_;
        next_ = (next_ + 1) % slots_.size();
    } else {
        ++skipped_;   // the GPU is a whole ring behind: this frame goes untimed rather than wait
    }
    in_frame_ = true;
}

void GpuTimer::end_frame() {
    if (!in_frame_) throw Error("GpuTimer::end_frame outside a frame");
    if (timed_) slots_[current_].pending = true;
    in_frame_ = false;
    timed_ = false;
    ++frame_;
}

std::uint32_t GpuTimer::begin(PassId id) {
    if (!in_frame_) throw Error("pass " + name(id) + " ran outside a frame");
    if (!timed_) return kUntimed;
    if (passes_[id.index].within >= 0 && !detail_) {   // its time is its parent's (gpu_timer.h)
        ++slots_[current_].untimed[id.index];
        return kUntimed;
    }
    Slot& s = slots_[current_];
    if (2 * s.records.size() + 2 > s.queries.size()) {
        if (s.queries.size() >= (std::size_t(1) << 24)) throw Error("over 8 million timed passes in one frame");
        s.queries.grow(s.queries.size());   // a frame with more passes than any before: double the pool
        s.records.reserve(s.queries.size() / 2);
    }
    const auto q = std::uint32_t(2 * s.records.size());
    s.records.push_back(Record{id.index, q});
    glQueryCounter(s.queries[q], GL_TIMESTAMP);
    return q;
}

void GpuTimer::end(std::uint32_t begin_query) {
    if (begin_query == kUntimed) return;
    glQueryCounter(slots_[current_].queries[begin_query + 1u], GL_TIMESTAMP);
}

std::vector<std::uint64_t> GpuTimer::untimed_calls() const {
    std::vector<std::uint64_t> n(passes_.size(), 0);
    for (std::size_t p = 0; p < passes_.size(); ++p)
        for (const std::uint32_t c : passes_[p].untimed) n[p] += c;
    return n;
}

void GpuTimer::drain() {
    for (std::size_t k = 0; k < slots_.size(); ++k) collect(slots_[(next_ + k) % slots_.size()]);   // oldest first
}

void GpuTimer::reset_samples() {
    for (PassSamples& p : passes_) {
        p.ms.clear();
        p.calls.clear();
        p.frames.clear();
        p.untimed.clear();
        p.untimed_frames.clear();
    }
    order_.clear();
    frame_ms_.clear();
    frame_numbers_.clear();
    skipped_ = 0;
}

GpuTimer::Scope::Scope(GpuTimer& t, PassId id) : timer_(t), outer_(t.open_) {
    query_ = timer_.begin(id);   // throws before anything needs undoing
    const std::string& n = t.name(id);
    glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, id.index, GLsizei(n.size()), n.c_str());
    gl::check_gl_error(gl::current_pass());   // an error raised between passes is named by the one before
    gl::set_current_pass(n);
    timer_.open_ = int(id.index);
}

GpuTimer::Scope::~Scope() {
    timer_.end(query_);
    glPopDebugGroup();
    gl::check_gl_error(gl::current_pass());   // with error checks on (gl/faults.h): the pass that raised it
    // The rest of the pass this one ran within is that pass's again (a pass of its own leaves the
    // name, so that an error between passes is named by the one before, as above).
    timer_.open_ = outer_;
    if (outer_ >= 0) gl::set_current_pass(timer_.name(PassId{std::uint16_t(outer_)}));
}

}  // namespace ranryu::profile
