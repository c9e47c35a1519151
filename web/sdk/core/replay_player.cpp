#include "web/sdk/core/replay_player.hpp"

#include <algorithm>
#include <variant>

#include "server/replay/reader.hpp"

namespace arena::sdk {

protocol::result<std::unique_ptr<replay_player>> replay_player::open(const std::string& path) {
    using r = protocol::result<std::unique_ptr<replay_player>>;
    auto read = replay::reader::open(path);
    if (!read) return r::failure(read.error);
    std::unique_ptr<replay_player> p(new replay_player);
    p->path_ = path;
    p->start_tick_ = read.value.file_header().start_tick;
    p->end_tick_ = p->start_tick_;
    p->recorded_.push_back({p->start_tick_, read.value.file_header().start_hash});
    for (;;) {
        auto next = read.value.next();
        // A file the server is still writing, or that a crash cut short, plays up to its
        // last complete Tick record.
        if (!next) {
            p->cut_short_ = next.error;
            break;
        }
        if (const auto* t = std::get_if<match::tick_record>(&next.value)) {
            p->end_tick_ = t->tick + 1;
        } else if (const auto* c = std::get_if<replay::hash_check>(&next.value)) {
            p->recorded_.push_back({c->tick, c->hash});
        } else if (const auto* e = std::get_if<replay::end_marker>(&next.value)) {
            p->recorded_.push_back({e->tick, e->hash});  // after a Hash record of the same tick, maybe
            break;
        }
    }
    if (!p->restart()) return r::failure(p->error_);
    return r::success(std::move(p));
}

bool replay_player::restart() {
    auto opened = replay::replayer::open(path_);
    if (!opened) {
        error_ = opened.error;
        return false;
    }
    replayer_ = std::move(opened.value);
    manifest_ = replayer_->game_rules().manifest();
    events_.clear();
    events_seen_ = 0;
    hashes_checked_ = 0;
    mismatch_.reset();
    error_.clear();
    return run_until(start_tick_);
}

bool replay_player::run_until(uint32_t tick) {
    replay::replay_options options;
    options.until = tick;
    options.on_tick = [this](uint32_t now, uint64_t hash) {
        hash_ = hash;
        // Called for the start state too, before any step: no rules have run there.
        if (now == start_tick_) return;
        for (const rules::declared_event& e : replayer_->game_rules().declared_events()) {
            events_.push_back({++events_seen_, now, e});
            if (events_.size() > max_logged_events) events_.pop_front();
        }
    };
    const replay::replay_report report = replayer_->run(options);
    hashes_checked_ += report.hashes_checked;
    mismatch_ = report.mismatch;
    error_ = report.error;
    return report.complete && !report.mismatch;
}

bool replay_player::step(uint32_t ticks) {
    if (mismatch_ || !error_.empty()) return false;
    const uint32_t now = tick();
    return run_until(static_cast<uint32_t>(std::min<uint64_t>(uint64_t{now} + ticks, end_tick_)));
}

bool replay_player::seek(uint32_t tick) {
    tick = std::clamp(tick, start_tick_, end_tick_);
    if (tick < this->tick() && !restart()) return false;
    if (mismatch_ || !error_.empty()) return false;
    return run_until(tick);
}

std::string replay_player::name_of(uint32_t id) const {
    rules::score_line line;
    line.player = id;
    return replayer_->scoreboard_names({&line, 1}).front();
}

std::optional<uint64_t> replay_player::recorded_hash() const {
    const auto at = std::lower_bound(recorded_.begin(), recorded_.end(), tick(),
                                     [](const recorded_hash_at& r, uint32_t t) { return r.tick < t; });
    if (at == recorded_.end() || at->tick != tick()) return std::nullopt;
    return at->hash;
}

}  // namespace arena::sdk
