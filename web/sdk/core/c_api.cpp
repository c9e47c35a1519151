// The C API the TypeScript SDK calls (web/sdk/src/core.ts): a session with the server (the
// client core the bots run too: client_sim/session.hpp) and the replay of a recording. Plain
// extern "C" functions over integers, floats and pointers into the module's memory, so that
// the JavaScript side needs no binding library: it copies a frame in, calls, and reads the
// answer where the returned pointer says. Pointers stay valid until the next call on the same
// handle.
#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "client_sim/session.hpp"
#include "protocol/manifest.hpp"
#include "server/match/shape_wire.hpp"
#include "server/replay/replayer.hpp"
#include "web/sdk/core/replay_player.hpp"

#ifdef __EMSCRIPTEN__
#include <emscripten/emscripten.h>
#define ARENA_API extern "C" EMSCRIPTEN_KEEPALIVE
#else
#define ARENA_API extern "C" __attribute__((visibility("default")))
#endif

namespace {

// A shape as the SDK reads it: 76 bytes, every field at a 4-byte offset.
struct sdk_shape {
    std::uint32_t id;
    std::uint8_t kind;
    std::uint8_t type;  // protocol ShapeType
    std::uint8_t vertex_count;
    std::uint8_t unused;
    float radius;
    float xy[2 * arena::protocol::max_shape_vertices];
};
static_assert(sizeof(sdk_shape) == 76);

// A static body of the Welcome: its pose, then its shape. 88 bytes.
struct sdk_static {
    float x, y, angle;
    sdk_shape shape;
};
static_assert(sizeof(sdk_static) == 88);

sdk_shape to_sdk(const arena::protocol::shape_desc& d) {
    sdk_shape s{};
    s.id = d.id;
    s.kind = d.kind;
    s.type = static_cast<std::uint8_t>(d.type);
    s.vertex_count = d.vertex_count;
    s.radius = d.radius;
    std::memcpy(s.xy, d.xy.data(), sizeof(s.xy));
    return s;
}

// An own bullet (client_sim/session.hpp): body_id, sequence, x, y, vx, vy; 24 bytes.
static_assert(sizeof(arena::bots::own_bullet) == 24);

struct client {
    arena::bots::session session;
    std::vector<sdk_shape> shapes;
    std::vector<sdk_static> statics;
    std::vector<arena::bots::own_bullet> bullets;  // arena_own_bullets's
    float predicted[6] = {};
    client(bool delta, bool spectator) : session({.delta_snapshots = delta, .spectator = spectator}) {}
};

struct replay {
    std::unique_ptr<arena::replay::replayer> replayer;
    arena::replay::replay_report report;
    std::string dump;  // "tick,hash" lines, as arena-replay --dump-hashes prints them
    std::vector<arena::protocol::BodyState> bodies;
    std::string error;
    std::string final_hash;
};

// A scoreboard line of the replayed game: the player, the protocol's own columns (PlayerLine),
// its team and the game's declared values (in its manifest's player_fields order; the rest 0).
// 64 bytes, every field at a 4-byte offset.
struct sdk_line {
    std::uint32_t player;
    std::uint32_t score, kills, deaths, shots, hits, lives;
    std::uint8_t state;  // protocol PlayerState: playing 0, respawning 1, out 2
    std::uint8_t team;   // 0 in a game without teams
    std::uint8_t out;
    std::uint8_t unused;
    std::int32_t values[arena::protocol::max_game_fields];
};
static_assert(sizeof(sdk_line) == 64);

// A team's line: its number (1 is the manifest's first team), its score and the game's declared
// values (team_fields order). 40 bytes.
struct sdk_team {
    std::uint32_t team;
    std::uint32_t score;
    std::int32_t values[arena::protocol::max_game_fields];
};
static_assert(sizeof(sdk_team) == 40);

// A declared event of the log (replay_player::logged_event): its number since the start, the
// tick, its kind (the manifest's events[kind]) and values. 28 bytes.
struct sdk_event {
    std::uint32_t sequence;
    std::uint32_t tick;
    std::uint8_t kind;
    std::uint8_t unused[3];
    std::int32_t values[arena::protocol::max_event_values];
};
static_assert(sizeof(sdk_event) == 28);

struct player {
    std::unique_ptr<arena::sdk::replay_player> playing;
    std::vector<arena::protocol::BodyState> bodies;
    std::vector<sdk_shape> shapes;
    std::vector<std::uint8_t> manifest;  // encoded once: the rules declare it once
    std::vector<sdk_line> lines;
    std::vector<std::string> names;  // of `lines`, in their order
    std::vector<sdk_team> teams;
    std::vector<sdk_event> events;
    std::vector<std::uint32_t> winners;
    std::string text;  // the last hash or error asked for
    std::string name;  // the last name asked for
};

std::string open_error;  // why the last arena_replay_open or arena_player_open failed

std::string hex(std::uint64_t value) {
    char text[17];
    std::snprintf(text, sizeof(text), "%016" PRIx64, value);
    return text;
}

std::string mismatch_text(const arena::replay::hash_mismatch& m) {
    return "tick " + std::to_string(m.tick) + ": hash mismatch: expected " + hex(m.expected) + ", actual " +
           hex(m.actual);
}

std::uint32_t out_size(std::span<const std::uint8_t> frame) {
    return static_cast<std::uint32_t>(frame.size());
}

}  // namespace

