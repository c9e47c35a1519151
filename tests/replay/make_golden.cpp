// arena-make-golden: writes a golden recording that tests/replay replays (a scripted 600-tick
// session with five players, see scripted_session.hpp): asteroids by default, or the world
// preset named second (`pyramid`: the sub-stepped solver). Regenerate one only when the
// physics change on purpose, in the same commit, and say why (server/replay/README.md).
#include <cinttypes>
#include <cstdio>

#include "scripted_session.hpp"

int main(int argc, char** argv) {
    if (argc != 2 && argc != 3) {
        std::fprintf(stderr, "usage: arena-make-golden OUT.arpl [PRESET]\n");
        return 2;
    }
    arena::replay::testing::session_script script;
    if (argc == 3) script.preset = argv[2];
    const auto result = arena::replay::testing::record_scripted_session(argv[1], script);
    if (!result) {
        std::fprintf(stderr, "arena-make-golden: %s\n", result.error.c_str());
        return 1;
    }
    std::printf("wrote %s: final_tick=%" PRIu32 " final_hash=%016" PRIx64 "\n", argv[1], result.value.final_tick,
                result.value.final_hash);
    std::printf("now set its final hash in tests/replay/golden_tests.cpp to 0x%016" PRIx64 "\n",
                result.value.final_hash);
    return 0;
}
