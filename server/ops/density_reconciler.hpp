#pragma once
// High density on Agones (many matches in one game server): the sidecar holds a Counter
// `rooms`, the number of matches in the process, and a List `players`, one value per player,
// which allocations and the fleet's autoscaler read. This is the pure half of keeping them
// true: given what the process wants and what the sidecar has confirmed, which request comes
// next. Level-triggered: it compares states, never replays events, so a lost or failed request
// is simply asked for again and an allocation that moved `rooms` behind our back is absorbed.
// No sockets and no clock (density_sync.hpp sends the requests).
#include <algorithm>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace arena::ops {

// What the process holds now.
struct density_state {
    int64_t rooms = 0;                // matches in the process, the default one included
    std::set<std::string> players{};  // one value per player of any match
    bool operator==(const density_state&) const = default;
};

// An allocation's request for a match: its GameServerAllocation's metadata annotations.
struct allocation_request {
    std::string mode{};   // arena.dev/mode ("": the default match's mode)
    std::string match{};  // arena.dev/match ("": a new random id)
};

// One request to the sidecar's REST API.
struct sidecar_call {
    enum class kind { read_rooms, change_rooms, read_players, add_player, remove_player };
    kind what = kind::read_rooms;
    int64_t diff = 0;     // change_rooms: the countDiff
    std::string value{};  // add_player, remove_player
    uint64_t epoch = 0;   // read_rooms: the GameServer version it was asked in
    bool operator==(const sidecar_call&) const = default;
};

// How the sidecar answered a call.
enum class sidecar_outcome {
    done,         // 2xx; or an add of a value already there, a remove of one already gone
    unknown_key,  // the GameServer declares no such Counter or List: stop asking
    failed,       // anything else (an error, no answer): ask again after a wait
};

class density_reconciler {
public:
    void want(density_state desired) { desired_ = std::move(desired); }
    const density_state& desired() const { return desired_; }

    // The watch showed the GameServer: the allocator may have moved `rooms` (its
    // status.counters.rooms.count, nullopt when the GameServer declares no such Counter).
    // A count other than the one confirmed means it moved: read it again before changing it,
    // since the status may also lag behind changes of ours still batched in the sidecar.
    void observed(std::optional<int64_t> rooms_count, bool players_declared) {
        if (!rooms_count) {
            rooms_known_ = false;
        } else if (rooms_known_ && confirmed_rooms_ != *rooms_count) {
            ++epoch_;
            confirmed_rooms_.reset();
        }
        if (!players_declared) players_known_ = false;
    }

    // The next request, or nothing when the sidecar holds what is wanted.
    std::optional<sidecar_call> next() const {
        using k = sidecar_call::kind;
        if (rooms_known_) {
            if (!confirmed_rooms_) return sidecar_call{k::read_rooms, 0, {}, epoch_};
            if (*confirmed_rooms_ != desired_.rooms)
                return sidecar_call{k::change_rooms, desired_.rooms - *confirmed_rooms_, {}, epoch_};
        }
        if (players_known_) {
            if (!confirmed_players_) return sidecar_call{k::read_players, 0, {}, epoch_};
            // Removals first: they free the List's capacity for the additions.
            for (const std::string& v : *confirmed_players_)
                if (!desired_.players.count(v)) return sidecar_call{k::remove_player, 0, v, epoch_};
            for (const std::string& v : desired_.players)
                if (!confirmed_players_->count(v)) return sidecar_call{k::add_player, 0, v, epoch_};
        }
        return std::nullopt;
    }

    // What the sidecar answered to `call` (a read's `count` or `values` with it).
    void answered(const sidecar_call& call, sidecar_outcome outcome, int64_t count = 0,
                  const std::vector<std::string>& values = {}) {
        using k = sidecar_call::kind;
        const bool about_rooms = call.what == k::read_rooms || call.what == k::change_rooms;
        if (outcome == sidecar_outcome::unknown_key) {
            (about_rooms ? rooms_known_ : players_known_) = false;
            return;
        }
        if (outcome != sidecar_outcome::done) return;
        switch (call.what) {
            case k::read_rooms:
                // A read sent before the GameServer last moved may predate the move.
                if (call.epoch == epoch_) confirmed_rooms_ = count;
                break;
            case k::change_rooms:
                if (confirmed_rooms_) *confirmed_rooms_ += call.diff;
                break;
            case k::read_players:
                confirmed_players_ = std::set<std::string>(values.begin(), values.end());
                break;
            case k::add_player:
                if (confirmed_players_) confirmed_players_->insert(call.value);
                break;
            case k::remove_player:
                if (confirmed_players_) confirmed_players_->erase(call.value);
                break;
        }
    }

    // Whether the sidecar is asked about these at all (false once it said it has no such key).
    bool rooms_enabled() const { return rooms_known_; }
    bool players_enabled() const { return players_known_; }
    std::optional<int64_t> confirmed_rooms() const { return confirmed_rooms_; }
    bool in_sync() const { return !next(); }

private:
    density_state desired_;
    bool rooms_known_ = true;  // until the sidecar or the GameServer says otherwise
    bool players_known_ = true;
    std::optional<int64_t> confirmed_rooms_;                  // the sidecar's count, when known
    std::optional<std::set<std::string>> confirmed_players_;  // the sidecar's values, when known
    uint64_t epoch_ = 0;  // GameServer moves seen: reads older than the last move are stale
};

}  // namespace arena::ops