// --- session ------------------------------------------------------------------------------

// spectator: join to watch (Hello.spectator), without a body; arena_input then encodes nothing.
ARENA_API client* arena_session_new(int delta_snapshots, int spectator) {
    return new client(delta_snapshots != 0, spectator != 0);
}
ARENA_API void arena_session_free(client* c) {
    delete c;
}

// One frame from the server: the payload type handled (protocol Payload), 0 when refused (the
// session ended: arena_error says why; a Reject or Bye also ends it, with its reason).
ARENA_API int arena_feed(client* c, const std::uint8_t* data, std::uint32_t size) {
    const auto type = c->session.feed({data, size});
    if (type == arena::protocol::Payload::Welcome) {
        c->statics.clear();
        for (const auto& s : c->session.statics()) c->statics.push_back({s.x, s.y, s.angle, to_sdk(s.shape)});
    } else if (type == arena::protocol::Payload::Snapshot) {
        c->shapes.clear();
        for (const auto& d : c->session.shapes()) c->shapes.push_back(to_sdk(d));
    }
    return static_cast<int>(type);
}
ARENA_API int arena_ended(const client* c) {
    return c->session.ended() ? 1 : 0;
}
ARENA_API const char* arena_error(const client* c) {
    return c->session.error().c_str();
}

// Outgoing frames: each call returns the frame's size; arena_out points at it. arena_input
// returns 0 for a tick the input pacing leaves out (client_sim/session.hpp): there is nothing to send.
ARENA_API std::uint32_t arena_hello(client* c, const char* name, const char* token) {
    return out_size(c->session.hello(name, token));
}

// The Hello that joins the match `match`, or joins or creates one of mode `mode` (either may be "").
ARENA_API std::uint32_t arena_hello_to(client* c, const char* name, const char* token, const char* match,
                                       const char* mode) {
    return out_size(c->session.hello(name, token, match, mode));
}
// The moment of the world the page shows now (its interpolated tick, and 1/256 ticks past it),
// which every input then carries for lag compensation (docs/LAG_COMPENSATION.md).
ARENA_API void arena_set_view_moment(client* c, std::uint32_t tick, std::uint32_t fraction) {
    c->session.set_view_moment(std::uint64_t{tick} * 256 + std::min<std::uint32_t>(fraction, 255));
}
ARENA_API std::uint32_t arena_input(client* c, float thrust, float turn, int buttons) {
    return out_size(c->session.input(thrust, turn, static_cast<std::uint8_t>(buttons)));
}
// client_time: an integer below 2^53 (JavaScript numbers are doubles).
ARENA_API std::uint32_t arena_ping(client* c, double client_time) {
    return out_size(c->session.ping(static_cast<std::uint64_t>(client_time)));
}
ARENA_API std::uint32_t arena_bye(client* c, const char* reason) {
    return out_size(c->session.bye(reason));
}
ARENA_API const std::uint8_t* arena_out(const client* c) {
    return c->session.out().data();
}

