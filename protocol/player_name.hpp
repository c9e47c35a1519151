#pragma once
// What a player's name may be. One rule for everyone who handles names: the server refuses a
// Hello whose name breaks it, and arena-token refuses to mint a token for such a name (a token
// the server would then refuse). A name reaches log lines, metric labels and other clients, so
// it must not be able to forge a line (newline), cut one short (NUL) or carry bytes that are
// not text (other control characters, invalid UTF-8).
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace arena::protocol {

// Longest name in bytes (UTF-8), the server's default game_config::max_name_bytes.
inline constexpr std::size_t max_player_name_bytes = 64;

// Why `name` is not a valid player name, as one line ("name has a control character at byte 5
// (0x0a)"), or nothing when it is valid: at most `max_bytes` bytes of well-formed UTF-8 (no
// overlong forms, surrogates or code points past U+10FFFF) without control characters (C0,
// which includes NUL and newline, DEL, and C1). The empty name is valid.
[[nodiscard]] std::optional<std::string> player_name_problem(std::string_view name,
                                                             std::size_t max_bytes = max_player_name_bytes);

// `text` as a log line, a metric label or another client may show it: every byte that is not
// part of well-formed UTF-8 without control characters is written as \xNN (a newline cannot
// forge a line, a NUL cannot cut one short), and at most `max_bytes` of the input are kept
// ("..." marks the cut). For text a client chose that is not refused outright (a Bye reason).
[[nodiscard]] std::string printable_text(std::string_view text, std::size_t max_bytes = 256);

}  // namespace arena::protocol
