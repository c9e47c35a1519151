// Many matches in one registry, driven through the intake as a transport drives it:
// join-or-create by mode, joining by id, the refusals, the end of an empty match, and a match
// whose tick throws ending alone.
#include <catch2/catch.hpp>
#include <stdexcept>

#include "protocol/decode.hpp"
#include "protocol/messages.hpp"
#include "protocol/verify.hpp"
#include "server/host/intake.hpp"
#include "server/host/match_registry.hpp"
#include "server/world/presets.hpp"

using namespace arena;

namespace {

struct fake_client : match::connection {
    std::vector<protocol::frame_bytes> frames;
    std::optional<protocol::RejectCode> rejected;
    std::string reason;
    std::string bye;
    bool throw_on_snapshot = false;
    void send(protocol::frame_bytes frame) override { frames.push_back(std::move(frame)); }
    void send_snapshot(const protocol::snapshot_encoder& s, uint32_t ack) override {
        send_snapshot_frame(s.frame_with_ack(ack));
    }
    void send_snapshot_frame(std::span<const uint8_t> frame) override {
        if (throw_on_snapshot) throw std::runtime_error("a snapshot send failed");
        frames.emplace_back(frame.begin(), frame.end());
    }
    void close(protocol::RejectCode code, std::string_view why) override {
        rejected = code;
        reason = why;
    }
    void close_with_bye(std::string_view why) override { bye = why; }
    std::string_view peer() const override { return "127.0.0.1:1"; }

    // The Welcome among the frames it was sent, if any.
    std::optional<protocol::welcome_info> welcome() const {
        for (const protocol::frame_bytes& f : frames) {
            auto m = protocol::verify_message(f, protocol::server_frame_limits);
            if (!m || m.value->payload_type() != protocol::Payload::Welcome) continue;
            auto w = protocol::decode_welcome(*m.value);
            if (w) return w.value;
        }
        return std::nullopt;
    }
};

host::registry_options options(uint32_t max_matches = 8) {
    host::registry_options o;
    o.base.tick_rate = 60;
    o.base.snapshot_rate = 20;
    o.modes = config::builtin_modes();
    config::mode duel{"duel", world::asteroids_preset(), "asteroids", 2, 0};
    o.modes.push_back(duel);
    o.default_mode = "asteroids";
    o.max_matches = max_matches;
    o.empty_match_ticks = 30;
    return o;
}

struct process {
    explicit process(host::registry_options o = options()) : matches(std::move(o)) {}
    host::match_registry matches;
    ops::process_counters counters;
    host::intake in{matches, counters};

    // Connects `c` as a transport does and sends its Hello; then one tick of every match so
    // that a player's Welcome goes out.
    void join(fake_client& c, const std::string& name, const std::string& match_id, const std::string& mode,
              bool spectator = false, bool then_tick = true) {
        matches.match_of(c).connect(c);
        const protocol::frame_bytes hello =
            protocol::encode_hello({protocol::protocol_version, name, "", true, spectator, match_id, mode});
        in.take(c, hello, std::nullopt);
        if (then_tick) tick();
    }
    void tick() {
        matches.tick_all([] { return int64_t{0}; });
    }
};

}  // namespace

TEST_CASE("a Hello naming neither a match nor a mode joins the default match", "[registry]") {
    process p;
    fake_client c;
    p.join(c, "ada", "", "");
    REQUIRE(c.welcome());
    CHECK(c.welcome()->match == "default");
    CHECK(c.welcome()->mode == "asteroids");
    CHECK(p.matches.size() == 1);
    CHECK(p.matches.default_match().live_player_count() == 1);
}

TEST_CASE("join-or-create fills a mode's match before it creates the next", "[registry]") {
    process p;
    fake_client a, b, c;
    p.join(a, "a", "", "duel");
    p.join(b, "b", "", "duel");
    p.join(c, "c", "", "duel");
    REQUIRE(a.welcome());
    REQUIRE(b.welcome());
    REQUIRE(c.welcome());
    CHECK(a.welcome()->mode == "duel");
    CHECK(a.welcome()->match == b.welcome()->match);  // a duel holds two
    CHECK(c.welcome()->match != a.welcome()->match);  // the third starts the next
    CHECK(a.welcome()->match.size() == 16);           // 64 random bits, in hex
    CHECK(p.matches.size() == 3);                     // the default and two duels
    CHECK(p.matches.default_match().connection_count() == 0);
    CHECK(p.matches.find(a.welcome()->match)->game->live_player_count() == 2);
}

