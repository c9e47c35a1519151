#pragma once
// Reads a replay file record by record (a long session never has to fit in memory) and checks
// everything before a replay trusts it: framing, checksum, FlatBuffer verification, record
// order and tick continuity. Every problem is one line,
//   "<file>: byte offset <N>: <what was wrong>"
// where N is the offset of the record at fault (or of the end of the file). Bytes from a file
// never assert, throw or read out of bounds.
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "protocol/result.hpp"
#include "server/match/tick_record.hpp"
#include "server/replay/file_handle.hpp"
#include "server/replay/header.hpp"
#include "server/replay/record_format.hpp"
#include "server/world/config.hpp"

namespace arena::replay {

// What follows the header: ticks, with Hash records between them, then one End.
using entry = std::variant<match::tick_record, hash_check, end_marker>;

class reader {
public:
    // Opens `path` and reads its Header record: refuses a file that is not a replay, from a
    // newer format version, from another world version, or whose config does not parse.
    static protocol::result<reader> open(const std::string& path);

    reader() = default;  // closed; for result<reader>

    const header& file_header() const { return header_; }
    // The world config parsed from the header's JSON.
    const world::world_config& config() const { return config_; }

    // The next record. After an end_marker, do not call again. A file that ends without one
    // (the recorder never finished: a crash or a kill) is an error at the end's offset.
    protocol::result<entry> next();

    // Offset of the next record; the file's size.
    uint64_t offset() const { return offset_; }
    uint64_t size() const { return size_; }
    const std::string& path() const { return path_; }

private:
    // Reads, frames and checks the record at offset_ and advances past it.
    protocol::result<record> read_record();
    protocol::result<entry> check_order(record r, uint64_t at);
    std::string at(uint64_t offset, const std::string& what) const;

    std::string path_;
    file_handle file_;
    uint64_t size_ = 0;
    uint64_t offset_ = 0;
    std::vector<uint64_t> storage_;  // words, so that a record starts 8-byte aligned
    header header_;
    world::world_config config_;
    uint32_t next_tick_ = 0;  // the world's tick after the records read so far
    bool ended_ = false;
};

}  // namespace arena::replay
