#include "server/host/match_registry.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <exception>
#include <random>

namespace arena::host {

using protocol::RejectCode;

registry_options one_match(const match::match_config& config, const world::world_config& world) {
    registry_options r;
    r.base = config;
    r.modes = {config::mode{"custom", world, config.preset, 0, 0}};
    r.default_mode = "custom";
    return r;
}

match_registry::match_registry(registry_options options, match::logger::sink log, match::token_check check_token)
    : options_(std::move(options)), log_(std::move(log)), check_token_(std::move(check_token)) {
    if (options_.threads > 1) pool_ = std::make_unique<tick_pool>(options_.threads);
    const config::mode* mode = config::find_mode(options_.modes, options_.default_mode);
    if (!mode) throw std::invalid_argument("the default mode '" + options_.default_mode + "' is not a mode");
    default_ = &start(*mode, false, true);
}

hosted_match& match_registry::start(const config::mode& mode, bool on_demand, bool listed, std::string id) {
    const uint64_t key = next_key_++;
    if (id.empty()) id = key == 0 ? std::string(default_match_id) : new_id();
    match::match_config config = options_.base;
    config.preset = mode.preset;
    config.match_id = id;
    config.mode = mode.name;
    if (mode.max_players != 0) config.admission.max_players = mode.max_players;
    // The default match logs as a server of one match always did; another names itself.
    match::logger logger;
    if (log_) {
        logger = key == 0 ? match::logger(log_) : match::logger([sink = log_, id](std::string_view line) {
            sink("match=" + id + " " + std::string(line));
        });
    }
    auto game = std::make_unique<match::match>(config, mode.world, std::move(logger), check_token_);
    hosted_match entry;
    entry.key = key;
    entry.id = id;
    entry.mode = mode.name;
    entry.on_demand = on_demand;
    entry.listed = listed;
    entry.created_unix_ms = options_.wall_clock_ms ? options_.wall_clock_ms() : 0;
    if (mode.duration_s > 0)
        entry.end_tick = std::max<uint32_t>(1, static_cast<uint32_t>(mode.duration_s * config.tick_rate));
    entry.game = std::move(game);
    ++created_;
    hosted_match& added = matches_.emplace(key, std::move(entry)).first->second;
    index_.push_back({key, &added, added.game.get()});  // keys only grow: the index stays in order
    return added;
}

std::string match_registry::new_id() {
    // 64 bits from the system's entropy: a private match's id is its invitation, so it must
    // not be guessed from the ids the lobby lists.
    std::random_device entropy;
    const uint64_t bits = (static_cast<uint64_t>(entropy()) << 32) ^ entropy();
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(bits));
    return text;
}

hosted_match* match_registry::find(std::string_view id) {
    for (auto& [key, m] : matches_)
        if (m.id == id) return &m;
    return nullptr;
}

match::match& match_registry::match_of(const match::connection& c) {
    const auto it = std::lower_bound(index_.begin(), index_.end(), c.match_key,
                                     [](const indexed_match& m, uint64_t key) { return m.key < key; });
    return it == index_.end() || it->key != c.match_key ? *default_->game : *it->game;
}

bool match_registry::reclaim_empty() {
    auto longest = matches_.end();
    for (auto it = matches_.begin(); it != matches_.end(); ++it)
        if (it->second.on_demand && it->second.empty_ticks >= options_.reclaim_empty_ticks &&
            (longest == matches_.end() || it->second.empty_ticks > longest->second.empty_ticks))
            longest = it;
    if (longest == matches_.end()) return false;
    end(longest, "match ended (empty, its slot given to a new match)");
    return true;
}

namespace {

bool valid_match_id(std::string_view id) {
    if (id.empty() || id.size() > 64) return false;
    for (const char c : id)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') return false;
    return true;
}

}  // namespace