TEST_CASE("join-or-create picks the fullest open match of the mode", "[registry]") {
    process p;
    auto made = p.matches.create("asteroids", true);  // an empty one, created first
    REQUIRE(std::holds_alternative<host::hosted_match*>(made));
    const std::string empty_id = std::get<host::hosted_match*>(made)->id;
    fake_client first, second;
    p.join(first, "first", "", "");  // the default match, also asteroids, now holds one
    p.join(second, "second", "", "asteroids");
    REQUIRE(second.welcome());
    CHECK(second.welcome()->match == "default");
    CHECK(second.welcome()->match != empty_id);
}

TEST_CASE("a private match is joined by its id, never by its mode", "[registry]") {
    process p;
    auto made = p.matches.create("duel", false);
    REQUIRE(std::holds_alternative<host::hosted_match*>(made));
    const std::string id = std::get<host::hosted_match*>(made)->id;
    fake_client stranger, friend_;
    p.join(stranger, "stranger", "", "duel");
    REQUIRE(stranger.welcome());
    CHECK(stranger.welcome()->match != id);
    p.join(friend_, "friend", id, "");
    REQUIRE(friend_.welcome());
    CHECK(friend_.welcome()->match == id);
}

TEST_CASE("joining by id refuses an unknown match, a full one and the wrong mode", "[registry]") {
    process p;
    fake_client a, b;
    p.join(a, "a", "", "duel");
    p.join(b, "b", "", "duel");
    const std::string id = a.welcome()->match;

    fake_client nowhere, late, wrong;
    p.join(nowhere, "n", "0123456789abcdef", "");
    CHECK(nowhere.rejected == protocol::RejectCode::no_such_match);
    p.join(late, "late", id, "");
    CHECK(late.rejected == protocol::RejectCode::match_full);
    CHECK(late.reason.find("2 players") != std::string::npos);
    p.join(wrong, "w", id, "sandbox");
    CHECK(wrong.rejected == protocol::RejectCode::no_such_match);

    // A spectator still finds room to watch the full match.
    fake_client eye;
    p.join(eye, "eye", id, "", true);
    CHECK_FALSE(eye.rejected);
    REQUIRE(eye.welcome());
    CHECK(eye.welcome()->match == id);
}

TEST_CASE("an unknown mode and a process at its match limit are refused with their codes", "[registry]") {
    process p(options(2));
    fake_client unknown, a, b, c;
    p.join(unknown, "u", "", "chess");
    CHECK(unknown.rejected == protocol::RejectCode::mode_unknown);
    CHECK(unknown.reason.find("duel") != std::string::npos);  // the modes it has
    p.join(a, "a", "", "duel");
    p.join(b, "b", "", "duel");
    CHECK(a.welcome());
    CHECK(b.welcome());
    p.join(c, "c", "", "duel");  // both seats taken, and two matches is the limit
    CHECK(c.rejected == protocol::RejectCode::no_room_for_match);
    CHECK(p.matches.size() == 2);
}

TEST_CASE("a bad Hello is refused for what it is, whatever it asks to join", "[registry]") {
    process p;
    fake_client c;
    p.matches.match_of(c).connect(c);
    p.in.take(c, protocol::encode_hello({protocol::protocol_version + 1, "old", "", true, false, "", "duel"}),
              std::nullopt);
    CHECK(c.rejected == protocol::RejectCode::version_mismatch);
    CHECK(p.matches.size() == 1);  // no match was created for it

    fake_client long_mode;
    p.matches.match_of(long_mode).connect(long_mode);
    p.in.take(long_mode,
              protocol::encode_hello({protocol::protocol_version, "x", "", true, false, "", std::string(65, 'm')}),
              std::nullopt);
    CHECK(long_mode.rejected == protocol::RejectCode::bad_request);
}

TEST_CASE("a second Hello with a mode does not move a joined player", "[registry]") {
    process p;
    fake_client c;
    p.join(c, "ada", "", "");
    REQUIRE(c.welcome());
    p.in.take(c, protocol::encode_hello({protocol::protocol_version, "ada", "", true, false, "", "duel"}),
              std::nullopt);
    CHECK(c.rejected == protocol::RejectCode::bad_request);  // the default match refuses it, as ever
    CHECK(p.matches.size() == 1);
}

