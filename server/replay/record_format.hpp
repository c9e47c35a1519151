#pragma once
// One record of a replay file, as bytes: encoding for the recorder, checking and decoding for
// the reader. No I/O here. On disk a record is
//
//   length: uint32 LE | body: `length` bytes, a FlatBuffer `Record` ("ARPL") | check: uint32 LE
//
// where length + body is exactly a FlatBuffers size-prefixed buffer and `check` is FNV-1a 32
// of the body. The checksum is what lets a reader name the record holding any flipped byte:
// the Verifier alone only catches bytes that break the structure, not a changed input value.
#include <cstdint>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include <flatbuffers/flatbuffers.h>

#include "protocol/result.hpp"
#include "server/match/tick_record.hpp"
#include "server/replay/header.hpp"

namespace arena::replay {

inline constexpr char record_identifier[] = "ARPL";
inline constexpr uint32_t record_prefix_size = 4;    // the length
inline constexpr uint32_t record_checksum_size = 4;  // after the body
// No valid body is shorter: root offset (4) + file identifier (4).
inline constexpr uint32_t min_record_body = 8;
// A Tick of a full world (2^20 bodies × 16-byte inputs) is about 16 MiB; a length above this
// is corruption, refused before anything is allocated.
inline constexpr uint32_t max_record_body = 64u << 20;

// The world's hash after the step that made its tick `tick`.
struct hash_check {
    uint32_t tick = 0;
    uint64_t hash = 0;
};

// The last record of a complete file.
struct end_marker {
    uint32_t tick = 0;
    uint64_t hash = 0;
};

using record = std::variant<header, match::tick_record, hash_check, end_marker>;

// FNV-1a 32 (server/world/fnv1a.hpp; offset basis 2166136261, prime 16777619): any single
// changed byte changes it, since every step is a bijection of the 32-bit state.
uint32_t record_checksum(std::span<const uint8_t> body);

// Appends whole records (prefix, body, checksum) to a byte buffer, reusing one builder.
class record_encoder {
public:
    void append(const header& h, std::vector<uint8_t>& out);
    void append(const match::tick_record& t, std::vector<uint8_t>& out);
    void append(const hash_check& c, std::vector<uint8_t>& out);
    void append(const end_marker& e, std::vector<uint8_t>& out);

private:
    void finish_into(std::vector<uint8_t>& out);
    flatbuffers::FlatBufferBuilder builder_{1024};
};

// Decodes one record from `frame` = prefix + body (no checksum; the caller checked it and the
// length). `frame.data()` must be 8-byte aligned. Runs flatbuffers::Verifier, then checks the
// record type and every field a replay relies on (finite inputs). Never reads outside frame.
protocol::result<record> decode_record(std::span<const uint8_t> frame);

// "Header", "Tick", "Hash", "End" for messages.
const char* record_type_name(const record& r);

}  // namespace arena::replay
