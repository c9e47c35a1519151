// arena-replay: re-simulates a recorded session and checks every recorded hash.
// Exit codes: 0 every hash matched; 1 a hash did not match (the line names the tick);
// 2 usage error, or a file that cannot be read, is corrupted, cut short, or from another
// version (the line names the byte offset). See server/replay/README.md.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <optional>
#include <string>

#include "server/cli_helpers.hpp"
#include "server/config/scoreboard_json.hpp"
#include "server/replay/replayer.hpp"

using namespace arena;

namespace {

constexpr int exit_match = 0;
constexpr int exit_mismatch = 1;
constexpr int exit_error = 2;

void print_state(const world::world& w) {
    std::printf("id,owner,x,y,vx,vy,angle,omega,mass,radius,impulse_cooldown\n");
    // %.9g: enough digits that every float reads back to the same bits.
    for (const world::body& b : w.bodies()) {
        std::printf("%" PRIu32 ",%" PRIu32 ",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%" PRIu32 "\n", b.id, b.owner,
                    b.position.x(), b.position.y(), b.velocity.x(), b.velocity.y(), b.angle, b.angular_velocity, b.mass,
                    b.radius, b.impulse_cooldown);
    }
}

void print_summary(std::FILE* out, const replay::header& h, const replay::replay_report& r, double seconds) {
    const double rate = r.ticks_replayed / (seconds > 1e-9 ? seconds : 1e-9);
    std::fprintf(out, "preset=%s\n", h.preset.c_str());
    std::fprintf(out, "seed=%" PRIu64 "\n", h.seed);
    std::fprintf(out, "start_tick=%" PRIu32 "\n", r.start_tick);
    std::fprintf(out, "final_tick=%" PRIu32 "\n", r.final_tick);
    std::fprintf(out, "ticks_replayed=%" PRIu32 "\n", r.ticks_replayed);
    std::fprintf(out, "hashes_checked=%" PRIu32 "\n", r.hashes_checked);
    std::fprintf(out, "final_hash=%016" PRIx64 "\n", r.final_hash);
    std::fprintf(out, "ticks_per_second=%.0f\n", rate);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"arena-replay: re-simulate a recorded Arena session and check every recorded hash", "arena-replay"};
    std::string path;
    bool dump_hashes = false, state = false, scoreboard = false;
    uint32_t until = 0;
    app.add_option("file", path, "replay file written by arena-server --record")->required();
    app.add_flag("--dump-hashes", dump_hashes,
                 "print tick,hash (16 hex digits) for the start tick and every tick after");
    auto* until_opt = app.add_option("--until", until, "stop when the world reaches this tick");
    app.add_flag("--state", state, "print every body where the replay stops (see --until), as CSV");
    app.add_flag("--scoreboard", scoreboard,
                 "print the game's scoreboard where the replay stops, as JSON (what --stats-json's scoreboard holds, "
                 "names included; recordings made before names were recorded give \"\")");
    if (int code = cli::parse_or_exit_code(app, argc, argv); code >= 0) return code;

    auto opened = replay::replayer::open(path);
    if (!opened) {
        std::fprintf(stderr, "arena-replay: %s\n", opened.error.c_str());
        return exit_error;
    }
    replay::replayer& rp = *opened.value;

    replay::replay_options options;
    if (until_opt->count() > 0) options.until = until;
    if (dump_hashes) {
        std::printf("tick,hash\n");
        options.on_tick = [](uint32_t tick, uint64_t hash) {
            std::printf("%" PRIu32 ",%016" PRIx64 "\n", tick, hash);
        };
    }
    const auto start = std::chrono::steady_clock::now();
    const replay::replay_report report = rp.run(options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    if (state) print_state(rp.state());
    if (scoreboard) {
        const std::vector<rules::score_line> lines = rp.game_rules().scoreboard();
        const protocol::game_manifest game = rp.game_rules().manifest();
        std::printf("%s\n", config::scoreboard_json(lines, rp.scoreboard_names(lines), &game).c_str());
    }
    // stdout is data when --dump-hashes, --state or --scoreboard asked for some; the summary then goes to stderr.
    print_summary(dump_hashes || state || scoreboard ? stderr : stdout, rp.file_header(), report, seconds);
    std::fflush(stdout);
    if (report.mismatch) {
        const replay::hash_mismatch& m = *report.mismatch;
        std::fprintf(stderr,
                     "arena-replay: %s: tick %" PRIu32 ": hash mismatch: expected %016" PRIx64 ", actual %016" PRIx64
                     "\n",
                     path.c_str(), m.tick, m.expected, m.actual);
        return exit_mismatch;
    }
    if (!report.error.empty()) {
        std::fprintf(stderr, "arena-replay: %s\n", report.error.c_str());
        return exit_error;
    }
    return exit_match;
}
