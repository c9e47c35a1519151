#include "server/replay/reader.hpp"

#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "games/registry.hpp"
#include "server/config/config_json.hpp"
#include "server/replay/status.hpp"
#include "server/world/little_endian.hpp"
#include "server/world/version.hpp"

namespace arena::replay {

namespace {

std::string hex32(uint32_t v) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%08" PRIx32, v);
    return text;
}

// Readable form of 4 identifier bytes: printable ASCII as is, the rest as \xNN.
std::string quoted_bytes(const uint8_t* p, size_t n) {
    std::string out = "\"";
    for (size_t i = 0; i < n; ++i) {
        if (p[i] >= 0x20 && p[i] < 0x7f && p[i] != '"' && p[i] != '\\') {
            out += static_cast<char>(p[i]);
        } else {
            char esc[8];
            std::snprintf(esc, sizeof esc, "\\x%02x", p[i]);
            out += esc;
        }
    }
    return out + "\"";
}

}  // namespace

std::string reader::at(uint64_t offset, const std::string& what) const {
    return path_ + ": byte offset " + std::to_string(offset) + ": " + what;
}

protocol::result<reader> reader::open(const std::string& path) {
    using r = protocol::result<reader>;
    reader rd;
    rd.path_ = path;
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) return r::failure(path + ": is a directory, not a replay file");
    rd.file_.reset(std::fopen(path.c_str(), "rb"));
    if (!rd.file_) return r::failure(io_error(path, "cannot open"));
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) return r::failure(path + ": cannot read its size: " + ec.message());
    rd.size_ = size;
    if (rd.size_ == 0) return r::failure(rd.at(0, "empty file: no Header record"));

    auto first = rd.read_record();
    if (!first) return r::failure(first.error);
    auto* h = std::get_if<header>(&first.value);
    if (!h) {
        return r::failure(rd.at(0, std::string("header missing: the first record is a ") +
                                       record_type_name(first.value) + ", not a Header"));
    }
    // In this order: a newer file may differ in everything below.
    if (h->format_version > current_format_version) {
        return r::failure(rd.at(0, "recorded by a newer Arena (format version " + std::to_string(h->format_version) +
                                       ", this build reads up to " + std::to_string(current_format_version) + ")"));
    }
    if (h->format_version == 0) return r::failure(rd.at(0, "Header: format version 0 is not valid"));
    if (h->world_version < world::oldest_replayable_world_version || h->world_version > world::world_version) {
        return r::failure(rd.at(0, "recorded with world version " + std::to_string(h->world_version) +
                                       ", this build simulates world version " + std::to_string(world::world_version) +
                                       ": the physics differ, so the hashes could not match (replay it with the "
                                       "Arena version that recorded it)"));
    }
    if (h->tick_rate == 0 || h->tick_rate > max_tick_rate)
        return r::failure(rd.at(0, "Header: tick_rate " + std::to_string(h->tick_rate) + " is outside [1, " +
                                       std::to_string(max_tick_rate) + "], the rates arena-server runs at"));
    if (h->hash_interval == 0 || h->hash_interval > max_hash_interval)
        return r::failure(rd.at(0, "Header: hash_interval " + std::to_string(h->hash_interval) + " is outside [1, " +
                                       std::to_string(max_hash_interval) + "]"));
    if (h->start_tick > max_start_tick(h->tick_rate))
        return r::failure(rd.at(0, "Header: start_tick " + std::to_string(h->start_tick) + " is more than " +
                                       std::to_string(max_start_seconds) + " s (" +
                                       std::to_string(max_start_tick(h->tick_rate)) + " ticks at " +
                                       std::to_string(h->tick_rate) +
                                       " Hz) after the world's start: arena-server records from a match's first tick"));
    auto parsed = config::parse_config_json(h->world_config);
    if (!parsed) return r::failure(rd.at(0, "Header: world config: " + parsed.error));
    // A game this build has, with parameters it accepts, as the recording server checked
    // before it started.
    if (const std::string problem = games::config_problem(parsed.value); !problem.empty())
        return r::failure(rd.at(0, "Header: world config: " + problem));
    rd.config_ = std::move(parsed.value);
    if (const std::string changed = world::changed_since(h->world_version, rd.config_); !changed.empty()) {
        return r::failure(rd.at(0, "recorded with world version " + std::to_string(h->world_version) +
                                       ", this build simulates world version " + std::to_string(world::world_version) +
                                       ", which changed what this world uses: " + changed +
                                       " (replay it with the Arena version that recorded it)"));
    }
    rd.header_ = std::move(*h);
    rd.next_tick_ = rd.header_.start_tick;
    return r::success(std::move(rd));
}