ARENA_API std::uint32_t arena_player_id(const client* c) {
    return c->session.player_id();
}
ARENA_API std::uint32_t arena_entity_id(const client* c) {
    return c->session.entity_id();
}
ARENA_API std::uint32_t arena_tick_rate(const client* c) {
    return c->session.tick_rate();
}
ARENA_API std::uint32_t arena_snapshot_rate(const client* c) {
    return c->session.snapshot_rate();
}
// The world's bounds from the Welcome's config, for drawing and for interpolating across a
// wrapping edge: 1 when bodies wrap around (Asteroids), and the world's width and height (m).
ARENA_API int arena_world_wraps(const client* c) {
    const auto* config = c->session.config();
    return config != nullptr && config->boundary == arena::world::boundary::wrap ? 1 : 0;
}
ARENA_API double arena_world_width(const client* c) {
    const auto* config = c->session.config();
    return config != nullptr ? static_cast<double>(config->size.x()) : 0.0;
}
ARENA_API double arena_world_height(const client* c) {
    const auto* config = c->session.config();
    return config != nullptr ? static_cast<double>(config->size.y()) : 0.0;
}
ARENA_API std::uint32_t arena_view_tick(const client* c) {
    return c->session.view_tick();
}
ARENA_API std::uint32_t arena_view_ack(const client* c) {
    return c->session.view_ack();
}
ARENA_API std::uint32_t arena_last_sequence(const client* c) {
    return c->session.last_sequence();
}
ARENA_API std::uint32_t arena_delta_ack(const client* c) {
    return c->session.delta_ack();
}
ARENA_API const char* arena_delta_problem(const client* c) {
    return c->session.delta_problem().c_str();
}
// Ticks whose input the pacing left out (arena_input returned 0 for them: nothing to send). A
// double: a count JavaScript reads exactly.
ARENA_API double arena_inputs_left_out(const client* c) {
    return static_cast<double>(c->session.inputs_left_out());
}

// The newest view: arena_view_count BodyStates of 32 bytes (id, owner, x, y, vx, vy, angle,
// angular_velocity), by increasing id.
ARENA_API const arena::protocol::BodyState* arena_view(const client* c) {
    return c->session.view().data();
}
ARENA_API std::uint32_t arena_view_count(const client* c) {
    return static_cast<std::uint32_t>(c->session.view().size());
}
ARENA_API const sdk_shape* arena_shapes(const client* c) {
    return c->shapes.data();
}
ARENA_API std::uint32_t arena_shape_count(const client* c) {
    return static_cast<std::uint32_t>(c->shapes.size());
}
ARENA_API const sdk_static* arena_statics(const client* c) {
    return c->statics.data();
}
ARENA_API std::uint32_t arena_static_count(const client* c) {
    return static_cast<std::uint32_t>(c->statics.size());
}

// The own body as predicted for the last input: x, y, vx, vy, angle, angular_velocity; null
// before a snapshot placed it.
ARENA_API const float* arena_predicted(client* c) {
    const arena::world::body* b = c->session.predicted();
    if (b == nullptr) return nullptr;
    const float values[6] = {b->position.x(), b->position.y(), b->velocity.x(),
                             b->velocity.y(), b->angle,        b->angular_velocity};
    std::memcpy(c->predicted, values, sizeof(values));
    return c->predicted;
}
// The own bullets where the prediction has them now (client_sim/session.hpp): 24 bytes each, as many as
// arena_own_bullet_count says, valid until the next call of this.
ARENA_API const arena::bots::own_bullet* arena_own_bullets(client* c) {
    c->bullets = c->session.own_bullets();
    return c->bullets.data();
}
ARENA_API std::uint32_t arena_own_bullet_count(const client* c) {
    return static_cast<std::uint32_t>(c->bullets.size());
}
// Metres, for the newest snapshot's acknowledged input; NaN when it measured none.
ARENA_API double arena_prediction_error(const client* c) {
    const auto e = c->session.prediction_error();
    return e ? static_cast<double>(*e) : std::numeric_limits<double>::quiet_NaN();
}

