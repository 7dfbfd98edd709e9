#include "record/gated_writer.h"

#include <algorithm>
#include <chrono>

#include "core/error.h"

namespace ranryu::record {

GatedWriter::GatedWriter(std::size_t buffers, int threads, bool gated, Write write, std::function<void()> pump)
    : write_(std::move(write)), pump_(std::move(pump)), gated_(gated), validated_end_(gated ? 0 : ~0ull) {
    for (std::size_t i = 0; i < buffers; ++i) free_.push_back(i);
    for (int i = 0; i < std::max(threads, 1); ++i) threads_.emplace_back([this] { loop(); });
}

GatedWriter::~GatedWriter() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
        discard_from_ = std::min(discard_from_, validated_end_);   // destroyed without finish(): drop the unvalidated
    }
    work_.notify_all();
    for (std::thread& t : threads_)
        if (t.joinable()) t.join();
}

std::size_t GatedWriter::acquire() {
    std::unique_lock lock(mutex_);
    while (free_.empty()) {
        if (pump_) {
            lock.unlock();
            pump_();
            lock.lock();
        }
        done_.wait_for(lock, std::chrono::milliseconds(1));
    }
    const std::size_t b = free_.back();
    free_.pop_back();
    return b;
}

void GatedWriter::submit(std::uint64_t frame, std::size_t buffer) {
    {
        std::lock_guard lock(mutex_);
        jobs_.push_back(Job{frame, buffer});
    }
    work_.notify_one();
}

void GatedWriter::release(std::size_t buffer) {
    {
        std::lock_guard lock(mutex_);
        free_.push_back(buffer);
    }
    done_.notify_all();
}

void GatedWriter::fail(const std::string& what) {
    std::lock_guard lock(mutex_);
    if (error_.empty()) error_ = what;
}

void GatedWriter::validate_through(std::uint64_t frame) {
    {
        std::lock_guard lock(mutex_);
        validated_end_ = std::max(validated_end_, frame + 1);
    }
    work_.notify_all();
}

void GatedWriter::discard_from(std::uint64_t frame) {
    {
        std::lock_guard lock(mutex_);
        discard_from_ = std::min(discard_from_, frame);
    }
    work_.notify_all();
}

void GatedWriter::loop() {
    for (;;) {
        Job job;
        {
            std::unique_lock lock(mutex_);
            // Jobs are in frame order: the front one waits for validation, or is dropped.
            for (;;) {
                while (!jobs_.empty() && jobs_.front().frame >= discard_from_) {
                    free_.push_back(jobs_.front().buffer);
                    jobs_.pop_front();
                    done_.notify_all();
                }
                if (!jobs_.empty() && jobs_.front().frame < validated_end_) break;
                if (stopping_) {   // the last validation has come: the rest never will be
                    for (const Job& j : jobs_) free_.push_back(j.buffer);
                    jobs_.clear();
                    done_.notify_all();
                    return;
                }
                work_.wait(lock);
            }
            job = jobs_.front();
            jobs_.pop_front();
        }
        std::string failure;
        try {
            write_(job.frame, job.buffer);
        } catch (const std::exception& e) {
            failure = e.what();
        }
        {
            std::lock_guard lock(mutex_);
            free_.push_back(job.buffer);
            if (failure.empty()) ++written_;
            else if (error_.empty()) error_ = failure;
        }
        done_.notify_all();
    }
}

void GatedWriter::finish() {
    {
        std::lock_guard lock(mutex_);
        if (stopping_ && threads_.empty()) return;
        stopping_ = true;
    }
    work_.notify_all();
    for (std::thread& t : threads_) t.join();
    threads_.clear();
    std::lock_guard lock(mutex_);
    if (!error_.empty()) throw Error(error_);
}

std::uint64_t GatedWriter::written() const {
    std::lock_guard lock(mutex_);
    return written_;
}

}  // namespace ranryu::record