protocol::result<record> reader::read_record() {
    using r = protocol::result<record>;
    const uint64_t start = offset_;
    const uint64_t left = size_ - start;
    if (left < record_prefix_size) {
        return r::failure(
            at(start, "truncated: " + std::to_string(left) + " bytes where a 4-byte record length was expected"));
    }
    // The whole prefix + root offset + identifier first: a file that is not a replay is named
    // as such, not as a bad length.
    uint8_t head[12];
    const size_t head_size = left < sizeof head ? static_cast<size_t>(left) : sizeof head;
    // Records are read strictly in order, so the file position is always `start` here.
    if (std::fread(head, 1, head_size, file_.get()) != head_size) {
        return r::failure(at(start, std::string("read failed: ") + std::strerror(errno)));
    }
    if (head_size < sizeof head) {
        return r::failure(at(start, "truncated record: " + std::to_string(left) +
                                        " bytes left, too few for a length, a root offset and an identifier"));
    }
    if (std::memcmp(head + 8, record_identifier, 4) != 0) {
        return r::failure(at(start, start == 0 ? "not an Arena replay file: identifier " + quoted_bytes(head + 8, 4) +
                                                     " where \"ARPL\" was expected"
                                               : "record identifier " + quoted_bytes(head + 8, 4) +
                                                     " where \"ARPL\" was expected: the file is corrupted"));
    }
    const uint32_t length = world::load_le32(head);
    if (length < min_record_body || length > max_record_body) {
        return r::failure(at(start, "bad record length " + std::to_string(length) +
                                        " (valid: " + std::to_string(min_record_body) + " to " +
                                        std::to_string(max_record_body) + " bytes)"));
    }
    const uint64_t needed = uint64_t{record_prefix_size} + length + record_checksum_size;
    if (needed > left) {
        return r::failure(at(start, "truncated record: its length says " + std::to_string(needed) +
                                        " bytes with prefix and checksum, but the file has " + std::to_string(left) +
                                        " left"));
    }
    storage_.resize((needed + 7) / 8);
    auto* bytes = reinterpret_cast<uint8_t*>(storage_.data());
    std::memcpy(bytes, head, sizeof head);
    if (std::fread(bytes + sizeof head, 1, needed - sizeof head, file_.get()) != needed - sizeof head) {
        return r::failure(at(start, "read failed: the file is shorter than when it was opened"));
    }
    const std::span<const uint8_t> frame(bytes, record_prefix_size + length);
    const uint32_t stored = world::load_le32(bytes + frame.size());
    const uint32_t computed = record_checksum(frame.subspan(record_prefix_size));
    if (stored != computed) {
        return r::failure(at(start, "checksum mismatch (stored " + hex32(stored) + ", computed " + hex32(computed) +
                                        "): the record's bytes are corrupted"));
    }
    auto decoded = decode_record(frame);
    if (!decoded) return r::failure(at(start, decoded.error));
    offset_ = start + needed;
    return decoded;
}

protocol::result<entry> reader::next() {
    using r = protocol::result<entry>;
    if (!file_) return r::failure(path_ + ": replay reader is not open");
    if (ended_) return r::failure(at(offset_, "read past the End record"));
    if (offset_ == size_) {
        return r::failure(at(offset_,
                             "the file ends without an End record: the recording was cut short "
                             "(the server stopped without finishing it) after tick " +
                                 std::to_string(next_tick_)));
    }
    const uint64_t start = offset_;
    auto rec = read_record();
    if (!rec) return r::failure(rec.error);
    return check_order(std::move(rec.value), start);
}

protocol::result<entry> reader::check_order(record rec, uint64_t start) {
    using r = protocol::result<entry>;
    if (std::holds_alternative<header>(rec))
        return r::failure(at(start, "unexpected record type Header after the header"));
    if (auto* t = std::get_if<match::tick_record>(&rec)) {
        if (t->tick != next_tick_) {
            return r::failure(at(start, "Tick record for tick " + std::to_string(t->tick) + " where tick " +
                                            std::to_string(next_tick_) + " was expected"));
        }
        if (t->joins.size() > max_joins_per_tick) {
            return r::failure(at(start, "Tick record for tick " + std::to_string(t->tick) + " has " +
                                            std::to_string(t->joins.size()) + " joins; a server admits at most " +
                                            std::to_string(max_joins_per_tick) + " players"));
        }
        ++next_tick_;
        return success_as<entry>(std::move(*t));
    }
    if (auto* c = std::get_if<hash_check>(&rec)) {
        if (c->tick != next_tick_) {
            return r::failure(at(start, "Hash record for tick " + std::to_string(c->tick) +
                                            " where the world is at tick " + std::to_string(next_tick_)));
        }
        return success_as<entry>(*c);
    }
    const end_marker e = std::get<end_marker>(rec);
    if (e.tick != next_tick_) {
        return r::failure(at(start, "End record for tick " + std::to_string(e.tick) + " where the world is at tick " +
                                        std::to_string(next_tick_)));
    }
    if (offset_ != size_) {
        return r::failure(at(offset_, std::to_string(size_ - offset_) + " bytes after the End record"));
    }
    ended_ = true;
    return success_as<entry>(e);
}

}  // namespace arena::replay
