#pragma once
// Constants of the wire contract that are not in arena.fbs (a schema cannot hold them).
#include <cstdint>

namespace arena::protocol {

// Hello.protocol_version must equal this; bump it only for a change old peers cannot read.
inline constexpr std::uint16_t protocol_version = 1;

// Every frame is a 4-byte little-endian body length, then the body (a FlatBuffer).
inline constexpr std::uint32_t frame_prefix_size = 4;

// Largest body a server accepts from a client (bytes). A real Hello or Input is < 200 bytes;
// the limit bounds what one connection can make the server buffer.
inline constexpr std::uint32_t max_client_frame_body = 64 * 1024;

// Largest body a client must accept from the server (bytes): a Welcome carries the whole
// world configuration and a Snapshot 32 bytes per body.
inline constexpr std::uint32_t max_server_frame_body = 16 * 1024 * 1024;

// No valid body is shorter: root offset (4) + file identifier (4).
inline constexpr std::uint32_t min_frame_body = 8;

// The FlatBuffers file identifier of every message, at body bytes 4..7.
inline constexpr char file_identifier[] = "ARNA";

}  // namespace arena::protocol