// --- replay -------------------------------------------------------------------------------

// Opens a recording (a path in the module's file system); null when it cannot be read:
// arena_replay_open_error says why.
ARENA_API replay* arena_replay_open(const char* path) {
    auto opened = arena::replay::replayer::open(path);
    if (!opened) {
        open_error = opened.error;
        return nullptr;
    }
    auto* r = new replay;
    r->replayer = std::move(opened.value);
    return r;
}
ARENA_API const char* arena_replay_open_error() {
    return open_error.c_str();
}
ARENA_API void arena_replay_free(replay* r) {
    delete r;
}

// Replays to the end (until < 0) or to tick `until`, checking every recorded hash. Returns 1
// when complete with every hash matching, 0 otherwise (arena_replay_error says why).
ARENA_API int arena_replay_run(replay* r, double until) {
    arena::replay::replay_options options;
    if (until >= 0) options.until = static_cast<std::uint32_t>(until);
    r->dump = "tick,hash\n";
    options.on_tick = [r](std::uint32_t tick, std::uint64_t hash) {
        char line[40];
        std::snprintf(line, sizeof(line), "%" PRIu32 ",%016" PRIx64 "\n", tick, hash);
        r->dump += line;
    };
    r->report = r->replayer->run(options);
    r->error = r->report.error;
    if (r->report.mismatch) r->error = mismatch_text(*r->report.mismatch);
    return r->report.complete && !r->report.mismatch ? 1 : 0;
}
// What arena-replay --dump-hashes prints: "tick,hash" then one line per tick.
ARENA_API const char* arena_replay_dump(const replay* r) {
    return r->dump.c_str();
}
ARENA_API const char* arena_replay_error(const replay* r) {
    return r->error.c_str();
}
ARENA_API std::uint32_t arena_replay_final_tick(const replay* r) {
    return r->report.final_tick;
}
ARENA_API std::uint32_t arena_replay_hashes_checked(const replay* r) {
    return r->report.hashes_checked;
}
// The final state hash (the world's and the rules'), 16 hex digits, as arena-replay's final_hash.
ARENA_API const char* arena_replay_final_hash(replay* r) {
    r->final_hash = hex(r->report.final_hash);
    return r->final_hash.c_str();
}
// The replayed world's bodies now, as BodyStates (32 bytes each), by id.
ARENA_API const arena::protocol::BodyState* arena_replay_bodies(replay* r) {
    r->bodies.clear();
    for (const arena::world::body& b : r->replayer->state().bodies())
        r->bodies.emplace_back(b.id, b.owner, b.position.x(), b.position.y(), b.velocity.x(), b.velocity.y(), b.angle,
                               b.angular_velocity);
    return r->bodies.data();
}
ARENA_API std::uint32_t arena_replay_body_count(const replay* r) {
    return static_cast<std::uint32_t>(r->bodies.size());
}

// --- player: a recording stepped, scrubbed and drawn (replay_player.hpp) --------------------