TEST_CASE("a match created on demand ends once empty for the empty-match time", "[registry]") {
    process p;
    fake_client c;
    p.join(c, "ada", "", "duel");
    const std::string id = c.welcome()->match;
    REQUIRE(p.matches.find(id));
    p.in.take(c, protocol::encode_bye("done"), std::nullopt);
    for (int i = 0; i < 29; ++i) p.tick();
    CHECK(p.matches.find(id));  // 30 ticks empty ends it (options()), not 29
    p.tick();
    CHECK_FALSE(p.matches.find(id));
    CHECK(p.matches.size() == 1);
    // What it sends now reaches the default match, which does not know it, and goes nowhere.
    CHECK_FALSE(p.in.take(c, protocol::encode_ping(1), std::nullopt).go_on);
    const auto summaries = p.matches.summaries();
    REQUIRE(summaries.size() == 2);
    CHECK(summaries[1].id == id);
    CHECK(summaries[1].ended == "match ended (empty)");
    CHECK(summaries[1].counters.joins == 1);
}

TEST_CASE("a match whose tick throws ends alone, and its neighbours play on", "[registry]") {
    process p;
    fake_client calm, doomed, neighbour;
    p.join(calm, "calm", "", "");
    p.join(doomed, "doomed", "", "duel");
    p.join(neighbour, "neighbour", "", "sandbox");
    const std::string doomed_id = doomed.welcome()->match;
    doomed.throw_on_snapshot = true;  // its match's next snapshot tick throws
    for (int i = 0; i < 3; ++i) p.tick();
    CHECK_FALSE(p.matches.find(doomed_id));
    CHECK(doomed.bye.find("its tick failed") != std::string::npos);
    CHECK(p.matches.size() == 2);
    const uint32_t before = p.matches.default_match().state().tick();
    p.tick();
    CHECK(p.matches.default_match().state().tick() == before + 1);
    CHECK(p.matches.default_match().live_player_count() == 1);
    CHECK_FALSE(calm.rejected);
    CHECK_FALSE(neighbour.rejected);
    CHECK(neighbour.bye.empty());
}

TEST_CASE("the default match's exception is the process's", "[registry]") {
    process p;
    fake_client c;
    p.join(c, "ada", "", "");
    c.throw_on_snapshot = true;
    CHECK_THROWS_AS(
        [&] {
            for (int i = 0; i < 3; ++i) p.tick();
        }(),
        std::runtime_error);
}

namespace {

// A client from an address of its own.
struct addressed_client : fake_client {
    std::string from;
    explicit addressed_client(std::string address) : from(std::move(address) + ":1") {}
    std::string_view peer() const override { return from; }
};

}  // namespace

TEST_CASE("one address cannot take every match slot: it holds four, others still create", "[registry][abuse]") {
    process p(options(8));
    // The attacker creates private matches through the lobby and by Hellos that leave at once.
    int made = 0;
    for (int i = 0; i < 6; ++i)
        if (std::holds_alternative<host::hosted_match*>(p.matches.create("duel", false, "10.0.0.66"))) ++made;
    CHECK(made == 4);
    auto refused = p.matches.create("duel", false, "10.0.0.66");
    REQUIRE(std::holds_alternative<match::rejection>(refused));
    CHECK(std::get<match::rejection>(refused).code == protocol::RejectCode::no_room_for_match);
    CHECK(std::get<match::rejection>(refused).detail.find("this address created 4 matches that are still empty") !=
          std::string::npos);
    // An honest player elsewhere still gets a match of the mode.
    addressed_client honest("192.0.2.7");
    p.join(honest, "honest", "", "duel");
    REQUIRE(honest.welcome());
    CHECK(honest.welcome()->mode == "duel");
}

