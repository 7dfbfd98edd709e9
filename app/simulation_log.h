#pragma once
// What the simulation did over a run, for the commands' reports (record, profile, run).
#include <chrono>
#include <optional>
#include <string>

#include "frame/pipeline.h"
#include "profile/report.h"

namespace ranryu::app {

// The summary of what the simulation did from the frame `from` on, fed by the fluid's records, and
// (--records) every record as a CSV row.
class SimulationLog {
public:
    SimulationLog(frame::Pipeline& p, std::uint64_t from, const std::string& records = {}) : from_(from) {
        if (sim::Simulation* sim = p.simulation()) {
            summary_.emplace();
            summary_->solver = scene::solver_name(p.scene().sph.solver);
            if (!records.empty()) csv_ = profile::record_csv_header();
            sim->fluid().set_record_sink([this, keep = !records.empty()](const gpu::StepState& r) {
                if (r.frame >= from_) summary_->add(r);
                else summary_->start_time = r.time;
                if (keep) csv_ += profile::record_csv_row(r);
            });
        }
    }
    // A run resumed from a checkpoint (frame/checkpoint.h) at `frame`, simulated time `time`: its
    // summary counts from there.
    void resume_at(std::uint64_t frame, double time) {
        from_ = std::max(from_, frame);
        if (summary_) summary_->start_time = time;
    }
    // Writes the rows (after the run: not the frame path).
    void write_records(const std::string& path) const {
        if (!path.empty()) profile::write_text_file(path, csv_, "--records " + path);
    }
    void start_clock() { start_ = std::chrono::steady_clock::now(); }
    void stop_clock() {
        if (summary_) summary_->wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    const std::optional<profile::SimulationSummary>& summary() const { return summary_; }

private:
    std::uint64_t from_;
    std::optional<profile::SimulationSummary> summary_;
    std::string csv_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace ranryu::app