// Opens a recording (a path in the module's file system) at its start tick; null when it
// cannot be read or its start hash does not match: arena_replay_open_error says why.
ARENA_API player* arena_player_open(const char* path) {
    auto opened = arena::sdk::replay_player::open(path);
    if (!opened) {
        open_error = opened.error;
        return nullptr;
    }
    auto* p = new player;
    p->playing = std::move(opened.value);
    p->manifest = arena::protocol::encode_manifest(p->playing->manifest());
    return p;
}
ARENA_API void arena_player_free(player* p) {
    delete p;
}
// Both return 1 while every hash compared so far matched, 0 once one did not or the file has
// a problem (arena_player_error).
ARENA_API int arena_player_step(player* p, std::uint32_t ticks) {
    return p->playing->step(ticks) ? 1 : 0;
}
ARENA_API int arena_player_seek(player* p, std::uint32_t tick) {
    return p->playing->seek(tick) ? 1 : 0;
}
ARENA_API std::uint32_t arena_player_tick(const player* p) {
    return p->playing->tick();
}
ARENA_API std::uint32_t arena_player_start_tick(const player* p) {
    return p->playing->start_tick();
}
ARENA_API std::uint32_t arena_player_end_tick(const player* p) {
    return p->playing->end_tick();
}
ARENA_API std::uint32_t arena_player_tick_rate(const player* p) {
    return p->playing->file_header().tick_rate;
}
ARENA_API std::uint32_t arena_player_hashes_checked(const player* p) {
    return p->playing->hashes_checked();
}
ARENA_API std::uint32_t arena_player_hashes_total(const player* p) {
    return p->playing->hashes_total();
}
// The hash computed at the current tick, 16 hex digits.
ARENA_API const char* arena_player_hash(player* p) {
    p->text = hex(p->playing->hash());
    return p->text.c_str();
}
// The recording's hash for the current tick; "" when it holds none for that tick.
ARENA_API const char* arena_player_recorded_hash(player* p) {
    const auto recorded = p->playing->recorded_hash();
    p->text = recorded ? hex(*recorded) : "";
    return p->text.c_str();
}
// "" while all is well; else the first mismatch ("tick T: hash mismatch: expected E, actual A")
// or the file's problem.
ARENA_API const char* arena_player_error(player* p) {
    const auto& m = p->playing->mismatch();
    p->text = m ? mismatch_text(*m) : p->playing->error();
    return p->text.c_str();
}
// "" for a complete recording; else the problem that ends it early (no End record: the server
// was still recording, or crashed), after which nothing is played.
ARENA_API const char* arena_player_cut_short(const player* p) {
    return p->playing->cut_short().c_str();
}
// The recorded world config (JSON, as a Welcome carries it): a game's page module reads it.
ARENA_API const char* arena_player_world_config(const player* p) {
    return p->playing->file_header().world_config.c_str();
}
// The world's bounds, as arena_world_wraps/width/height give them for a session.
ARENA_API int arena_player_world_wraps(const player* p) {
    return p->playing->world().config().boundary == arena::world::boundary::wrap ? 1 : 0;
}
ARENA_API double arena_player_world_width(const player* p) {
    return static_cast<double>(p->playing->world().config().size.x());
}
ARENA_API double arena_player_world_height(const player* p) {
    return static_cast<double>(p->playing->world().config().size.y());
}
// Every body now (static ones too), as BodyStates (32 bytes each) by id, and the shape of each
// (arena_player_shapes: the same count, the same order); both valid until the next call.
ARENA_API const arena::protocol::BodyState* arena_player_bodies(player* p) {
    p->bodies.clear();
    p->shapes.clear();
    const arena::world::world& w = p->playing->world();
    for (const arena::world::body& b : w.bodies()) {
        p->bodies.emplace_back(b.id, b.owner, b.position.x(), b.position.y(), b.velocity.x(), b.velocity.y(), b.angle,
                               b.angular_velocity);
        p->shapes.push_back(to_sdk(arena::match::describe(w, b, p->playing->game_rules().kind_of(b.id))));
    }
    return p->bodies.data();
}
ARENA_API std::uint32_t arena_player_body_count(const player* p) {
    return static_cast<std::uint32_t>(p->bodies.size());
}
ARENA_API const sdk_shape* arena_player_shapes(const player* p) {
    return p->shapes.data();
}

// --- player: the replayed game's scoreboard, events and result -----------------------------

