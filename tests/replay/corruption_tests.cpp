// Bytes from a file never crash a replay: every truncation, flipped byte and malformed record
// is one line naming the byte offset of the record at fault and what was wrong.
#include <catch2/catch.hpp>

#include <algorithm>
#include <vector>

#include "protocol/replay_generated.h"
#include "replay_files.hpp"
#include "scripted_session.hpp"
#include "server/config/config_json.hpp"
#include "server/replay/reader.hpp"
#include "server/replay/replayer.hpp"
#include "server/world/presets.hpp"

using namespace arena;
using namespace arena::replay;
using testing::read_bytes;
using testing::record_offsets;
using testing::temp_file;
using testing::write_bytes;

namespace {

// The replay's file problem, or "" when it replayed (a hash mismatch is not a file problem).
std::string replay_error(const std::string& path) {
    auto opened = replayer::open(path);
    if (!opened) return opened.error;
    return opened.value->run().error;
}

std::string offset_text(const std::string& path, uint64_t offset) {
    return path + ": byte offset " + std::to_string(offset) + ": ";
}

// The offset of the record that holds byte `at`.
uint64_t record_holding(const std::vector<uint64_t>& offsets, uint64_t at) {
    return *(std::upper_bound(offsets.begin(), offsets.end(), at) - 1);
}

header valid_header() {
    world::world w(world::asteroids_preset(), 1);
    return make_header(w, "asteroids", 1, 60);
}

// A small real recording: 12 ticks, joins, inputs and Hash records every 5 ticks.
std::vector<uint8_t> small_recording(const std::string& path) {
    testing::session_script script;
    script.ticks = 12;
    script.hash_interval = 5;
    REQUIRE(testing::record_scripted_session(path, script).ok());
    return read_bytes(path);
}

// Appends a raw FlatBuffers Record the encoder would never write, with a valid checksum.
void append_raw_record(flatbuffers::FlatBufferBuilder& fbb, std::vector<uint8_t>& out) {
    const uint8_t* data = fbb.GetBufferPointer();
    out.insert(out.end(), data, data + fbb.GetSize());
    const uint32_t check = record_checksum({data + 4, fbb.GetSize() - 4});
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(check >> (8 * i)));
}

}  // namespace

TEST_CASE("a flipped byte in the golden recording is reported with its record's byte offset", "[replay][corruption]") {
    const std::vector<uint8_t> golden = read_bytes(testing::golden_path());
    const std::vector<uint64_t> offsets = record_offsets(golden);
    REQUIRE(offsets.size() > 100);
    temp_file file("golden_flipped");

    SECTION("inside a Tick's inputs: the checksum catches a value the Verifier cannot") {
        const uint64_t record = offsets[50];
        std::vector<uint8_t> bytes = golden;
        bytes[record + 40] ^= 0x10;
        write_bytes(file.path(), bytes);
        const std::string error = replay_error(file.path());
        CHECK_THAT(error, Catch::StartsWith(offset_text(file.path(), record) + "checksum mismatch"));
    }
    SECTION("in a length prefix") {
        const uint64_t record = offsets[80];
        std::vector<uint8_t> bytes = golden;
        bytes[record + 3] ^= 0x01;  // + 16 MiB
        write_bytes(file.path(), bytes);
        CHECK_THAT(replay_error(file.path()), Catch::StartsWith(offset_text(file.path(), record) + "truncated record"));
    }
    SECTION("in the header") {
        std::vector<uint8_t> bytes = golden;
        bytes[100] ^= 0x01;
        write_bytes(file.path(), bytes);
        CHECK_THAT(replay_error(file.path()), Catch::StartsWith(offset_text(file.path(), 0) + "checksum mismatch"));
    }
}

TEST_CASE("every flipped byte of a recording is reported at the record that holds it", "[replay][corruption]") {
    temp_file original("small_original"), file("small_flipped");
    const std::vector<uint8_t> clean = small_recording(original.path());
    const std::vector<uint64_t> offsets = record_offsets(clean);
    REQUIRE(replay_error(original.path()).empty());
    for (uint8_t mask : {uint8_t{0x01}, uint8_t{0xff}}) {
        for (uint64_t at = 0; at < clean.size(); ++at) {
            std::vector<uint8_t> bytes = clean;
            bytes[at] ^= mask;
            write_bytes(file.path(), bytes);
            const std::string error = replay_error(file.path());
            INFO("byte " << at << " ^ " << int{mask} << ": " << error);
            REQUIRE_THAT(error, Catch::StartsWith(offset_text(file.path(), record_holding(offsets, at))));
        }
    }
}