TEST_CASE("at the match limit, creating and leaving cannot starve joins: an empty match gives its slot up",
          "[registry][abuse]") {
    host::registry_options o = options(4);
    o.reclaim_empty_ticks = 10;
    o.empty_match_ticks = 1000;  // the attackers' matches would otherwise hold their slots this long
    process p(std::move(o));
    // Three addresses each create a private match and never come: with the default, the limit.
    for (const char* attacker : {"10.0.0.1", "10.0.0.2", "10.0.0.3"})
        REQUIRE(std::holds_alternative<host::hosted_match*>(p.matches.create("duel", false, attacker)));
    REQUIRE(p.matches.size() == 4);
    addressed_client early("192.0.2.7");
    p.join(early, "early", "", "duel");  // they have been empty 1 tick: nothing to reclaim yet
    CHECK(early.rejected == protocol::RejectCode::no_room_for_match);
    for (int i = 0; i < 10; ++i) p.tick();
    addressed_client honest("192.0.2.8");
    p.join(honest, "honest", "", "duel");
    REQUIRE(honest.welcome());
    CHECK(p.matches.size() == 4);  // one of the empty matches went, the honest one took its slot
    const auto summaries = p.matches.summaries();
    CHECK(summaries.back().ended == "match ended (empty, its slot given to a new match)");
}

namespace {

// Every match's state hash at every tick of a 300-tick run, the default match's first: two
// players fly and shoot in the default match, beside `neighbours` duels whose players do the
// same with other inputs, ticked by `threads` threads.
std::vector<std::vector<uint64_t>> match_hashes(int neighbours, unsigned threads) {
    host::registry_options o = options(256);
    o.threads = threads;
    process p(std::move(o));
    std::vector<std::unique_ptr<fake_client>> clients;
    auto add = [&](const std::string& name, const std::string& mode) {
        // Each from an address of its own: one address may create only a few matches.
        clients.push_back(std::make_unique<addressed_client>("10.0." + std::to_string(clients.size()) + ".1"));
        p.join(*clients.back(), name, "", mode, false, false);  // all join in the same tick
    };
    add("a", "");
    add("b", "");
    for (int i = 0; i < neighbours; ++i) {
        const std::string number = std::to_string(i);
        add(std::string("n").append(number), "duel");
        add(std::string("m").append(number), "duel");
    }
    p.tick();
    for (const auto& c : clients) REQUIRE(c->welcome());
    std::vector<std::vector<uint64_t>> hashes(p.matches.size());
    for (uint32_t t = 1; t <= 300; ++t) {
        for (size_t c = 0; c < clients.size(); ++c) {
            protocol::input_msg in;
            in.sequence = t;
            in.thrust = c % 2 ? 1.0f : 0.5f;
            in.turn = (t / 30 + c) % 3 == 0 ? 1.0f : -0.25f;
            in.buttons = t % 20 == c % 20 ? 2 : 0;  // fire now and then
            p.in.take(*clients[c], protocol::encode_input(in), std::nullopt);
        }
        p.tick();
        size_t i = 0;
        for (const auto& [key, m] : p.matches.matches())
            hashes[i++].push_back(rules::state_hash(m.game->state(), m.game->game_rules()));
    }
    return hashes;
}

}  // namespace

TEST_CASE("a match's hashes do not depend on its neighbours", "[registry][determinism]") {
    const std::vector<uint64_t> alone = match_hashes(0, 1).front();
    CHECK(match_hashes(100, 1).front() == alone);
    CHECK(alone.front() != alone.back());  // it did move
}

TEST_CASE("every match's hashes are the same on 1 thread and on 8", "[registry][determinism][threads]") {
    const auto one = match_hashes(100, 1);
    const auto eight = match_hashes(100, 8);
    REQUIRE(one.size() == 101);
    CHECK(eight == one);
    CHECK(one.front() == match_hashes(0, 8).front());  // and alone on 8
}

TEST_CASE("a match's output on a worker thread reaches its clients in the order it was said", "[registry][threads]") {
    host::registry_options o = options(8);
    o.threads = 3;
    process p(std::move(o));
    fake_client a, b, c;
    p.join(a, "a", "", "duel");
    p.join(b, "b", "", "duel");
    p.join(c, "c", "", "sandbox");
    for (int i = 0; i < 9; ++i) p.tick();
    for (fake_client* client : {&a, &b, &c}) {
        REQUIRE(client->welcome());
        REQUIRE_FALSE(client->frames.empty());
        // The Welcome first, then the snapshots, as when the match ticks on the io thread.
        REQUIRE(client->frames.size() >= 3);
        for (size_t i = 0; i < client->frames.size(); ++i) {
            auto m = protocol::verify_message(client->frames[i], protocol::server_frame_limits);
            REQUIRE(m);
            CHECK(m.value->payload_type() == (i == 0 ? protocol::Payload::Welcome : protocol::Payload::Snapshot));
        }
    }
}

