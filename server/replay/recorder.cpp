#include "server/replay/recorder.hpp"

#include <utility>

namespace arena::replay {

namespace {
// Besides the once-a-second flush, a burst of large ticks (thousands of joins) is written
// before the buffer grows past this many bytes.
constexpr size_t max_buffered_bytes = 1u << 20;
}  // namespace

protocol::result<recorder> recorder::open(const std::string& path, const header& h) {
    using r = protocol::result<recorder>;
    if (h.tick_rate == 0) return r::failure(path + ": header: tick_rate must be above 0");
    if (h.hash_interval == 0) return r::failure(path + ": header: hash_interval must be above 0");
    recorder rec;
    rec.path_ = path;
    rec.file_.reset(std::fopen(path.c_str(), "wb"));
    if (!rec.file_) return r::failure(io_error(path, "cannot create the replay file"));
    rec.next_tick_ = h.start_tick;
    rec.tick_rate_ = h.tick_rate;
    rec.hash_interval_ = h.hash_interval;
    rec.encoder_.append(h, rec.buffer_);
    if (status s = rec.flush(); !s) return r::failure(s.error);
    return r::success(std::move(rec));
}

recorder::recorder(recorder&& other) noexcept {
    *this = std::move(other);
}

recorder& recorder::operator=(recorder&& other) noexcept {
    if (this != &other) {
        flush_quietly();  // what this recorder held must not vanish with the assignment
        path_ = std::move(other.path_);
        file_ = std::move(other.file_);
        encoder_ = std::move(other.encoder_);
        buffer_ = std::move(other.buffer_);
        other.buffer_.clear();
        next_tick_ = other.next_tick_;
        tick_rate_ = other.tick_rate_;
        hash_interval_ = other.hash_interval_;
        ticks_since_flush_ = other.ticks_since_flush_;
        error_ = std::move(other.error_);
    }
    return *this;
}

recorder::~recorder() {
    flush_quietly();
}

void recorder::flush_quietly() noexcept {
    // A destructor cannot report; the bytes are written if the disk takes them.
    if (file_ && error_.empty() && !buffer_.empty()) {
        std::fwrite(buffer_.data(), 1, buffer_.size(), file_.get());
        std::fflush(file_.get());
    }
    buffer_.clear();
}

status recorder::flush() {
    if (!error_.empty()) return status::failure(error_);
    if (!file_) return status::failure("replay recorder is not open");
    if (!buffer_.empty() && std::fwrite(buffer_.data(), 1, buffer_.size(), file_.get()) != buffer_.size()) {
        error_ = io_error(path_, "write failed");
    } else if (std::fflush(file_.get()) != 0) {
        error_ = io_error(path_, "write failed");
    }
    buffer_.clear();
    ticks_since_flush_ = 0;
    if (!error_.empty()) return status::failure(error_);
    return ok_status();
}

status recorder::record_tick(const match::tick_record& record, uint64_t hash_after_step) {
    if (!error_.empty()) return status::failure(error_);
    if (!file_) return status::failure("replay recorder is not open");
    if (record.tick != next_tick_) {
        return status::failure(path_ + ": tick " + std::to_string(record.tick) + " recorded where tick " +
                               std::to_string(next_tick_) + " was due: ticks must be recorded one after another");
    }
    encoder_.append(record, buffer_);
    next_tick_ = record.tick + 1;  // the world's tick after the step
    if (next_tick_ % hash_interval_ == 0) encoder_.append(hash_check{next_tick_, hash_after_step}, buffer_);
    ++ticks_since_flush_;
    if (ticks_since_flush_ >= tick_rate_ || buffer_.size() >= max_buffered_bytes) return flush();
    return ok_status();
}

status recorder::finish(uint32_t final_tick, uint64_t final_hash) {
    if (!error_.empty()) return status::failure(error_);
    if (!file_) return status::failure("replay recorder is not open");
    if (final_tick != next_tick_) {
        return status::failure(path_ + ": finish at tick " + std::to_string(final_tick) +
                               ", but the recorded ticks end at tick " + std::to_string(next_tick_));
    }
    encoder_.append(end_marker{final_tick, final_hash}, buffer_);
    status s = flush();
    if (s && std::fclose(file_.release()) != 0) {
        error_ = io_error(path_, "close failed");
        return status::failure(error_);
    }
    file_.reset();
    return s;
}

}  // namespace arena::replay