TEST_CASE("a truncated recording is reported with the byte offset of the cut record", "[replay][corruption]") {
    const std::vector<uint8_t> golden = read_bytes(testing::golden_path());
    const std::vector<uint64_t> offsets = record_offsets(golden);
    temp_file file("golden_truncated");

    SECTION("in the middle of a record") {
        const uint64_t record = offsets[200];
        write_bytes(file.path(), {golden.begin(), golden.begin() + static_cast<long>(record + 13)});
        CHECK_THAT(replay_error(file.path()),
                   Catch::StartsWith(offset_text(file.path(), record) + "truncated record: its length says"));
    }
    SECTION("inside a record's length prefix") {
        const uint64_t record = offsets[300];
        write_bytes(file.path(), {golden.begin(), golden.begin() + static_cast<long>(record + 2)});
        CHECK_THAT(replay_error(file.path()), Catch::StartsWith(offset_text(file.path(), record) +
                                                                "truncated: 2 bytes where a 4-byte record length"));
    }
    SECTION("between records: the End record is missing") {
        const uint64_t record = offsets[400];
        write_bytes(file.path(), {golden.begin(), golden.begin() + static_cast<long>(record)});
        CHECK_THAT(replay_error(file.path()),
                   Catch::StartsWith(offset_text(file.path(), record) + "the file ends without an End record"));
    }
}

TEST_CASE("every truncation of a recording is reported, never replayed as complete", "[replay][corruption]") {
    temp_file original("small_for_cuts"), file("small_cut");
    const std::vector<uint8_t> clean = small_recording(original.path());
    const std::vector<uint64_t> offsets = record_offsets(clean);
    for (uint64_t length = 1; length < clean.size(); ++length) {
        write_bytes(file.path(), {clean.begin(), clean.begin() + static_cast<long>(length)});
        const std::string error = replay_error(file.path());
        INFO("cut at " << length << ": " << error);
        const bool at_boundary = std::binary_search(offsets.begin(), offsets.end(), length);
        REQUIRE_THAT(
            error, Catch::StartsWith(offset_text(file.path(), at_boundary ? length : record_holding(offsets, length))));
    }
}

TEST_CASE("a recording from a newer format version says so", "[replay][corruption]") {
    temp_file file("newer_format");
    header h = valid_header();
    h.format_version = current_format_version + 1;
    std::vector<uint8_t> bytes;
    record_encoder encoder;
    encoder.append(h, bytes);
    encoder.append(end_marker{0, h.start_hash}, bytes);
    write_bytes(file.path(), bytes);
    CHECK(replay_error(file.path()) == offset_text(file.path(), 0) + "recorded by a newer Arena (format version " +
                                           std::to_string(current_format_version + 1) + ", this build reads up to " +
                                           std::to_string(current_format_version) + ")");
}

