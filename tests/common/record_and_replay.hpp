#pragma once
// A game's record-and-replay test in one call: a scripted match recorded to a file of its own,
// then replayed from it. What each game's tests check of it (every verdict the same, the same
// final hash and scoreboard) is the same for every game.
#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "server/replay/recorder.hpp"
#include "server/replay/replayer.hpp"

namespace arena::testing {

struct replayed_match {
    replay::replay_report report;
    std::vector<rules::score_line> scoreboard;  // the replayed rules' at the end
};

// Records `play(recorder&)` (a scripted match on a world of `config` and `seed`, recording
// every tick and finishing the recording) under a header naming `preset`, replays the file and
// removes it. False `opened`: the recording could not be opened.
template <class Play>
replayed_match record_and_replay(const world::world_config& config, uint64_t seed, const std::string& preset,
                                 Play play) {
    const std::string path =
        "/tmp/arena_replay_" + preset + "_" + std::to_string(::getpid()) + "_" + std::to_string(seed) + ".arpl";
    {
        const world::world start(config, seed);  // the header's start hash is the world's alone
        auto opened = replay::recorder::open(path, replay::make_header(start, preset, seed, 60));
        if (!opened.ok()) return {};
        play(opened.value);
    }
    replayed_match out;
    auto rp = replay::replayer::open(path);
    if (rp.ok()) {
        out.report = rp.value->run();
        out.scoreboard = rp.value->game_rules().scoreboard();
    }
    std::remove(path.c_str());
    return out;
}

}  // namespace arena::testing