std::variant<hosted_match*, match::rejection> match_registry::create(std::string_view mode_name, bool listed,
                                                                     std::string_view creator, std::string_view id) {
    if (!id.empty() && (!valid_match_id(id) || find(id)))
        return match::rejection{RejectCode::bad_request, find(id)
                                                             ? "a match named '" + std::string(id) + "' already runs"
                                                             : "a match id is 1 to 64 of A-Z, a-z, 0-9, '_' and '-'"};
    const config::mode* mode = config::find_mode(options_.modes, mode_name);
    if (!mode)
        return match::rejection{RejectCode::mode_unknown, "no mode '" + std::string(mode_name.substr(0, 64)) +
                                                              "' (modes: " + config::mode_names(options_.modes) + ")"};
    if (!creator.empty()) {
        // Matches in play are what a server is for, whoever created them (one address may be a
        // whole office behind NAT, or a load test); empty ones only hold slots.
        size_t empty = 0;
        for (const auto& [key, m] : matches_) empty += m.creator == creator && m.game->connection_count() == 0 ? 1 : 0;
        if (empty >= options_.max_matches_per_address)
            return match::rejection{RejectCode::no_room_for_match,
                                    "this address created " + std::to_string(empty) +
                                        " matches that are still empty, as many as one address may"};
    }
    if (matches_.size() >= options_.max_matches && !reclaim_empty())
        return match::rejection{RejectCode::no_room_for_match, "the server holds as many matches as it may (" +
                                                                   std::to_string(options_.max_matches) + ")"};
    try {
        hosted_match& m = start(*mode, true, listed, std::string(id));
        m.creator = std::string(creator);
        if (started_) started_(m);
        if (log_) log_("match created id=" + m.id + " mode=" + m.mode + (listed ? "" : " private"));
        return &m;
    } catch (const std::exception& e) {
        if (log_) log_("match of mode " + mode->name + " did not start: " + e.what());
        return match::rejection{RejectCode::no_room_for_match,
                                "a match of mode '" + mode->name + "' did not start: " + e.what()};
    }
}

hosted_match* match_registry::fullest_with_seat(std::string_view mode, const protocol::hello_msg& hello) {
    hosted_match* best = nullptr;
    for (auto& [key, m] : matches_) {
        if (m.mode != mode || !m.listed || m.game->draining() || m.game->over()) continue;
        if (m.game->seat_refusal(hello)) continue;
        // The fullest first (a seat goes where it completes a match soonest), then the oldest.
        if (!best || m.game->live_player_count() > best->game->live_player_count()) best = &m;
    }
    return best;
}

match::match* match_registry::route_hello(match::connection& c, const protocol::hello_msg& hello) {
    match::match& current = match_of(c);
    // A signed token that names a match takes its player there when the Hello names none: an
    // allocator that made the match and the token need not tell the client the id as well.
    std::string wanted = hello.match;
    if (wanted.empty() && !hello.token.empty() && check_token_)
        if (auto signed_for = check_token_(hello.token)) wanted = signed_for.value.match;
    // A second Hello stays where it is, for its match to refuse it.
    if ((wanted.empty() && hello.mode.empty()) || !current.waiting_for_hello(c)) return &current;
    // The Hello's own rules first (version, name, token, lengths), so that a bad Hello is
    // refused for what it is, whatever it asks to join.
    if (auto no = current.seat_refusal(hello, false); no && no->code != RejectCode::server_full) {
        current.reject(c, *no);
        return nullptr;
    }
    hosted_match* target = nullptr;
    if (!wanted.empty()) {
        target = find(wanted);
        if (!target || target->game->draining()) {
            current.reject(c, {RejectCode::no_such_match, "no match '" + wanted + "' on this server"});
            return nullptr;
        }
        if (!hello.mode.empty() && hello.mode != target->mode) {
            current.reject(
                c, {RejectCode::no_such_match, "match '" + wanted + "' plays " + target->mode + ", not " + hello.mode});
            return nullptr;
        }
        if (auto no = target->game->seat_refusal(hello)) {
            if (no->code == RejectCode::server_full) no->code = RejectCode::match_full;
            current.reject(c, *no);
            return nullptr;
        }
    } else {
        target = fullest_with_seat(hello.mode, hello);
        if (!target) {
            auto made = create(hello.mode, true, c.address());
            if (auto* no = std::get_if<match::rejection>(&made)) {
                current.reject(c, *no);
                return nullptr;
            }
            target = std::get<hosted_match*>(made);
        }
    }
    if (target->game.get() == &current) return &current;
    current.release(c);
    c.match_key = target->key;
    if (!target->game->connect(c)) return nullptr;  // refused: its Reject is on its way
    return target->game.get();
}