TEST_CASE("malformed recordings are each refused with the offset and the reason", "[replay][corruption]") {
    temp_file file("malformed");
    const header h = valid_header();
    record_encoder encoder;
    std::vector<uint8_t> bytes;
    std::string expected;

    SECTION("empty file") {
        expected = offset_text(file.path(), 0) + "empty file";
    }
    SECTION("not a replay file") {
        const std::string json = config::config_to_json(world::asteroids_preset());
        bytes.assign(json.begin(), json.end());
        expected = offset_text(file.path(), 0) + "not an Arena replay file";
    }
    SECTION("header missing") {
        encoder.append(match::tick_record{0, {}, {}, {}, {}}, bytes);
        expected = offset_text(file.path(), 0) + "header missing: the first record is a Tick, not a Header";
    }
    SECTION("bad record length") {
        encoder.append(h, bytes);
        bytes[0] = 3;
        bytes[1] = bytes[2] = bytes[3] = 0;
        expected = offset_text(file.path(), 0) + "bad record length 3";
    }
    SECTION("another world version") {
        header other = h;
        other.world_version = world::world_version + 1;
        encoder.append(other, bytes);
        expected = offset_text(file.path(), 0) + "recorded with world version";
    }
    SECTION("a version-2 world with a chain, whose physics changed in version 3") {
        header other = h;
        other.world_version = 2;
        other.world_config =
            R"({"preset": "platformer", "bodies": [{"shape": {"type": "chain", "points": [[0, 1], [10, 1], [20, 3]]}}]})";
        encoder.append(other, bytes);
        expected = offset_text(file.path(), 0) +
                   "recorded with world version 2, this build simulates world version 4, which changed what this "
                   "world uses: chains";
    }
    SECTION("a version-3 sub-stepped world, whose solver changed in version 4") {
        header other = h;
        other.world_version = 3;
        other.world_config = R"({"preset": "pyramid", "substeps": 4})";
        encoder.append(other, bytes);
        expected = offset_text(file.path(), 0) +
                   "recorded with world version 3, this build simulates world version 4, which changed what this "
                   "world uses: sub-steps";
    }
    SECTION("a config that does not parse") {
        header other = h;
        other.world_config = R"({"gravity": "down"})";
        encoder.append(other, bytes);
        expected = offset_text(file.path(), 0) + "Header: world config:";
    }
    SECTION("a second header") {
        encoder.append(h, bytes);
        const uint64_t second = bytes.size();
        encoder.append(h, bytes);
        expected = offset_text(file.path(), second) + "unexpected record type Header after the header";
    }
    SECTION("a missing tick") {
        encoder.append(h, bytes);
        encoder.append(match::tick_record{0, {}, {}, {}, {}}, bytes);
        const uint64_t gap = bytes.size();
        encoder.append(match::tick_record{2, {}, {}, {}, {}}, bytes);
        expected = offset_text(file.path(), gap) + "Tick record for tick 2 where tick 1 was expected";
    }
    SECTION("a Hash record for another tick") {
        encoder.append(h, bytes);
        encoder.append(match::tick_record{0, {}, {}, {}, {}}, bytes);
        const uint64_t at = bytes.size();
        encoder.append(hash_check{5, 0}, bytes);
        expected = offset_text(file.path(), at) + "Hash record for tick 5 where the world is at tick 1";
    }
    SECTION("bytes after the End record") {
        encoder.append(h, bytes);
        encoder.append(end_marker{0, h.start_hash}, bytes);
        const uint64_t after = bytes.size();
        encoder.append(match::tick_record{0, {}, {}, {}, {}}, bytes);
        expected =
            offset_text(file.path(), after) + std::to_string(bytes.size() - after) + " bytes after the End record";
    }
    SECTION("an unknown record type") {
        encoder.append(h, bytes);
        const uint64_t at = bytes.size();
        namespace fb = protocol::replay;
        flatbuffers::FlatBufferBuilder fbb;
        const auto end = fb::CreateEnd(fbb, 0, 0);
        fb::RecordBuilder rb(fbb);
        rb.add_content_type(static_cast<fb::Content>(99));
        rb.add_content(end.Union());
        fb::FinishSizePrefixedRecordBuffer(fbb, rb.Finish());
        append_raw_record(fbb, bytes);
        expected = offset_text(file.path(), at) + "unknown record type 99";
    }
    SECTION("a record type without its table") {
        encoder.append(h, bytes);
        const uint64_t at = bytes.size();
        namespace fb = protocol::replay;
        flatbuffers::FlatBufferBuilder fbb;
        fb::RecordBuilder rb(fbb);
        rb.add_content_type(fb::Content::Tick);
        fb::FinishSizePrefixedRecordBuffer(fbb, rb.Finish());
        append_raw_record(fbb, bytes);
        expected = offset_text(file.path(), at) + "record type Tick has no table";
    }
    write_bytes(file.path(), bytes);
    CHECK_THAT(replay_error(file.path()), Catch::StartsWith(expected));
}

TEST_CASE("a missing file and a directory are refused with their reason", "[replay][corruption]") {
    CHECK_THAT(replay_error("/nonexistent/x.arpl"), Catch::Contains("/nonexistent/x.arpl: cannot open"));
    CHECK_THAT(replay_error(ARENA_TEST_DATA_DIR), Catch::Contains("is a directory"));
}
