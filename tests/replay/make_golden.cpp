// arena-make-golden: writes the golden recording that tests/replay replays (a scripted
// 600-tick asteroids session with five players, see scripted_session.hpp). Regenerate it only
// when the physics change on purpose, in the same commit, and say why (server/replay/README.md).
#include <cinttypes>
#include <cstdio>

#include "scripted_session.hpp"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: arena-make-golden OUT.arpl\n");
        return 2;
    }
    const auto result = arena::replay::testing::record_scripted_session(argv[1], {});
    if (!result) {
        std::fprintf(stderr, "arena-make-golden: %s\n", result.error.c_str());
        return 1;
    }
    std::printf("wrote %s: final_tick=%" PRIu32 " final_hash=%016" PRIx64 "\n", argv[1], result.value.final_tick,
                result.value.final_hash);
    std::printf("now set golden_final_hash in tests/replay/golden_tests.cpp to 0x%016" PRIx64 "\n",
                result.value.final_hash);
    return 0;
}
