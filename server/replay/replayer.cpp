#include "server/replay/replayer.hpp"

#include <utility>

#include "games/registry.hpp"

namespace arena::replay {

replayer::replayer(reader r, const world::world_config& config, uint64_t seed)
    : reader_(std::move(r)), world_(config, seed), rules_(games::make_rules(world_)) {}

protocol::result<std::unique_ptr<replayer>> replayer::open(const std::string& path) {
    using r = protocol::result<std::unique_ptr<replayer>>;
    auto opened = reader::open(path);
    if (!opened) return r::failure(opened.error);
    const world::world_config config = opened.value.config();
    const uint64_t seed = opened.value.file_header().seed;
    std::unique_ptr<replayer> rp(new replayer(std::move(opened.value), config, seed));
    while (rp->world_.tick() < rp->file_header().start_tick) rp->world_.step({});
    return r::success(std::move(rp));
}

replay_report replayer::run(const replay_options& options) {
    replay_report report;
    report.start_tick = world_.tick();
    const auto finish = [&](replay_report& rep) -> replay_report {
        rep.final_tick = world_.tick();
        rep.final_hash = rules::state_hash(world_, *rules_);
        if (rep.mismatch) failed_hash_ = rep.mismatch;
        return rep;
    };
    const auto file_problem = [&](replay_report& rep, std::string error) -> replay_report {
        failed_file_ = error;
        rep.error = std::move(error);
        return finish(rep);
    };
    // Each recorded hash is compared with the world now; false on a mismatch. The start hash
    // is the world's alone (make_header); the rules' state joins it from the first step.
    const auto check = [&](uint32_t tick, uint64_t expected) {
        ++report.hashes_checked;
        const uint64_t actual =
            world_.tick() == file_header().start_tick ? world_.hash() : rules::state_hash(world_, *rules_);
        if (actual != expected) report.mismatch = hash_mismatch{tick, expected, actual};
        return actual == expected;
    };

    if (failed_hash_ || !failed_file_.empty()) {
        report.mismatch = failed_hash_;
        report.error = failed_file_;
        return finish(report);
    }
    if (options.until && *options.until < report.start_tick) {
        report.error = "tick " + std::to_string(*options.until) +
                       (start_checked_ ? " is before the replay's tick " : " is before the recording's start tick ") +
                       std::to_string(report.start_tick);
        return finish(report);
    }
    if (!start_checked_) {
        start_checked_ = true;
        if (!check(report.start_tick, file_header().start_hash)) return finish(report);
        if (options.on_tick) options.on_tick(world_.tick(), world_.hash());
    }
    // The recording ended at `end_tick`: an `until` past it cannot be reached.
    const auto ended_at = [&](uint32_t end_tick) -> replay_report {
        if (options.until && *options.until > end_tick) {
            report.error = "tick " + std::to_string(*options.until) + " is after the recording's end at tick " +
                           std::to_string(end_tick);
            return finish(report);
        }
        report.complete = true;
        return finish(report);
    };
    if (ended_) return ended_at(world_.tick());

    const auto reached_until = [&] {
        return options.until && world_.tick() == *options.until;
    };
    for (;;) {
        protocol::result<entry> next;
        if (pending_) {
            next = protocol::result<entry>::success(std::move(*pending_));
            pending_.reset();
        } else {
            next = reader_.next();
        }
        // Past `until`, what is asked for is in hand: a problem further on (a recording cut
        // short by a crash, the usual reason to look at a state) does not take it away.
        if (!next && reached_until()) break;
        if (!next) return file_problem(report, next.error);
        if (auto* t = std::get_if<match::tick_record>(&next.value)) {
            // `until` stops before the next step, once that tick's Hash record (if any) is
            // checked; the tick read is kept for the next run.
            if (reached_until()) {
                pending_ = std::move(*t);
                break;
            }
            match::apply_tick(world_, *rules_, *t);
            for (size_t k = 0; k < t->join_names.size() && k < t->joins.size(); ++k)
                names_[t->joins[k].value()] = t->join_names[k];
            ++report.ticks_replayed;
            if (options.on_tick) options.on_tick(world_.tick(), rules::state_hash(world_, *rules_));
        } else if (auto* c = std::get_if<hash_check>(&next.value)) {
            if (!check(c->tick, c->hash)) return finish(report);
        } else {
            const end_marker& e = std::get<end_marker>(next.value);
            if (!check(e.tick, e.hash)) return finish(report);
            ended_ = true;
            return ended_at(e.tick);
        }
    }
    report.complete = true;
    return finish(report);
}

std::vector<std::string> replayer::scoreboard_names(std::span<const rules::score_line> lines) const {
    std::vector<std::string> out;
    out.reserve(lines.size());
    for (const rules::score_line& line : lines) {
        const auto it = names_.find(line.player);
        out.push_back(it == names_.end() ? std::string() : it->second);
    }
    return out;
}

}  // namespace arena::replay