// The game's manifest as a GameManifest buffer (protocol/manifest.hpp, Welcome.game's bytes:
// the SDK reads both with one decoder); size 0 for a game that declares nothing (the sandbox).
ARENA_API const std::uint8_t* arena_player_manifest(const player* p) {
    return p->manifest.data();
}
ARENA_API std::uint32_t arena_player_manifest_size(const player* p) {
    return static_cast<std::uint32_t>(p->manifest.size());
}
// The scoreboard now, by player id: 64-byte lines (sdk_line), as many as
// arena_player_scoreboard_count says; arena_player_scoreboard_name(i) is line i's name as the
// player joined with it ("" when the recording holds none). Valid until the next call of this.
ARENA_API const sdk_line* arena_player_scoreboard(player* p) {
    const std::vector<arena::rules::score_line> board = p->playing->game_rules().scoreboard();
    p->lines.clear();
    for (const arena::rules::score_line& l : board) {
        sdk_line out{};
        out.player = l.player;
        out.score = l.score;
        out.kills = l.kills;
        out.deaths = l.deaths;
        out.shots = l.shots;
        out.hits = l.hits;
        out.lives = l.lives;
        out.state = static_cast<std::uint8_t>(l.state);
        out.team = l.team;
        out.out = l.out ? 1 : 0;
        std::copy(l.values.begin(), l.values.end(), out.values);
        p->lines.push_back(out);
    }
    p->names = p->playing->names_of(board);
    return p->lines.data();
}
ARENA_API std::uint32_t arena_player_scoreboard_count(const player* p) {
    return static_cast<std::uint32_t>(p->lines.size());
}
ARENA_API const char* arena_player_scoreboard_name(const player* p, std::uint32_t i) {
    return i < p->names.size() ? p->names[i].c_str() : "";
}
// The name player `id` joined with (an event may name a player who has left since); "" when the
// recording holds none. Valid until the next call of this.
ARENA_API const char* arena_player_name(player* p, std::uint32_t id) {
    p->name = p->playing->name_of(id);
    return p->name.c_str();
}
// The teams now, in team order: 40-byte lines (sdk_team); none in a game without teams.
ARENA_API const sdk_team* arena_player_teams(player* p) {
    p->teams.clear();
    for (const arena::rules::team_line& t : p->playing->game_rules().teams()) {
        sdk_team out{};
        out.team = t.team;
        out.score = t.score;
        std::copy(t.values.begin(), t.values.end(), out.values);
        p->teams.push_back(out);
    }
    return p->teams.data();
}
ARENA_API std::uint32_t arena_player_team_count(const player* p) {
    return static_cast<std::uint32_t>(p->teams.size());
}
// The newest declared events up to the current tick, oldest first (at most
// replay_player::max_logged_events): 28-byte records (sdk_event).
ARENA_API const sdk_event* arena_player_events(player* p) {
    p->events.clear();
    for (const arena::sdk::replay_player::logged_event& e : p->playing->events()) {
        sdk_event out{};
        out.sequence = e.sequence;
        out.tick = e.tick;
        out.kind = e.event.kind;
        std::copy(e.event.values.begin(), e.event.values.end(), out.values);
        p->events.push_back(out);
    }
    return p->events.data();
}
ARENA_API std::uint32_t arena_player_event_count(const player* p) {
    return static_cast<std::uint32_t>(p->events.size());
}
// 1 once the replayed rules have ended the match (a match clock ran out), else 0.
ARENA_API int arena_player_finished(const player* p) {
    return p->playing->game_rules().finished() ? 1 : 0;
}
// The team winning now (0: none, a draw or no teams), and the players winning now (the winning
// team's, or every player tied at the top; none: nobody): arena_player_winner_count ids.
ARENA_API std::uint32_t arena_player_winning_team(const player* p) {
    return p->playing->game_rules().winning_team();
}
ARENA_API const std::uint32_t* arena_player_winners(player* p) {
    p->winners = p->playing->game_rules().winners();
    return p->winners.data();
}
ARENA_API std::uint32_t arena_player_winner_count(const player* p) {
    return static_cast<std::uint32_t>(p->winners.size());
}