void match_registry::tick_all(const std::function<int64_t()>& now_ns,
                              const std::function<void(const hosted_match&, int64_t)>& ticked) {
    // Each match's tick is its own: it reads and writes nothing of another's, so the matches
    // tick in any order or at once with the same results (docs/DETERMINISM.md).
    struct outcome {
        hosted_match* m = nullptr;
        int64_t spent = 0;
        std::exception_ptr failure{};
        match::outbox out{};
    };
    std::vector<outcome> outcomes;
    outcomes.reserve(matches_.size());
    for (const indexed_match& m : index_) outcomes.push_back({m.hosted});
    auto tick_one = [&](size_t i, bool deferred) {
        outcome& o = outcomes[i];
        match::match& game = *o.m->game;
        if (deferred) game.defer_output(&o.out);
        const int64_t begin = now_ns();
        try {
            game.tick();
        } catch (...) {
            o.failure = std::current_exception();
        }
        o.spent = now_ns() - begin;
        game.defer_output(nullptr);
    };
    if (pool_ && outcomes.size() > 1) {
        pool_->run(outcomes.size(), [&](size_t i) { tick_one(i, true); });
    } else {
        for (size_t i = 0; i < outcomes.size(); ++i) tick_one(i, false);
    }
    // Back on the calling thread: what the matches said goes out, in the order of the matches.
    std::vector<std::pair<uint64_t, std::string>> ended;
    for (outcome& o : outcomes) {
        hosted_match& m = *o.m;
        o.out.deliver();
        if (o.failure) {
            if (!m.on_demand) std::rethrow_exception(o.failure);
            try {
                std::rethrow_exception(o.failure);
            } catch (const std::exception& e) {
                ended.emplace_back(m.key, std::string("its tick failed: ") + e.what());
            } catch (...) {
                ended.emplace_back(m.key, "its tick failed");
            }
            continue;
        }
        if (ticked) ticked(m, o.spent);
        if (!m.on_demand) continue;
        m.empty_ticks = m.game->connection_count() == 0 && m.game->players_in_grace() == 0 ? m.empty_ticks + 1 : 0;
        if (m.game->over()) {
            ended.emplace_back(m.key, "match over (its rules ended it)");
        } else if (m.end_tick != 0 && m.game->state().tick() >= m.end_tick) {
            ended.emplace_back(m.key, "match over (its mode's duration reached)");
        } else if (m.empty_ticks >= options_.empty_match_ticks) {
            ended.emplace_back(m.key, "match ended (empty)");
        }
    }
    for (const auto& [key, why] : ended) end(matches_.find(key), why);
}

void match_registry::end(std::map<uint64_t, hosted_match>::iterator it, const std::string& why) {
    hosted_match& m = it->second;
    if (log_) log_("match ended id=" + m.id + " mode=" + m.mode + ": " + why);
    try {
        m.game->shut_down(why);  // the Bye, with the result when its rules keep score
    } catch (const std::exception& e) {
        if (log_) log_("match id=" + m.id + " failed to say Bye: " + e.what());
    }
    if (ending_) ending_(m, why);
    if (ended_.size() >= max_summaries) ended_.erase(ended_.begin());
    try {
        ended_.push_back(summary_of(m, why));
    } catch (const std::exception&) {
        // Its rules cannot say their scoreboard.
        ended_.push_back({m.id, m.mode, why, {}, {}, 0, m.ticks_late, m.ticks_dropped});
    }
    std::erase_if(index_, [key = it->first](const indexed_match& m) { return m.key == key; });
    matches_.erase(it);
}

void match_registry::observe(std::function<void(hosted_match&)> started,
                             std::function<void(hosted_match&, const std::string&)> ending) {
    started_ = std::move(started);
    ending_ = std::move(ending);
    if (started_)
        for (auto& [key, m] : matches_) started_(m);
}

std::string match_registry::default_match_over() const {
    if (default_->game->over())
        return default_->game->game_rules().finished() ? "match over (its rules ended it)"
                                                       : "match over (--score-limit reached)";
    if (default_->end_tick != 0 && default_->game->state().tick() >= default_->end_tick)
        return "match over (its mode's duration reached)";
    return "";
}

void match_registry::shut_down(std::string_view reason) {
    for (auto& [key, m] : matches_) m.game->shut_down(reason);
}

match_summary match_registry::summary_of(const hosted_match& m, std::string ended) const {
    const bool scored = m.game->game_rules().has_state();
    return {m.id,
            m.mode,
            std::move(ended),
            m.game->counters(),
            m.game->scoreboard(),
            scored ? m.game->game_rules().winner() : 0,
            m.ticks_late,
            m.ticks_dropped};
}

void match_registry::count_late_ticks(uint64_t late, uint64_t dropped) {
    for (auto& [key, m] : matches_) {
        m.ticks_late += late;
        m.ticks_dropped += dropped;
    }
}

std::vector<match_summary> match_registry::summaries() const {
    std::vector<match_summary> all;
    for (const auto& [key, m] : matches_) all.push_back(summary_of(m, ""));
    all.insert(all.end(), ended_.begin(), ended_.end());
    return all;
}

}  // namespace arena::host
