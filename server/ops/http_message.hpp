#pragma once
// The client side of the little HTTP the ops code speaks, as pure functions over text: format
// a POST for the Agones sidecar, read a response's status.
#include <cstdint>
#include <string>
#include <string_view>

namespace arena::ops {

// The status code of "HTTP/1.x NNN ...", or 0 when the text does not start like that.
int parse_response_status(std::string_view response);

// "HTTP/1.1 POST" request with a JSON body, for the Agones sidecar.
std::string format_post(std::string_view host, uint16_t port, std::string_view path, std::string_view json_body);

}  // namespace arena::ops
