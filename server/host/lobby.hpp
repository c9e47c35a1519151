#pragma once
// The lobby on --http-port: GET /modes lists the modes a client may ask for (name, capacity,
// preset, rules, duration); GET /matches lists the open, listed matches; GET /matches/{id}
// describes one (a private one too: its id is the invitation); POST /matches with
// {"mode": "...", "private": bool} creates one. JSON in and out. No sockets and no clock: the
// web transport hands each request in and writes the answer.
//
// Bounds: a request body of at most max_lobby_body_bytes; a source address may hold
// registry_options::max_matches_per_address matches it created that still run; the process
// holds max_matches in all (match_registry.hpp). With a token secret, creating needs a signed
// token (Authorization: Bearer TOKEN).
#include <cstddef>
#include <string>
#include <string_view>

#include "server/host/match_registry.hpp"

namespace arena::host {

inline constexpr size_t max_lobby_body_bytes = 4096;

struct lobby_request {
    std::string method;         // "GET", "HEAD", "POST"
    std::string path;           // "/matches" or "/matches/{id}", without the query
    std::string body;           // POST's
    std::string address;        // the client's, without its port: creations are bounded by it
    std::string authorization;  // the Authorization header ("Bearer TOKEN"), "" when absent
};

struct lobby_answer {
    unsigned status = 200;
    std::string body;  // JSON, or one line of text for an error
    std::string content_type = "application/json";
};

// Whether `path` is the lobby's ("/modes", "/matches", "/matches/...").
bool is_lobby_path(std::string_view path);

// `check_token` is the server's (unset: an open server, where anyone may create).
lobby_answer answer_lobby(match_registry& matches, const lobby_request& request, const match::token_check& check_token);

}  // namespace arena::host