TEST_CASE("a match created under a name the caller gives keeps it, and a name in use or malformed is refused",
          "[registry]") {
    process p;
    auto made = p.matches.create("duel", true, "", "tournament-7");
    REQUIRE(std::holds_alternative<host::hosted_match*>(made));
    CHECK(std::get<host::hosted_match*>(made)->id == "tournament-7");
    CHECK(std::holds_alternative<match::rejection>(p.matches.create("duel", true, "", "tournament-7")));
    CHECK(std::holds_alternative<match::rejection>(p.matches.create("duel", true, "", "no spaces")));
    CHECK(std::holds_alternative<match::rejection>(p.matches.create("duel", true, "", "default")));
    fake_client c;
    p.join(c, "ada", "tournament-7", "");
    REQUIRE(c.welcome());
    CHECK(c.welcome()->match == "tournament-7");
}

TEST_CASE("a signed token that names a match joins that match and no other", "[registry][auth]") {
    host::registry_options o = options();
    // A checker as the server's: "NAME@ID" is NAME's token good for match ID, "NAME" for any.
    match::token_check check = [](std::string_view token) {
        const std::string t(token);
        const size_t at = t.find('@');
        if (at == std::string::npos) return result<match::signed_token>::success({t, ""});
        return result<match::signed_token>::success({t.substr(0, at), t.substr(at + 1)});
    };
    host::match_registry matches(std::move(o), {}, check);
    ops::process_counters counters;
    host::intake in(matches, counters);
    auto made = matches.create("asteroids", false, "", "finals");
    REQUIRE(std::holds_alternative<host::hosted_match*>(made));
    auto join = [&](fake_client& c, const std::string& token, const std::string& match_id, const std::string& mode) {
        matches.match_of(c).connect(c);
        in.take(c, protocol::encode_hello({protocol::protocol_version, "x", token, true, false, match_id, mode}),
                std::nullopt);
        matches.tick_all([] { return int64_t{0}; });
    };
    fake_client invited, token_alone, elsewhere, other_mode, open_token;
    join(invited, "ada@finals", "finals", "");
    REQUIRE(invited.welcome());
    CHECK(invited.welcome()->match == "finals");
    join(token_alone, "bob@finals", "", "");  // naming no match: the token's
    REQUIRE(token_alone.welcome());
    CHECK(token_alone.welcome()->match == "finals");
    join(elsewhere, "cy@finals", "default", "");
    CHECK(elsewhere.rejected == protocol::RejectCode::unauthorized);
    CHECK(elsewhere.reason == "this token is good for match finals only");
    join(other_mode, "di@finals", "", "duel");  // finals plays asteroids: not a new duel either
    CHECK(other_mode.rejected == protocol::RejectCode::no_such_match);
    CHECK(matches.size() == 2);
    join(open_token, "eve", "finals", "");
    CHECK(open_token.welcome());
    CHECK(matches.find("finals")->game->live_player_count() == 3);
}

TEST_CASE("late and dropped ticks are counted by every match running, and kept when it ends", "[registry][late]") {
    process p;
    fake_client c;
    p.join(c, "ada", "", "duel");
    const std::string id = c.welcome()->match;
    p.matches.count_late_ticks(3, 1);                 // the process fell behind: both matches were late
    auto made = p.matches.create("asteroids", true);  // after the stall: none of it is its
    REQUIRE(std::holds_alternative<host::hosted_match*>(made));
    const std::string later = std::get<host::hosted_match*>(made)->id;
    p.matches.count_late_ticks(2, 0);
    CHECK(p.matches.find(id)->ticks_late == 5);
    CHECK(p.matches.find(id)->ticks_dropped == 1);
    CHECK(p.matches.find(later)->ticks_late == 2);
    CHECK(p.matches.find(later)->ticks_dropped == 0);
    CHECK(p.matches.default_match().counters().ticks >= 1);
    p.in.take(c, protocol::encode_bye("done"), std::nullopt);
    for (int i = 0; i < 30; ++i) p.tick();
    REQUIRE_FALSE(p.matches.find(id));
    bool found = false;
    for (const host::match_summary& s : p.matches.summaries())
        if (s.id == id) {
            found = true;
            CHECK(s.ticks_late == 5);
            CHECK(s.ticks_dropped == 1);
        }
    CHECK(found);
}
